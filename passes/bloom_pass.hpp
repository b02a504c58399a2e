#pragma once
// Bloom: "bloom" makes the bloom buffer from the HDR buffer (bright pass + separable Gaussian,
// or the Jimenez mip chain), "bloom_composite" adds strength x bloom into the HDR buffer. Each runs
// in CUDA or GLSL compute per PostBackend; the graph is the same either way.
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/post_backend.hpp"

namespace lp {

struct BloomPass {
    gl::Program bright, blur, composite, down, up;
    gl::Texture scratchA, scratchB;  // separable: bright pass, horizontal blur (full resolution)
    gl::Texture mips;                // mip chain: level 0 = half resolution
    gl::Program blurFragment;        // the fragment version of the blur (bloom_blur.frag)
    gl::Framebuffer fbo;
    gl::VertexArray vao;
    // CUDA: the frame (PostBackend::frameIndex) whose composite the bloom pass already did, fused
    // into its last kernel; bloom_composite then has nothing left to do.
    unsigned long cudaCompositedFrame = 0;
};

struct BloomResult {
    fg::ResourceId hdr;    // after the composite
    fg::ResourceId bloom;  // the bloom buffer alone (RGBA16F, before strength)
};

BloomResult addBloomPass(fg::FrameGraph& graph, BloomPass& state, PostBackend& backend, const FrameData& frame,
                         const post::PostConfig& config, fg::ResourceId hdr);

// The GLSL path on plain textures (hdr: RGBA16F read; bloom: RGBA16F written), for the passes
// and the benchmark.
void runBloomGlsl(BloomPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width, int height,
                  const post::BloomParams& p);
void runBloomCompositeGlsl(BloomPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width,
                           int height, float strength);

}  // namespace lp
