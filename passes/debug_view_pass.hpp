#pragma once
// One G-buffer channel as an image (depth, normals, diffuse, position, shininess, specular,
// texcoords). It reads only that channel, so the graph culls lighting and tone mapping by itself.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct DebugViewPass {
    gl::Program program;
};

// Which G-buffer channels `view` needs (texcoords are only written for their view).
GBufferChannels channelsForView(DebugView view);
fg::ResourceId addDebugViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                const GBuffer& gbuffer, DebugView view);

}  // namespace lp
