#pragma once
// HDR -> display: exposure, the tone map of EnvironmentSettings::toneMap (default the seeds'
// pow(c / (c + 1), 1.2) per channel), sRGB encoding, into RGBA8 at the output size (its input has
// that size: at render scale < 1 the upscale pass comes first, with --aa ssaa the downsample pass).
// The 8-bit quantisation adds triangular-PDF dither of +-1 LSB unless --no-dither.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct ToneMapPass {
    gl::Program program;       // RGBA8 target
    gl::Program floatProgram;  // RGBA16F target
};

// Display8: RGBA8, quantised here (dithered with settings.aa.dither); the displayed image.
// Float16: the same sRGB-encoded values unquantised in RGBA16F, for a pass after it (FXAA) that
// does the 8-bit quantisation itself.
enum class ToneMapTarget { Display8, Float16 };

// `autoExposure`: the auto_exposure pass's 1x1 EV, added to exposureEvBase(); invalid: not metered.
fg::ResourceId addToneMapPass(fg::FrameGraph& graph, ToneMapPass& state, const FrameData& frame, fg::ResourceId hdr,
                              fg::ResourceId autoExposure = {}, ToneMapTarget target = ToneMapTarget::Display8);

}  // namespace lp
