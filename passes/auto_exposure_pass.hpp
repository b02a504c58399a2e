#pragma once
// Auto exposure (--auto-exposure): a 128-bin histogram of the HDR buffer's log2 luminance, then the
// mean of its middle part (the darkest 40% and brightest 5% of pixels left out) put on middle grey.
// Writes a 1x1 R32F "exposure" (EV) that the tone map adds to --exposure, which becomes the
// compensation. Instant: every frame is exposed for itself (no adaptation over time).
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

// The same computation on the CPU, in double, over pixel luminances (the tests' reference).
double autoExposureEvReference(const std::vector<float>& luminances);

}  // namespace lp
