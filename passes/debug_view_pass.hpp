#pragma once
// One G-buffer channel as an image (depth, normals, diffuse, position, shininess, specular,
// texcoords), decoded from whatever layout the G-buffer has. It reads only the G-buffer, so the graph
// culls lighting and tone mapping by itself.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/ibl_pass.hpp"
#include "passes/shadow_map_pass.hpp"

namespace lp {

struct DebugViewPass {
    gl::Program program;
    GBufferSettings layout;  // the G-buffer layout `program` was compiled for
    IblPass* ibl = nullptr;  // the environment views draw from its cache (set by the frame builder)
    const ShadowMaps* shadowMaps = nullptr;  // this frame's maps, for the shadowmap view (set by the frame builder)
};

// Which G-buffer channels `view` needs (texcoords are only written for their view).
GBufferChannels channelsForView(DebugView view);
fg::ResourceId addDebugViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                const GBuffer& gbuffer, DebugView view);

}  // namespace lp
