#pragma once
// Toon: the luminance ramp and Sobel outlines (depth and normals) on the lit HDR buffer, in
// place, in CUDA or GLSL compute per PostBackend (see engine/post/post_math.hpp for the definitions).
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/post_backend.hpp"

namespace lp {

struct ToonPass {
    gl::Program program;
};

// position / normal: the G-buffer's eye-space position (w = coverage) and normal (RGBA32F).
fg::ResourceId addToonPass(fg::FrameGraph& graph, ToonPass& state, PostBackend& backend, const FrameData& frame,
                           const post::PostConfig& config, fg::ResourceId position, fg::ResourceId normal,
                           fg::ResourceId hdr);

void runToonGlsl(ToonPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint position, GLuint normal,
                 int width, int height, const post::ToonParams& p);

}  // namespace lp
