#pragma once
// Bloom: "bloom" makes the bloom buffer from the HDR buffer (bright pass + separable Gaussian,
// or the Jimenez mip chain), "bloom_composite" adds strength x bloom into the HDR buffer. Each runs
// in CUDA or GLSL compute per PostBackend (per step), chosen before the graph is built. When both
// run in CUDA and the composite is wanted, one fused "bloom" pass does both (one launch and one
// GL<->CUDA hand-over fewer) and declares that it writes the HDR buffer. The GLSL path's scratch textures are graph transients (pooled).
#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/post/post_config.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/post_backend.hpp"

namespace lp {

struct BloomPass {
    gl::Program bright, blur, composite, down, up;
    gl::Program blurFragment;        // the fragment version of the blur (bloom_blur.frag)
    gl::Framebuffer fbo;
    gl::VertexArray vao;
};

struct BloomResult {
    fg::ResourceId hdr;    // after the composite (unchanged when `composite` is false)
    fg::ResourceId bloom;  // the bloom buffer alone (RGBA16F, before strength)
    bool fusedComposite = false;  // the CUDA bloom pass also composites: no bloom_composite pass
};

// `cuda.bloom` / `cuda.composite`: the post backend chose CUDA for that step. `fuse` (both in CUDA
// only): one pass does bloom and composite; otherwise bloom_composite is its own pass (culled when
// only the bloom buffer is shown), and either step may run in CUDA with the other in GLSL.
BloomResult addBloomPass(fg::FrameGraph& graph, BloomPass& state, PostBackend& backend, const PostBackendChoice& cuda,
                         bool fuse, const FrameData& frame, const post::PostConfig& config, fg::ResourceId hdr);

// The scratch textures of the GLSL path: separable uses `bright` and `blurH` (full size, RGBA16F),
// the mip chain `mips` (bloomScratchDescs gives their sizes).
struct BloomScratch {
    GLuint bright = 0, blurH = 0, mips = 0;
};
struct BloomScratchDescs {
    fg::TextureDesc bright, blurH, mips;  // width 0: not used by this method
};
BloomScratchDescs bloomScratchDescs(const post::BloomParams& p, int width, int height);

// The GLSL path on plain textures (hdr: RGBA16F read; bloom: RGBA16F written), for the passes
// and the tests. Barriers between its own dispatches only: the caller orders what comes after.
void runBloomGlsl(BloomPass& state, const gl::ShaderLibrary& shaders, const BloomScratch& scratch, GLuint hdr,
                  GLuint bloom, int width, int height, const post::BloomParams& p);
void runBloomCompositeGlsl(BloomPass& state, const gl::ShaderLibrary& shaders, GLuint hdr, GLuint bloom, int width,
                           int height, float strength);

}  // namespace lp
