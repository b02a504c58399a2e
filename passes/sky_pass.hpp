#pragma once
// The background, drawn after the geometry: only pixels whose depth is at the far plane are
// written. Without an environment map it is the scene's plain colour.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct SkyPass {
    gl::Program program;
};

fg::ResourceId addSkyPass(fg::FrameGraph& graph, SkyPass& state, const FrameData& frame, fg::ResourceId depth,
                          fg::ResourceId hdr);

}  // namespace lp
