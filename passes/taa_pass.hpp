#pragma once
// --aa taa: temporal anti-aliasing ("taa"). Each frame is rendered with a Halton(2,3) sub-pixel jitter
// (taaJitterPixels, 16 phases; FrameData::jitterPixels shifts the projection) and this pass blends
// it, at the output size before the tone map, with the history: last frame's result reprojected
// through gbuffer.velocity, its colour clipped to the variance box of the current 3x3 neighbourhood
// in YCoCg (Salvi 2016, Karis 2014), and rejected where the motion stored with it disagrees with the
// pixel's (a disocclusion, the background a moving object uncovered). The blend gives the current
// frame --taa-history-weight of the weight (luma-weighted against flicker). The history (colour
// RGBA16F and velocity RG16F, two of each, ping-ponged) outlives frames in TaaPass and is imported
// into each frame's graph, as EnvironmentCache's textures are; it is reset (the frame shown as it is)
// on the first frame, a resize, a camera cut (FrameData::hasPrevious false) and any setting change.
// Shader: shaders/taa.comp, math in common/taa.glsl.
#include <string>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct TaaPass {
    gl::Program program;
    gl::Texture color[2], velocity[2];
    glm::ivec2 size{0};
    int latest = -1;        // which of the pair holds the last resolved frame; -1: none
    std::string signature;  // the settings that frame was rendered with (taaSettingsSignature)
};

// Sub-pixel jitter of TAA frame `index` in output pixels, in [-0.5, 0.5)^2: Halton bases 2 and 3,
// 16 phases (index 1..16 of the sequence, so the first is not the pixel centre).
glm::vec2 taaJitterPixels(uint64_t index);
double halton(uint64_t index, uint32_t base);

// Whether `state`'s history can be used by `frame` rendered with settings signature `signature`.
bool taaHistoryUsable(const TaaPass& state, const FrameData& frame, const std::string& signature);

// Reads `hdr` (output size, jittered) and `velocity` (render size); returns the resolved HDR image.
fg::ResourceId addTaaPass(fg::FrameGraph& graph, TaaPass& state, const FrameData& frame, fg::ResourceId hdr,
                          fg::ResourceId velocity, const std::string& signature);

}  // namespace lp
