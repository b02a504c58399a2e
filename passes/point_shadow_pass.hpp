#pragma once
// "point_shadows": one depth-only raster pass drawing a cube shadow map for every local point light
// (no spot cone) with castsShadow (up to kMaxPointShadows, the first ones): six perspective faces,
// one row of six square tiles of one D32F atlas "point_shadows.depth" per light. The local-light
// passes pick a pixel's face by the direction from the light (the face whose clip w, the distance
// along its axis, is largest) and filter it like a spot's map (PCF, settings.shadows.filter, the
// same normal, constant and slope bias). Each face's frustum is a little wider than 90 degrees, so
// its 45-degree edge lies kPointShadowFaceMargin texels inside the tile and PCF taps near a cube
// edge still read depth of their own face. Casters: the clusters whose bounds reach the light's
// range sphere (nothing outside it can come between the light and a point it lights), opaque ones
// plainly, MASK and BLEND ones alpha-tested as the spots' and suns'.
//
// --shadow-cache on (the default): the atlas is kept across frames and a light's row is redrawn
// only when its key changed (PointShadowKey: the light's position and range bit for bit, the tile
// size, the slope bias, and the signature of the casters within its range: the scene on the GPU and
// each such cluster's model matrix, buffers, pose (an animated mesh's poseVersion) and alpha
// inputs). A kept row is exactly what a redraw would write. --explain notes per light "redrawn
// (why)" or "kept". --shadow-cache off: a transient atlas, every row drawn every frame.
// No shadow-casting point light in the frame, or shadows off: no pass.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

constexpr int kMaxPointShadows = 8;
constexpr int kPointShadowFaces = 6;  // +X, -X, +Y, -Y, +Z, -Z
// Texels between a face's 45-degree edge and its tile's edge: at least the farthest PCF tap (the
// Poisson disc's 3.6 texels) stays on the face's own depth.
constexpr int kPointShadowFaceMargin = 4;
constexpr int kPointShadowAtlasMaxSide = 8192;  // texels: six faces wide, one row per light

// The tangent of a cube face's half-angle for faces of `tileSize` texels: its 45-degree edge lies
// kPointShadowFaceMargin texels inside the tile.
float pointShadowFaceTan(int tileSize);
// Face tile size for `lights` shadowed point lights under shadow size `shadowSize` (--shadow-size):
// the spot tiles' half of it, at least 64, at most what keeps the atlas within kPointShadowAtlasMaxSide.
int pointShadowTileSize(int shadowSize, int lights);
// World-to-clip of the six faces of a cube at `position`, depth from nearPlane to farPlane, each of
// half-angle tangent `faceTan`. Face f looks along axis f / 2 (+ for even f, - for odd).
std::array<glm::mat4, kPointShadowFaces> pointShadowFaceMatrices(glm::vec3 position, float nearPlane, float farPlane,
                                                                 float faceTan);
// The face whose clip w (distance along its axis) is largest for the world direction `d` from the
// light: its major axis, as the shaders pick it.
int pointShadowFace(glm::vec3 d);

// What one light's row of the atlas holds: equal keys give bit-identical depth.
struct PointShadowKey {
    glm::vec3 position{0.0f};
    float range = 0.0f;
    int tileSize = 0;
    float slopeBias = 0.0f;
    uint64_t casters = 0;  // pointShadowCasterSignature
    bool operator==(const PointShadowKey& o) const;
};

// A hash of what can cast into the cube of a light at `position` reaching `range`: the SceneGpu, and
// per caster cluster within the range sphere its model's matrix, buffers and pose version, its index
// range and alpha kind, and its material's alpha inputs.
uint64_t pointShadowCasterSignature(const FrameData& frame, glm::vec3 position, float range);

// Rows of point-shadow cubes drawn and kept (--shadow-cache) since the counters were reset.
struct PointShadowStats {
    uint64_t drawn = 0, kept = 0;
};

struct PointShadowPass {
    gl::Program program;       // opaque casters
    gl::Program alphaProgram;  // MASK and BLEND casters (LP_SHADOW_ALPHA_TEST), made when the scene has some
    gl::Framebuffer fbo;
    // --shadow-cache on: the kept atlas and what each row holds (none: not drawn yet)
    gl::Texture atlas;
    int width = 0, height = 0;
    std::vector<std::optional<PointShadowKey>> rows;
    PointShadowStats stats;
    size_t cacheBytes() const { return atlas ? size_t(width) * size_t(height) * sizeof(float) : 0; }  // the kept atlas
};

struct PointShadowMaps {
    fg::ResourceId depth;  // the atlas; invalid when no point light casts a shadow this frame
    std::vector<int> light;  // per cube (atlas row): the index into localLightsForFrame's lights
    std::vector<std::array<glm::mat4, kPointShadowFaces>> worldToClip;  // per cube, per face
    std::vector<float> nearPlane, farPlane;  // per cube: its depth range (metres along a face's axis)
    float texelSlope = 0.0f;  // a texel's world size per metre along a face's axis
    int tileSize = 0;
    bool any() const { return !light.empty(); }
};

// Why the frame has no point_shadows pass ("": it has one); the frame builder records it.
std::string pointShadowSkipReason(const FrameData& frame);
// Adds the pass; with --shadow-cache off it first lets the kept atlas go, even on a frame without it.
PointShadowMaps addPointShadowPass(fg::FrameGraph& graph, PointShadowPass& state, const FrameData& frame);

}  // namespace lp
