#pragma once
// Screen-space ambient occlusion (GTAO, Jimenez et al. 2016) over the G-buffer's depth and normals, at
// full or half size ("raw" texels): "ao_depth" copies the eye depth to a compact R32F target the
// horizon search reads; "ao" integrates the cosine-weighted visible horizon along a few screen slices
// per texel (rotated and offset per texel by an 8x8 pattern) into an R16F target; "ao_blur" averages
// one period of the pattern along x and "ao_denoise" along y, each weighting taps by their distance
// from the centre's tangent plane, the latter upsampling into the full-size R8 "ao" target.
// global_lights multiplies the constant ambient by it, ibl the diffuse IBL, and the IBL specular by
// the specular occlusion derived from it; the suns and local lights never see it.
// Settings: RenderSettings::ao.
#include <array>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct AmbientOcclusionPass {
    gl::Program depth, gtao, blur, denoise;
    // the G-buffer layouts the programs were compiled for
    GBufferProgramKey depthLayout, gtaoLayout, blurLayout, denoiseLayout;
};

// The passes addAmbientOcclusionPasses adds, in order (the frame builder skips them all together).
const std::array<const char*, 4>& ambientOcclusionPassNames();

// Texture unit the light passes sample the AO target on (LP_BIND_AO in their shaders).
inline constexpr unsigned kAoTextureUnit = 14;

// The raw target's size: the G-buffer's, or half of it rounded up.
glm::ivec2 aoRawSize(const FrameData& frame);

// Adds the passes; returns the full-size R8 AO target (1 = unoccluded, sky 1).
fg::ResourceId addAmbientOcclusionPasses(fg::FrameGraph& graph, AmbientOcclusionPass& state, const FrameData& frame,
                                         const GBuffer& gbuffer);

}  // namespace lp
