#pragma once
// --aa fxaa: FXAA 3.11 quality (Lottes; preset 39's 12-step edge search) on the tone-mapped image,
// after the tone map, at the output size ("fxaa"). The tone map hands it the sRGB-encoded colour
// unquantised (RGBA16F); this pass computes luma itself, filters, and does the display's one 8-bit
// quantisation (dithered unless --no-dither). Shader: shaders/fxaa.comp, math in common/fxaa.glsl.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct FxaaPass {
    gl::Program program;
};

// Reads the tone map's RGBA16F `tonemapped` and creates the RGBA8 display image.
fg::ResourceId addFxaaPass(fg::FrameGraph& graph, FxaaPass& state, const FrameData& frame, fg::ResourceId tonemapped);

}  // namespace lp
