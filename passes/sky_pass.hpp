#pragma once
// The background, drawn after the geometry: only pixels whose depth is at the far plane are
// written: the environment cubemap in the view direction (times the scene's intensity), or without
// an environment map the scene's plain colour.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

struct SkyPass {
    gl::Program program;
    GBufferProgramKey layout;  // the G-buffer layout (depth convention) `program` was compiled for
};

// `environmentCube`: the environment (importEnvironment / addIblBakePass); invalid without a map.
fg::ResourceId addSkyPass(fg::FrameGraph& graph, SkyPass& state, const FrameData& frame, fg::ResourceId depth,
                          fg::ResourceId environmentCube, fg::ResourceId hdr);

}  // namespace lp
