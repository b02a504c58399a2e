#pragma once
// One depth-only raster pass per shadow-casting directional light ("shadow_map_<i>",
// i = the light's index in the scene). Each creates a D32F atlas "shadow_map_<i>.depth" holding its
// cascades as square tiles (see engine/render/shadows.hpp), drawn with slope-scaled depth bias.
// Each cascade draws only the caster clusters that can reach its tile (--shadow-culling, counts in
// 'lightpass graph --explain'), conservatively grown, plain, or by the compute rasteriser
// (--shadow-raster compute: shadow_raster.comp writes an R32UI image private to this pass, which a
// full-atlas draw turns into the D32F atlas; triangles whose window box exceeds
// kComputeRasterMaxTexels in x or y are drawn by the hardware plain path after it), or auto: the
// fastest of the four on this GPU, measured once on the first frame and cached per GPU.
// Conservative and split grow casters by GL_NV_conservative_raster where the GPU has it (and
// GL_NV_fragment_shader_barycentric), else by a geometry shader (--shadow-conservative).
// No shadow-casting light, or shadows switched off: no pass at all.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/render/shadows.hpp"

namespace lp {

constexpr float kComputeRasterMaxTexels = 64.0f;

// Whether this GPU can grow shadow casters in hardware: GL_NV_conservative_raster for the coverage and
// GL_NV_fragment_shader_barycentric for the triangle's vertices in the fragment shader (its depth
// plane and range). `reason` says what is missing when `hardware` is false.
struct ConservativeRasterSupport {
    bool hardware = false;
    std::string reason;
};
ConservativeRasterSupport queryConservativeRasterSupport();  // needs a current context
// Whether --shadow-conservative `setting` takes the hardware path on a GPU with `support` (auto and
// hardware do where it exists; hardware without it falls back to the geometry shader with a warning).
bool usesHardwareConservative(ShadowSettings::ConservativeRaster setting, const ConservativeRasterSupport& support);
const char* conservativeRasterLabel(bool hardware);  // "hardware" / "geometry shader"

struct ShadowMapPass {
    gl::Program program;       // conservative casters (shadow_depth.geom)
    // Hardware conservative casters (GL_CONSERVATIVE_RASTERIZATION_NV, no geometry shader): the faces
    // towards the light (conservative only) and the faces away from it (conservative and split).
    gl::Program hardwareTowardProgram;
    gl::Program hardwareAwayProgram;
    std::optional<ConservativeRasterSupport> conservativeSupport;  // asked of the GPU on the first frame
    bool hardwareConservative = false;  // this frame's conservative raster (set when its passes are added)
    bool warnedNoHardware = false;
    gl::Program plainProgram;  // --shadow-raster plain, and split's faces towards the light
    gl::Program awayProgram;   // --shadow-raster split: conservative, faces away from the light only
    gl::Framebuffer fbo;
    // --shadow-raster compute
    gl::Program rasterProgram;   // shadow_raster.comp
    gl::Program resolveProgram;  // R32UI bits -> D32F atlas
    gl::Program largeProgram;    // the large triangles, plainly
    gl::VertexArray emptyVao;
    gl::Texture depthBits;       // R32UI, the atlas's size
    gl::Buffer largeVertices;    // clip-space vertices of the large triangles, one region per cascade
    size_t largeCapacity = 0;    // vertices
    gl::Buffer largeDraws;       // one DrawArraysIndirectCommand per cascade
    // --shadow-raster auto: resolved on the first frame drawn (from the cache, or measured)
    bool autoResolved = false;
    ShadowSettings::Raster autoRaster = ShadowSettings::Raster::Conservative;
    std::string autoReport;  // the line logged: the choice, the measured times or "cached", the file
};

// --shadow-raster auto's cache: one line per GPU, "<raster>\t<GL_VENDOR / GL_RENDERER / GL_VERSION>",
// in $LIGHTPASS_CACHE_DIR/shadow_raster.txt, else $XDG_CACHE_HOME/lightpass/, else ~/.cache/lightpass/.
std::string shadowRasterCacheKey();
std::filesystem::path shadowRasterCachePath();

struct LightShadowMap {
    int light = -1;          // index into scene.directionalLights
    fg::ResourceId depth;    // the atlas
    ShadowFrustum frustum;   // cascades, matrices, tile layout
};
using ShadowMaps = std::vector<LightShadowMap>;

ShadowMaps addShadowMapPasses(fg::FrameGraph& graph, ShadowMapPass& state, const FrameData& frame);

// Draws every mesh of the frame's scene with `prog` (bound), its uniform `locMvp` set to
// worldToClip x model: the caster loop the sun cascades and the spot shadow maps share.
void drawShadowCasters(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip);

// Draws one cascade's culled caster list (engine/render/shadow_casters.hpp) the same way.
void drawCasterList(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip, const CasterList& casters);

}  // namespace lp
