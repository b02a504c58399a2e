#pragma once
// Which implementation runs bloom and toon: CUDA (kernels on the GL textures through
// interop) or GLSL compute. Decided on first use, when a GL context exists, and again when the
// requested backend changes; the fallback from `auto` is logged once.
#include <memory>
#include <string>

#include "engine/render/settings.hpp"

namespace lp {

namespace cuda {
class PostInterop;  // cuda/post_cuda.hpp, included by the .cpp files that call it
}

struct PostBackend {
    PostBackend();
    ~PostBackend();
    PostBackend(PostBackend&&) noexcept;
    PostBackend& operator=(PostBackend&&) noexcept;

    // Whether CUDA runs the post effects for `requested`. `cuda` with no usable device throws
    // lp::Error("--post-backend cuda: <why>"); `auto` falls back to GLSL.
    bool useCuda(PostSettings::Backend requested);
    // Empty when CUDA can run here (device present, GL context on NVIDIA), else why not. Needs GL.
    static std::string cudaProblem();
    static bool compiledWithCuda();
    // Once per frame, by whichever post pass runs first (CUDA registrations age by these frames).
    void beginFrame(unsigned long frame);

    unsigned long frameIndex = 0;  // counts built frames (addPostPasses)

    std::unique_ptr<cuda::PostInterop> interop;  // made when CUDA is first chosen (never without CUDA)

private:
    bool resolved_ = false;
    bool cuda_ = false;
    bool fallbackLogged_ = false;
    PostSettings::Backend requested_ = PostSettings::Backend::Auto;
};

}  // namespace lp
