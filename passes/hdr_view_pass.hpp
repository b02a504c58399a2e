#pragma once
// The HDR buffer inspected, in place of the tone map: "invalid-pixels" paints NaN (magenta) and Inf
// (cyan) texels over a dimmed image (Falcor's InvalidPixelDetection); "exposure-ev" shows each
// pixel's luminance in EV stops around middle grey as false colour (Filament's DisplayRange). Both
// read the HDR buffer the tone map would read (after post effects, at the output size).
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct HdrViewPass {
    gl::Program program;
};

bool isHdrView(DebugView view);

// A new RGBA8 image at the output size (pass "hdr_view"); `hdr` has that size (after the upscale).
// `autoExposure`: the auto_exposure pass's 1x1 EV (invalid: not metered), applied as the tone map does.
fg::ResourceId addHdrViewPass(fg::FrameGraph& graph, HdrViewPass& state, const FrameData& frame, fg::ResourceId hdr,
                              fg::ResourceId autoExposure, DebugView view);

}  // namespace lp
