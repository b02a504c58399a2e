#include "passes/post_backend.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/measured_cache.hpp"
#include "engine/gl/gl.hpp"

#ifdef LIGHTPASS_HAVE_CUDA
#include "cuda/post_cuda.hpp"
#else
namespace lp::cuda {
class PostInterop {};  // never made without CUDA; complete so unique_ptr can delete it
}  // namespace lp::cuda
#endif

namespace lp {

PostBackendChoice chooseByTimes(const std::map<post::PostEffect, post::BackendTimes>& times) {
    PostBackendChoice c;
    for (const auto& [effect, t] : times) {
        const bool cuda = post::cudaWins(t);
        switch (effect) {
            case post::PostEffect::Bloom: c.bloom = cuda; break;
            case post::PostEffect::Composite: c.composite = cuda; break;
            case post::PostEffect::Toon: c.toon = cuda; break;
        }
    }
    return c;
}

double postEffectsMs(const std::map<post::PostEffect, post::BackendTimes>& times, bool cudaForAll) {
    double sum = 0.0;
    for (const auto& [effect, t] : times) {
        if (t.cudaMs < 0.0 || (!cudaForAll && t.glslMs < 0.0)) return -1.0;
        sum += cudaForAll ? t.cudaMs : std::min(t.cudaMs, t.glslMs);
    }
    return sum;
}

bool sharedInteropWins(const std::map<post::PostEffect, post::BackendTimes>& shared,
                       const std::map<post::PostEffect, post::BackendTimes>& mapped, bool cudaForAll) {
    if (shared.empty() || shared.size() != mapped.size()) return false;
    for (const auto& [effect, t] : shared)
        if (!mapped.count(effect)) return false;
    const double viaShared = postEffectsMs(shared, cudaForAll), viaMap = postEffectsMs(mapped, cudaForAll);
    if (viaShared < 0.0) return false;
    return viaMap < 0.0 || viaShared < viaMap;
}

PostBackend::PostBackend() : cacheFile(measuredCachePath()) {}
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

fg::ExternalTextureSource* PostBackend::externalTextureSource() {
#ifdef LIGHTPASS_HAVE_CUDA
    if (interop && cuda_) return interop->sharedTextureSource();
#endif
    return nullptr;
}

bool PostBackend::cudaUsable(PostSettings::Backend requested, PostSettings::CudaInterop interopMode) {
    if (resolved_ && requested == requested_ && interopMode == requestedInterop_) return cuda_;
    resolved_ = true;
    requested_ = requested;
    requestedInterop_ = interopMode;
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
    // A change of interop mode starts the CUDA side afresh (the pool drops the old shared textures).
    if (interop && interopMadeFor_ != interopMode) interop.reset();
    if (!interop) {
        interopMadeFor_ = interopMode;
        interop = std::make_unique<cuda::PostInterop>();
        interopUndecided_ = false;
        const bool external = interopMode == PostSettings::CudaInterop::External;
        // The fallback chain: shared textures ordered by Vulkan semaphores, then (external only) by
        // host waits, then map/unmap; each step down is one warning line saying why.
        const std::string why = interopMode == PostSettings::CudaInterop::Map ? "" : interop->useSharedTextures();
        if (interopMode == PostSettings::CudaInterop::Map) {
            interopPath_ = kInteropMap;
            logInfo("post effects: CUDA through per-use map/unmap (--cuda-interop map)");
        } else if (!why.empty()) {
            if (external) throw Error("--cuda-interop external: " + why);
            interopPath_ = kInteropMap;
            logWarn("post effects: CUDA through per-use map/unmap (shared textures unavailable: " + why + ")");
        } else if (interop->sharedSync() == cuda::SharedSync::Semaphores) {
            interopPath_ = kInteropSemaphores;
            if (external)
                logInfo("post effects: CUDA on shared textures (GL_EXT_memory_object_fd on CUDA allocations, made "
                        "once; ordered on the GPU by " + interop->syncName() + ")");
            else
                interopUndecided_ = true;  // measured against map/unmap at the first frame's size
        } else if (external) {
            interopPath_ = kInteropHostWaits;
            logWarn("post effects: CUDA on shared textures ordered by host waits (Vulkan semaphores unavailable: " +
                    interop->semaphoreProblem() + ")");
        } else {
            // auto: host waits leave the GPU idle inside the pass and measured slower than
            // map/unmap on the H100 (bench/results/post/2026-11-24_cuda-interop), so auto does not take them.
            const std::string semaphores = interop->semaphoreProblem();
            interop = std::make_unique<cuda::PostInterop>();
            interopPath_ = kInteropMap;
            logWarn("post effects: CUDA through per-use map/unmap (Vulkan semaphores unavailable: " + semaphores +
                    "; shared textures would need host waits)");
        }
    }
    cuda_ = true;
#endif
    return cuda_;
}

void PostBackend::keepSharedInterop() { interopUndecided_ = false; }

void PostBackend::useMapInterop() {
#ifdef LIGHTPASS_HAVE_CUDA
    interop = std::make_unique<cuda::PostInterop>();  // its pool source is gone: the pool drops its textures
#endif
    interopPath_ = kInteropMap;
    interopUndecided_ = false;
}

PostBackendChoice PostBackend::autoChoice(const post::TimingKey& base, const std::vector<post::PostEffect>& effects,
                                          bool remeasure,
                                          const std::function<post::BackendTimes(post::PostEffect)>& measure) {
    const std::string decidedKey = base.text() + (remeasure ? "|remeasure" : "");
    if (auto it = decided_.find(decidedKey); it != decided_.end()) return it->second;
    const PostBackendChoice choice = chooseByTimes(effectTimes(base, effects, remeasure, measure));
    decided_[decidedKey] = choice;
    return choice;
}

std::map<post::PostEffect, post::BackendTimes> PostBackend::effectTimes(
    const post::TimingKey& base, const std::vector<post::PostEffect>& effects, bool remeasure,
    const std::function<post::BackendTimes(post::PostEffect)>& measure) {
    if (!cacheRead_ && !cacheFile.empty()) {
        post::CacheRead read = post::readTimingCache(cacheFile);
        if (!read.warning.empty()) logWarn(read.warning);
        cache_ = std::move(read.entries);
    }
    cacheRead_ = true;
    std::map<post::PostEffect, post::BackendTimes> times;
    std::string report;
    bool wrote = false;
    for (post::PostEffect effect : effects) {
        post::TimingKey key = base;
        key.effect = effect;
        const std::string text = key.text();
        auto cached = cache_.find(text);
        const bool measureNow = cached == cache_.end() || (remeasure && !remeasured_.count(text));
        post::BackendTimes t = measureNow ? measure(effect) : cached->second;
        if (measureNow) {
            remeasured_.insert(text);
            if (t.measured()) {
                cache_[text] = t;
                wrote = true;
            }
        }
        times[effect] = t;
        char line[160];
        std::snprintf(line, sizeof line, "%s%s %s (cuda %.3f ms, glsl %.3f ms, %s)", report.empty() ? "" : ", ",
                      post::postEffectName(effect), post::cudaWins(t) ? "cuda" : "glsl", t.cudaMs, t.glslMs,
                      measureNow ? "measured" : "cached");
        report += line;
    }
    if (wrote && !cacheFile.empty()) {
        const std::string warning = post::writeTimingCache(cacheFile, cache_);
        if (!warning.empty()) logWarn(warning);
    }
    if (!effects.empty())
        logInfo("post backend auto at " + std::to_string(base.width) + "x" + std::to_string(base.height) +
                ", bloom kernel " + std::to_string(base.kernel) + ", interop " + base.interop + ": " + report);
    return times;
}

}  // namespace lp
