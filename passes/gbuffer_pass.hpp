#pragma once
// G-buffer: rasterises every mesh once into the layout settings.gbuffer chooses (normal format,
// position stored or rebuilt from standard / reversed-Z depth; see shaders/common/gbuffer_layout.glsl).
// Writes only the channels some pass will read. Passes that read it use readGBuffer / bindGBuffer
// and compile their programs with gbufferDefines() through programForLayout.
#include "engine/gl/handles.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/scene_gpu.hpp"

namespace lp {

struct GBufferChannels {
    bool position = true;  // only when the position mode stores positions
    bool texcoord = false;
    bool tangent = false;  // only for the tangent view
    // gbuffer.velocity (RG16F, uv_current - uv_previous; engine/render/motion.hpp): only when a pass
    // reads motion (the velocity view, motion blur, temporal AA).
    bool velocity = false;
    // gbuffer.material_input (RGBA16F): the input a material-input view shows (base-color, metallic,
    // roughness, occlusion), only in those views.
    bool materialInput = false;
    // gbuffer.fresnel (RG16F: Schlick's f90 and the diffuse layer's Fresnel shape): only when a material
    // of the scene gives its f90 (KHR_materials_specular; gbufferCarriesFresnel), never beside
    // materialInput, whose colour location and image unit it takes.
    bool fresnel = false;
    // gbuffer.clearcoat (RGBA16 unorm: KHR_materials_clearcoat's weight, sqrt alpha, octahedral normal): only
    // when an opaque material of the scene has a coat (gbufferCarriesClearcoat), never beside texcoord,
    // whose colour location and image unit (4) it takes.
    bool clearcoat = false;
};

struct GBuffer {
    fg::ResourceId depth, normal, diffuse, position, specular, texcoord, tangent;  // position invalid when rebuilt
    fg::ResourceId velocity;  // invalid unless GBufferChannels::velocity
    fg::ResourceId materialInput;  // invalid unless GBufferChannels::materialInput
    fg::ResourceId fresnel;        // invalid unless GBufferChannels::fresnel
    fg::ResourceId clearcoat;      // invalid unless GBufferChannels::clearcoat
};

// What a program that reads or draws the G-buffer was compiled for: the layout, whether the scene's
// meshes carry vertex colours (LP_VERTEX_COLOR; without them the mesh-drawing programs neither
// fetch nor interpolate a colour: on the H100 that varying cost the gallery's classic G-buffer 0.18 ms
// at 1080p, 8%) and whether a material samples the second uv set (LP_SECOND_UV, likewise).
struct GBufferProgramKey {
    GBufferSettings layout;
    bool vertexColors = false;
    bool secondUvSet = false;
    bool fresnel = false;  // gbufferCarriesFresnel: LP_GBUFFER_FRESNEL
    bool clearcoat = false;  // gbufferCarriesClearcoat: LP_GBUFFER_CLEARCOAT
    bool operator==(const GBufferProgramKey& o) const {
        return layout == o.layout && vertexColors == o.vertexColors && secondUvSet == o.secondUvSet &&
               fresnel == o.fresnel && clearcoat == o.clearcoat;
    }
    bool operator!=(const GBufferProgramKey& o) const { return !(*this == o); }
};

struct GBufferPass {
    gl::Program program;
    GBufferProgramKey layout;  // what `program` was compiled for
    gl::Program velocityProgram;  // the same with LP_GBUFFER_VELOCITY: also writes motion vectors
    GBufferProgramKey velocityLayout;
    gl::Program depthOnlyProgram;  // LP_GBUFFER_DEPTH_ONLY: no material channel is read (forward+'s pre-pass)
    GBufferProgramKey depthOnlyLayout;
    gl::Program depthOnlyVelocityProgram;
    GBufferProgramKey depthOnlyVelocityLayout;
    gl::Program background;  // gbuffer_background.comp: what the pixels no mesh covers hold
    GBufferProgramKey backgroundLayout;
    gl::Framebuffer fbo;
};

// "gbuffer": the opaque draws (alpha-blended ones are the transparent pass's) into the targets read.
GBuffer addGBufferPass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels);
// "depth_prepass": forward+'s depth pre-pass, the same raster under another name. With no material
// channel read it runs gbuffer.frag's depth-only variant (depth, and motion when read); a pass that
// reads a channel (ambient occlusion: depth and normals; a channel view) makes it write that channel.
GBuffer addDepthPrepass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels);

// The texture units of KHR_materials_specular's maps (common/material.glsl's LP_MATERIAL_BIND_SPECULAR*):
// above the 0..15 the light passes and the forward passes' lighting use.
constexpr GLuint kMaterialSpecularUnit = 16, kMaterialSpecularColorUnit = 17;
// KHR_materials_clearcoat's three maps (LP_MATERIAL_BIND_CLEARCOAT*): factor, roughness, normal.
constexpr GLuint kMaterialClearcoatUnit = 18, kMaterialClearcoatRoughnessUnit = 19, kMaterialClearcoatNormalUnit = 20;
// Unbinds the material's texture units (0..4, the specular maps' and the clearcoat maps').
void unbindMaterialTextures();

// The material uniforms of common/material_uniforms.glsl in a program (the G-buffer raster, the
// forward passes): their locations, looked up once per program.
struct GpuMaterial;
struct MaterialUniforms {
    explicit MaterialUniforms(const gl::Uniforms& u);  // the program's, looked up (and checked) once
    void set(GLuint prog, const GpuMaterial& m) const;  // also binds the material's textures (units 0..4, 16, 17)
    GLint kd, opacity, ks, metallic, shininess, roughness, hasDiffuse, hasBump, bumpScale, hasNormal, normalScale,
        hasMetalRough, hasOcclusion, occlusionStrength, mask, cutoff, twoSided, flat, secondUvMaps, specularF90,
        specularF90Given, hasSpecularMap, hasSpecularColorMap, clearcoat, clearcoatRoughness, clearcoatNormalScale,
        hasClearcoatMap, hasClearcoatRoughnessMap, hasClearcoatNormalMap;
};

// common/brdf.glsl's uBrdf, uSpecularMasking and uHiddenTerms (the term views: lp::hiddenShadingTerms)
// from the settings, on every program that evaluates the BRDF or stores a material for it (the
// G-buffer's diffuse colour depends on the BRDF: materialDiffuseAlbedo).
void setBrdfUniforms(GLuint prog, const FrameData& frame);
// common/material.glsl's uMaterialInput (lp::materialInputShown), on the programs that read materials
// (the G-buffer, the visibility resolve, the forward passes).
void setMaterialInputUniform(GLuint prog, const FrameData& frame);

// GL internal formats of the targets under a layout (docs/gbuffer.md). The colours that hold a
// material's base colour in 8 bits are sRGB-encoded, as the textures they come from: kd in diffuse in
// every layout, and F0 in the seed formats' specular (the others keep F0 in RGBA16F). Writers encode
// in GLSL through an RGBA8 view of the target, the raster (gbuffer.frag) and compute stores
// (shaders/common/gbuffer_images.glsl) alike, so both round exactly; texel fetches decode.
constexpr GLenum kGBufferDiffuseFormat = GL_SRGB8_ALPHA8;
// The texture unit bindGBuffer gives gbuffer.fresnel: common/gbuffer_layout.glsl's LP_BIND_FRESNEL.
constexpr GLuint kGBufferFresnelUnit = 15;
// The texture unit bindGBuffer gives gbuffer.clearcoat: common/gbuffer_layout.glsl's LP_BIND_CLEARCOAT.
constexpr GLuint kGBufferClearcoatUnit = 21;
GLenum gbufferNormalFormat(GBufferNormalFormat format);
GLenum gbufferSpecularFormat(GBufferNormalFormat format);

// The projection the G-buffer's depth was written with: frame.projection, or for reversed-Z the
// same frustum mapping near to 1 and far to 0 (with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)).
glm::mat4 gbufferDepthProjection(const FrameData& frame);

// For passes that raster against the G-buffer depth (light globes): sets the clip control and
// depth function matching the depth convention (GL_LESS or, reversed-Z, GL_GREATER); the caller's
// gl::ScopedRasterState puts both back.
void setGBufferDepthTest(const GBufferSettings& layout);

// Declares reads of the targets the decode API needs (position only when stored; diffuse when asked;
// with `shading`, gbuffer.fresnel and gbuffer.clearcoat where the G-buffer carries them: the passes that
// shade, gbufferFresnel and gbufferClearcoat).
void readGBuffer(fg::PassBuilder& b, const GBuffer& g, bool diffuse = true, bool shading = false);
// Creates the colour targets (every one but depth) of a w x h G-buffer in `layout`, each only if some
// pass reads it and its channel is asked for, written with `how`: the classic pass's attachments and
// the visibility resolve's image stores are the same targets, names and formats.
GBuffer createGBufferColourTargets(fg::PassBuilder& b, int w, int h, const GBufferSettings& layout,
                                   GBufferChannels channels, fg::Usage how);
// The G-buffer's colour targets as images (shaders/common/gbuffer_images.glsl): the defines that give
// their image formats (added to `defines`, e.g. programForLayout's), binding the created ones to image
// units 0..7 (returns uTargets' bits) and unbinding them, and the uniforms of the background's motion.
void addGBufferImageDefines(std::vector<std::string>& defines, const GBufferSettings& layout);
GLuint bindGBufferImages(const fg::PassResources& res, const GBuffer& g);
void unbindGBufferImages();
void setBackgroundMotionUniforms(GLuint program, const FrameData& frame);
// Binds the targets to units LP_BIND_* and sets `program`'s uGbufferCamera; unbindGBuffer clears the units.
void bindGBuffer(GLuint program, const fg::PassResources& res, const GBuffer& g, const FrameData& frame,
                 bool diffuse = true, bool shading = false);
void unbindGBuffer();

// Whether the frame's G-buffer carries gbuffer.fresnel: an opaque material of the scene gives its f90
// (KHR_materials_specular), and the view is no material-input view (those light nothing, and their
// target takes the fresnel target's colour location and image unit). Without it every pass derives f90
// from F0, as for a scene without the extension, and pays nothing.
bool gbufferCarriesFresnel(const FrameData& frame);
// Whether it carries gbuffer.clearcoat: an opaque material of the scene has a coat
// (KHR_materials_clearcoat, Material::hasClearcoat), and the view is not the texcoords view (which
// lights nothing; its target takes the clearcoat target's colour location and image unit). Without
// it no pass reads or pays for a coat.
bool gbufferCarriesClearcoat(const FrameData& frame);
// What 'graph --explain' says under the G-buffer pass about gbuffer.clearcoat: written for how many
// coated materials, or why not (no opaque material has a coat; the texcoords view).
std::string gbufferClearcoatNote(const FrameData& frame);

// `program`, compiled by compile(defines) for the frame's G-buffer layout (and LP_VERTEX_COLOR where
// the scene has vertex colours, LP_SECOND_UV where it samples TEXCOORD_1, LP_GBUFFER_FRESNEL where the
// G-buffer carries gbuffer.fresnel); compiled again when any
// changed since (lightpass sweep changes the layout within one process, the viewer the scene).
template <class Compile>
const gl::Program& programForLayout(gl::Program& program, GBufferProgramKey& builtFor, const FrameData& frame,
                                    Compile compile) {
    const GBufferProgramKey key{frame.settings->gbuffer, frame.gpu != nullptr && frame.gpu->vertexColors,
                                frame.gpu != nullptr && frame.gpu->secondUvSet, gbufferCarriesFresnel(frame),
                                gbufferCarriesClearcoat(frame)};
    if (!program || builtFor != key) {
        std::vector<std::string> defines = gbufferDefines(key.layout);
        if (key.vertexColors) defines.push_back("LP_VERTEX_COLOR");
        if (key.secondUvSet) defines.push_back("LP_SECOND_UV");
        if (key.fresnel) defines.push_back("LP_GBUFFER_FRESNEL");
        if (key.clearcoat) defines.push_back("LP_GBUFFER_CLEARCOAT");
        program = compile(defines);
        builtFor = key;
    }
    return program;
}

}  // namespace lp
