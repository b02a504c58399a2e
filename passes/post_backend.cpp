#include "passes/post_backend.hpp"

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/gl.hpp"

#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/post_cuda.hpp"
#else
namespace lp::cuda {
class PostInterop {};  // never made without CUDA; complete so unique_ptr can delete it
}  // namespace lp::cuda
#endif

namespace lp {

PostBackend::PostBackend() = default;
PostBackend::~PostBackend() = default;
PostBackend::PostBackend(PostBackend&&) noexcept = default;
PostBackend& PostBackend::operator=(PostBackend&&) noexcept = default;

bool PostBackend::compiledWithCuda() {
#ifdef LIGHTPASS_HAVE_CUDA
    return true;
#else
    return false;
#endif
}

std::string PostBackend::cudaProblem() {
#ifndef LIGHTPASS_HAVE_CUDA
    return "built without a CUDA toolkit";
#else
    std::string problem = cuda::postDeviceProblem();
    if (!problem.empty()) return problem;
    const char* vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    const std::string v = vendor ? vendor : "";
    if (v.find("NVIDIA") == std::string::npos) return "the GL context is not on NVIDIA (" + v + "), so no interop";
    return {};
#endif
}

void PostBackend::beginFrame(unsigned long frame) {
#ifdef LIGHTPASS_HAVE_CUDA
    if (interop) interop->beginFrame(frame);
#else
    (void)frame;
#endif
}

bool PostBackend::useCuda(PostSettings::Backend requested) {
    if (resolved_ && requested == requested_) return cuda_;
    resolved_ = true;
    requested_ = requested;
    cuda_ = false;
    if (requested == PostSettings::Backend::Glsl) return false;
    const std::string problem = cudaProblem();
    if (!problem.empty()) {
        if (requested == PostSettings::Backend::Cuda) throw Error("--post-backend cuda: " + problem);
        if (!fallbackLogged_) logInfo("post effects: GLSL compute (CUDA unavailable: " + problem + ")");
        fallbackLogged_ = true;
        return false;
    }
#ifdef LIGHTPASS_HAVE_CUDA
    if (!interop) interop = std::make_unique<cuda::PostInterop>();
    cuda_ = true;
#endif
    return cuda_;
}

}  // namespace lp
