#pragma once
// gbuffer_visibility (--gbuffer-mode visibility): the raster half of a visibility-buffer G-buffer
// (Burns & Hunt 2013). Every mesh is drawn once with the G-buffer's vertex shader (the same depth,
// so the emission pass's GL_EQUAL test still holds) into the depth target and an R32UI id target
// alone: 4 bytes of colour a pixel instead of the classic G-buffer's 16..44. MASK materials sample
// their alpha and discard as gbuffer.frag does; single-sided materials cull back faces, which is the
// classic pass's back-face discard. gbuffer_resolve (passes/visibility_resolve_pass) then rebuilds
// the G-buffer targets from the id. Id packing: shaders/common/visibility.glsl.
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp {

class SceneGpu;

struct VisibilityBuffer {
    fg::ResourceId depth;  // gbuffer.depth, as the classic pass writes it
    fg::ResourceId ids;    // gbuffer.visibility: R32UI, global triangle index + 1 where depth holds a surface
                           // (not cleared: undefined where depth keeps its cleared value)
};

struct VisibilityPass {
    gl::Program opaque;  // no texture, no discard: early depth tests hold
    GBufferProgramKey opaqueLayout;
    gl::Program masked;  // MASK materials: the alpha test of gbuffer.frag
    GBufferProgramKey maskedLayout;
    gl::Framebuffer fbo;
};

// One record per draw of the scene, in the order both visibility passes number the triangles
// (std430 layout of visibility_resolve.comp's DrawRecord).
struct VisibilityDrawRecord {
    uint32_t firstTriangle = 0;  // the scene's global index of the draw's first triangle
    uint32_t firstIndex = 0;     // into the concatenation of every mesh's index buffer
    uint32_t vertexBase = 0;     // the mesh's first vertex in the concatenated vertex buffer
    uint32_t mesh = 0;           // into SceneGpu::meshes
    int32_t material = 0;        // into SceneGpu::materials
    uint32_t indexCount = 0;
    uint32_t pad[2] = {0, 0};
};
// meshIndexBases / meshVertexBases: each mesh's first index and vertex in the concatenated buffers
// (the instances of a model, sharing its buffers, share them).
std::vector<VisibilityDrawRecord> visibilityDrawRecords(const SceneGpu& gpu, const std::vector<uint32_t>& meshIndexBases,
                                                        const std::vector<uint32_t>& meshVertexBases);

VisibilityBuffer addVisibilityPass(fg::FrameGraph& graph, VisibilityPass& state, const FrameData& frame);

}  // namespace lp
