#pragma once
// Forward shading. "forward_opaque" is forward+'s one lighting pass (--render-path forward+): after
// the depth pre-pass (addDepthPrepass) it draws every opaque surface again with depth test EQUAL and
// shades each fragment in shaders/forward.frag from the suns and their shadows, the ambient and IBL
// (times the ambient occlusion), the local lights listed in the fragment's froxel (the clustered
// method's grid of whole froxels, built once a frame by the first pass that binds it through
// bindClusteredLightLists) and its emission, writing the HDR
// buffer directly. The lighting helpers here also serve the transparent pass (passes/transparent_pass).
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/ibl_pass.hpp"
#include "passes/local_light_pass.hpp"
#include "passes/shadow_map_pass.hpp"
#include "passes/spot_shadow_pass.hpp"

namespace lp {

struct ForwardPass {
    gl::Program program;
    bool spotShadowVariant = false;  // `program` compiled with LP_SPOT_SHADOWS
    bool pointShadowVariant = false; // and with LP_POINT_SHADOWS
    int shadowFilter = -1;           // and for this sun shadow filter (sunShadowFilterDefine)
    bool vertexColors = false;       // and with LP_VERTEX_COLOR (the scene has vertex colours)
    bool secondUvSet = false;        // and with LP_SECOND_UV (a material samples TEXCOORD_1)
    bool transmissionVariant = false;  // the transparent pass's: with LP_FORWARD_TRANSMISSION
    gl::Framebuffer fbo;
};

// What lights a forward-shaded surface this frame (invalid ids: that input is absent).
struct ForwardLighting {
    ShadowMaps shadowMaps;            // the suns' cascades (addShadowMapPasses)
    EnvironmentTextures environment;  // irradiance, prefiltered, dfg valid: IBL on
    fg::ResourceId ao;                // the ambient-occlusion target (opaque surfaces only)
    bool localLights = false;         // the frame has local lights in view
    LocalShadowMaps localShadows;     // with localLights: the spot shadow atlas and the point shadow cubes
    LocalLightRecords lightRecords;   // with localLights: the frame's light records
    bool fillsLightRecords = false;   // the pass uploads them (forward_opaque); else it reads them
    bool lightingOnly = false;        // the lighting view
};

// The ids a pass using ForwardLighting got from its reads (declareForwardLighting), for execute.
struct ForwardLightingReads {
    std::vector<fg::ResourceId> shadowMaps;
    fg::ResourceId irradiance, prefiltered, dfg, ao, spotAtlas, pointAtlas;
};

// Declares the reads of `lighting`'s textures (sampled) and of its light records (or, with
// fillsLightRecords, their upload).
ForwardLightingReads declareForwardLighting(fg::PassBuilder& b, LocalLightPass& localLights, const ForwardLighting& lighting);

// Compiles `program` (shaders/gbuffer.vert + forward.frag with `defines`, and LP_SPOT_SHADOWS when a spot
// casts a shadow, LP_POINT_SHADOWS when a point light does) if needed, sets every lighting uniform, binds the textures and builds and binds the
// clustered light lists; unbindForwardLighting undoes the bindings.
void bindForwardLighting(ForwardPass& state, LocalLightPass& localLights, const FrameData& frame,
                         const ForwardLighting& lighting, const ForwardLightingReads& reads,
                         const fg::PassResources& res, const std::vector<std::string>& defines);
void unbindForwardLighting();

// Material uniforms of common/material.glsl and forward.frag's emission, looked up once per program.
struct ForwardMaterialUniforms {
    explicit ForwardMaterialUniforms(const gl::Uniforms& u);
    void set(GLuint prog, const GpuMaterial& m) const;  // also binds the material's textures (units 0..4, 6)
    // uModelView and uNormalMatrix of a mesh drawn with `view`.
    void setModel(GLuint prog, const glm::mat4& view, const glm::mat4& model) const;
    MaterialUniforms material;  // the G-buffer's (passes/gbuffer_pass)
    GLint emission, hasEmissive, modelView, normalMatrix;
};
// After a forward pass's draws: unbinds the material textures and bindForwardLighting's bindings, and
// detaches the pass's targets from `fbo`.
void finishForwardDraws(GLuint fbo);

// Adds "forward_opaque": creates the HDR buffer (cleared to 0: the background is the sky pass's) and
// shades the opaque draws where their depth equals `depthPrepass.depth`.
fg::ResourceId addForwardOpaquePass(fg::FrameGraph& graph, ForwardPass& state, LocalLightPass& localLights,
                                    const FrameData& frame, const GBuffer& depthPrepass, const ForwardLighting& lighting);

}  // namespace lp
