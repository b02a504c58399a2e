#pragma once
// G-buffer: rasterises every mesh once into the seeds' unpacked layout (see
// shaders/common/gbuffer_layout.glsl). Writes only the channels some pass will read.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct GBufferChannels {
    bool position = true;
    bool texcoord = false;
};

struct GBuffer {
    fg::ResourceId depth, normal, diffuse, position, specular, texcoord;
};

struct GBufferPass {
    gl::Program program;
    gl::Framebuffer fbo;
};

GBuffer addGBufferPass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels);

}  // namespace lp
