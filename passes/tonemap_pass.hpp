#pragma once
// HDR -> display: exposure, the tone map of EnvironmentSettings::toneMap (default the seeds'
// pow(c / (c + 1), 1.2) per channel), sRGB encoding, into RGBA8 at the output size (its input has
// that size: at render scale < 1 the upscale pass comes first).
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct ToneMapPass {
    gl::Program program;
};

// `autoExposure`: the auto_exposure pass's 1x1 EV, added to settings.exposureEV; invalid: manual.
fg::ResourceId addToneMapPass(fg::FrameGraph& graph, ToneMapPass& state, const FrameData& frame, fg::ResourceId hdr,
                              fg::ResourceId autoExposure = {});

}  // namespace lp
