#pragma once
// Motion blur on the HDR buffer, before bloom and the tone map (McGuire et al. 2012, "A Reconstruction
// Filter for Plausible Motion Blur"; shaders/common/motion_blur.glsl): three compute passes,
// motion_blur_tiles (longest half blur vector per K x K tile), motion_blur_neighbors (over 3 x 3
// tiles) and motion_blur (the gather), reading gbuffer.velocity and gbuffer.depth.
#include <string>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct MotionBlurPass {
    gl::Program tiles, neighbors, gather;
};

// K: the tile size and the longest half blur in pixels, from the render height (20 px at 720 lines,
// 30 at 1080, 60 at 2160; at least 8).
int motionBlurTileSize(int renderHeight);

// Why the frame gets no motion blur (off, nothing moves), or empty when it does.
std::string motionBlurSkipReason(const FrameData& frame);

// The blurred HDR buffer: a new version of `hdr` (the gather reads a copy, motion_blur.source).
fg::ResourceId addMotionBlurPasses(fg::FrameGraph& graph, MotionBlurPass& state, const FrameData& frame,
                                   const GBuffer& gbuffer, fg::ResourceId hdr);

}  // namespace lp
