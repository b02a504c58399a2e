#pragma once
// Toon: the luminance ramp and Sobel outlines (depth and normals) on the lit HDR buffer, in
// place, in CUDA or GLSL compute per PostBackend (see engine/post/post_math.hpp for the definitions).
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/post_backend.hpp"

namespace lp {

struct ToonPass {
    gl::Program program;
    GBufferSettings layout;  // the G-buffer layout `program` was compiled for
    bool toldGlslForLayout = false;  // the once-logged note that a non-default layout runs the GLSL toon
};

// Reads the G-buffer's depth (coverage), eye depth and normal through shaders/common/gbuffer_layout.glsl.
// `cuda`: the post backend chose CUDA. Its kernel reads the unpacked, stored layout only; other
// layouts run the GLSL toon.
fg::ResourceId addToonPass(fg::FrameGraph& graph, ToonPass& state, PostBackend& backend, bool cuda,
                           const FrameData& frame, const post::PostConfig& config, const GBuffer& gbuffer,
                           fg::ResourceId hdr);

// The G-buffer targets the GLSL toon reads (texture ids; position 0 when rebuilt from depth), their
// layout, and the camera that rebuilds positions: (near, far, tan(vertical fov / 2), width / height).
struct ToonGBufferTextures {
    GLuint depth = 0, normal = 0, position = 0;
    GBufferSettings layout;
    glm::vec4 camera{0.1f, 100.0f, 1.0f, 1.0f};
};
// No barrier after it: the caller (the graph) orders what reads `hdr` next.
void runToonGlsl(ToonPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, const ToonGBufferTextures& g,
                 int width, int height, const post::ToonParams& p);

}  // namespace lp
