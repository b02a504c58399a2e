#pragma once
// skinning (--skinning gpu, the default; docs/motion.md "Skinning on the GPU"): poses the animated
// glTF models' vertices once a frame with shaders/skinning.comp, into the vertex buffers every pass
// draws from (G-buffer or visibility raster and resolve, shadow maps, forward, transparent,
// emission) and the previous positions their motion vectors read. SceneGpu::pose uploads the
// frame's joint matrices, node matrices and morph weights and lists the dispatches; this pass
// records them. Its buffers are one imported resource, "posed_vertices": written here as storage,
// read by every pass that draws the meshes (readPosedVertices), so the graph orders them after it
// and issues the barriers. Skipped with --skinning cpu, when nothing is animated, and in a frame
// whose pose the buffers already hold.
#include <string>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

struct SkinningPass {
    gl::Program program;
};

inline constexpr const char* kPosedVerticesName = "posed_vertices";

// Why the frame runs no skinning pass ("" when it does): the settings and the scene decide, and,
// where the GPU scene is known, whether its vertex buffers already hold this frame's pose.
std::string skinningSkipReason(const FrameData& frame);
// Adds the pass (call only when skinningSkipReason is empty); the frame's drawing passes then read
// its buffers once frame.posedVerticesOnGpu is set.
void addSkinningPass(fg::FrameGraph& graph, SkinningPass& state, const FrameData& frame);
// For a pass that draws the scene's meshes (as vertex attributes, or copying them: fg::Usage::Transfer):
// declares that it reads the posed vertices, when the frame poses them on the GPU.
void readPosedVertices(fg::PassBuilder& b, const FrameData& frame, fg::Usage how = fg::Usage::VertexBuffer);

}  // namespace lp
