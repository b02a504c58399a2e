#pragma once
// --aa ssaa: the G-buffer, lighting and post effects ran at S x the output size in each axis
// (FrameData::width = S x outputWidth); this pass filters their HDR result down to the output size
// before the tone map ("ssaa_downsample"). The filter is a box over each output pixel's exact S x S
// footprint: every sample inside the pixel weighs 1 / S^2 and none outside it, so the result is the
// pixel's area average of the supersampled image (what the coverage test checks), and there are no
// negative lobes to ring around HDR highlights. Shader: shaders/ssaa_downsample.comp, math in
// common/downsample.glsl.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct DownsamplePass {
    gl::Program program;
};

// Reads `hdr` (scale x the output size) and creates its box-filtered copy at outputWidth x outputHeight.
fg::ResourceId addDownsamplePass(fg::FrameGraph& graph, DownsamplePass& state, const FrameData& frame, fg::ResourceId hdr,
                                 int scale);

}  // namespace lp
