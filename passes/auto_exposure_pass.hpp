#pragma once
// Auto exposure (on unless the scene sets a fixed "exposure"; --auto-exposure / --no-auto-exposure): a
// 128-bin histogram of the HDR buffer's log2 luminance, each pixel weighted by its distance from the
// centre, then the mean of the weights' middle part (the darkest 20% and brightest 30% left out) put
// on middle grey (shaders/common/exposure.glsl). Writes a 1x1 R32F "exposure" (EV) that the tone map
// and the HDR views add to --exposure, which becomes the compensation. Instant: every frame is exposed
// for itself (no adaptation over time).
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct AutoExposurePass {
    gl::Program histogram, average;
};

fg::ResourceId addAutoExposurePass(fg::FrameGraph& graph, AutoExposurePass& state, const FrameData& frame,
                                   fg::ResourceId hdr);

// The same computation on the CPU, in double, over a width x height image's pixel luminances (row
// by row, row 0 first; the tests' reference).
double autoExposureEvReference(const std::vector<float>& luminances, int width, int height);

}  // namespace lp
