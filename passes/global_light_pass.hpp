#pragma once

// Global (directional) lights with the chosen analytic BRDF (normalised Blinn-Phong or GGX), their
// cascaded shadow maps, plus a constant ambient, as one compute pass over the G-buffer. Creates the
// HDR buffer (RGBA16F) that later light passes add into.
#include <string>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/ambient_occlusion_pass.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/shadow_map_pass.hpp"

namespace lp {

struct GlobalLightPass {
    gl::Program program;
    GBufferProgramKey layout;  // the G-buffer layout `program` was compiled for
    int shadowFilter = -1;   // and the shadow filter (sunShadowFilterDefine)
};

// `shadowMaps`: this frame's maps (addShadowMapPasses); lights without one are unshadowed.
// `lightingOnly` (the lighting debug view) lights a white albedo and does not read the diffuse target.
// `ao`: the ambient-occlusion target (passes/ambient_occlusion_pass), which darkens the constant
// ambient only; invalid: no occlusion.
fg::ResourceId addGlobalLightPass(fg::FrameGraph& graph, GlobalLightPass& state, const FrameData& frame,
                                  const GBuffer& gbuffer, const ShadowMaps& shadowMaps, bool lightingOnly,
                                  fg::ResourceId ao = {});

// The suns' uniforms of common/sun_light.glsl on `prog` (directions, irradiance, ambient, BRDF,
// cascades); returns the number of suns drawn. The caller binds the shadow atlases of `shadowMaps`
// to the program's LP_SUN_SHADOW_UNIT + slot.
int setSunUniforms(GLuint prog, const FrameData& frame, const ShadowMaps& shadowMaps);

// The define that compiles common/sun_light.glsl's shadows for the settings' filter alone (a program
// choosing it by uniform pays the costliest filter's registers: 10-25% slower with `--pcf off`).
// Programs keep the filter they were compiled for and are rebuilt when it changes.
std::string sunShadowFilterDefine(const FrameData& frame);

}  // namespace lp
