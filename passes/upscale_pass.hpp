#pragma once
// Render scale < 1: the G-buffer, lighting and post effects ran at FrameData::width x height; this
// pass brings their result to the output size. The HDR buffer is upsampled bilinearly before the
// tone map ("upscale"); a debug view's RGBA8 image is upsampled nearest ("upscale_debug") so it
// still shows the G-buffer's own texels. Shader: shaders/upscale.comp, math in common/upscale.glsl.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct UpscalePass {
    gl::Program hdrProgram;    // bilinear, RGBA16F
    gl::Program debugProgram;  // nearest, RGBA8
};

enum class UpscaleInput { Hdr, DebugView };

// Reads `input` (FrameData::width x height) and creates its copy at outputWidth x outputHeight.
fg::ResourceId addUpscalePass(fg::FrameGraph& graph, UpscalePass& state, const FrameData& frame, fg::ResourceId input,
                              UpscaleInput kind);

}  // namespace lp
