#pragma once
// Screen-space ambient occlusion (GTAO, Jimenez et al. 2016) over the G-buffer's depth and normals:
// "ao" integrates the cosine-weighted visible horizon along a few screen slices into a raw RG16F
// target (AO, eye depth) at full or half size; "ao_denoise" filters it with a depth-aware 4x4 box
// (upsampling from half size) into the full-size R8 "ao" target. global_lights multiplies the
// constant ambient by it, ibl the diffuse IBL, and the IBL specular by the specular occlusion derived
// from it; the suns and local lights never see it. Settings: RenderSettings::ao.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct AmbientOcclusionPass {
    gl::Program gtao, denoise;
    GBufferProgramKey gtaoLayout, denoiseLayout;  // the G-buffer layouts the programs were compiled for
};

// Texture unit the light passes sample the AO target on (LP_BIND_AO in their shaders).
inline constexpr unsigned kAoTextureUnit = 14;

// The raw target's size: the G-buffer's, or half of it rounded up.
glm::ivec2 aoRawSize(const FrameData& frame);

// Adds "ao" and "ao_denoise"; returns the full-size R8 AO target (1 = unoccluded, sky 1).
fg::ResourceId addAmbientOcclusionPasses(fg::FrameGraph& graph, AmbientOcclusionPass& state, const FrameData& frame,
                                         const GBuffer& gbuffer);

}  // namespace lp
