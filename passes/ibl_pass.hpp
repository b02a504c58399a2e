#pragma once
// Image-based lighting: adds the environment's diffuse (SH or irradiance cube) and specular
// (prefiltered GGX chain x split-sum DFG) light into the HDR buffer, when
// EnvironmentSettings::ibl is on and the scene has an environment map. "ibl_bake" makes the
// environment's textures in the frame where they change.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/ibl_environment.hpp"
#include "passes/ambient_occlusion_pass.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct IblPass {
    gl::Program program;
    GBufferProgramKey layout;  // the G-buffer layout `program` was compiled for
};

// The environment's textures in this frame's graph: imported from frame.environments (the cache
// outlives frames), written by ibl_bake in the frame where they are made. irradiance, prefiltered
// and dfg are valid only when imported with `bake`.
struct EnvironmentTextures {
    fg::ResourceId cube, irradiance, prefiltered, dfg;
};

bool isEnvironmentView(DebugView view);

EnvironmentTextures importEnvironment(fg::FrameGraph& graph, const FrameData& frame, bool bake);

// "ibl_bake": makes the environment cube and, if `bake`, its irradiance / prefiltered cubes and the
// DFG LUT. The frame builder adds it only in a frame where the cache lacks them (the environment or
// the bake settings changed); it writes the imported textures, so the passes reading them follow it.
EnvironmentTextures addIblBakePass(fg::FrameGraph& graph, const FrameData& frame, const EnvironmentTextures& in,
                                   bool bake);

// `ao`: the ambient-occlusion target: the diffuse IBL is multiplied by it and the specular by the
// specular occlusion derived from it (common/ambient_occlusion.glsl); invalid: no occlusion.
// The environment's uniforms of common/ibl_shading.glsl on `prog` (SH, eye-to-world, intensity,
// prefiltered levels) from the baked environment `env`.
void setIblUniforms(GLuint prog, const FrameData& frame, const BakedEnvironment& env);

fg::ResourceId addIblPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, const GBuffer& gbuffer,
                          const EnvironmentTextures& environment, fg::ResourceId hdr, bool lightingOnly,
                          fg::ResourceId ao = {});

}  // namespace lp
