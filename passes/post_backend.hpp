#pragma once
// Which implementation runs each post effect (bloom, the bloom composite, toon): CUDA (kernels
// on the GL textures, shared through external memory or mapped per use) or GLSL compute. Decided
// when a GL context exists: `cuda` and `glsl` for every effect; `auto` per effect by a measurement
// made at start-up at the frame's size and bloom kernel (passes/post_pass.cpp measures), cached
// per GPU in engine/post/backend_timings' file. The fallbacks and the choices are logged once.
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "engine/post/backend_timings.hpp"
#include "engine/render/settings.hpp"

namespace lp {

namespace cuda {
class PostInterop;  // cuda/post_cuda.hpp, included by the .cpp files that call it
}
namespace fg {
struct ExternalTextureSource;
}

// Per effect, true: CUDA runs it.
struct PostBackendChoice {
    bool bloom = false, composite = false, toon = false;
    bool any() const { return bloom || composite || toon; }
};

// Pure: the choice from measured times (CUDA only where strictly faster, see post::cudaWins).
PostBackendChoice chooseByTimes(const std::map<post::PostEffect, post::BackendTimes>& times);

// Pure: whether CUDA on shared textures (ordered on the GPU by semaphores) beats map/unmap, from each
// path's measured times of the same effects: the post effects' cost summed over the effects, each at
// its CUDA time when `cudaForAll` (--post-backend cuda), else at the faster of CUDA and GLSL (what
// auto would run). Shared only where strictly cheaper; a tie, or an effect not measured, keeps map.
bool sharedInteropWins(const std::map<post::PostEffect, post::BackendTimes>& shared,
                       const std::map<post::PostEffect, post::BackendTimes>& mapped, bool cudaForAll);
// The cost sharedInteropWins compares (ms; negative when an effect was not measured).
double postEffectsMs(const std::map<post::PostEffect, post::BackendTimes>& times, bool cudaForAll);

// The timing-cache names of the interop paths (TimingKey::interop).
inline constexpr const char* kInteropSemaphores = "external+semaphores";
inline constexpr const char* kInteropHostWaits = "external+host-waits";
inline constexpr const char* kInteropMap = "map";

struct PostBackend {
    PostBackend();
    ~PostBackend();
    PostBackend(PostBackend&&) noexcept;
    PostBackend& operator=(PostBackend&&) noexcept;

    // Whether CUDA can run the post effects for `requested` with `interop`, making the CUDA side on
    // first use. `cuda` with no usable device throws lp::Error("--post-backend cuda: <why>"), and
    // `--cuda-interop external` where CUDA runs but shared textures do not work throws too; otherwise
    // it falls back (to GLSL, to map/unmap) with one info line.
    bool cudaUsable(PostSettings::Backend requested, PostSettings::CudaInterop interop);
    // Empty when CUDA can run here (device present, GL context on NVIDIA), else why not. Needs GL.
    static std::string cudaProblem();
    static bool compiledWithCuda();
    // Once per frame, by whichever post pass runs first (CUDA registrations age by these frames).
    void beginFrame(unsigned long frame);
    // kInteropSemaphores, kInteropHostWaits (shared textures and how they are ordered) or
    // kInteropMap once CUDA was made; "" before.
    const std::string& interopPath() const { return interopPath_; }
    // `--cuda-interop auto` where shared textures work with semaphores: whether they or map/unmap
    // run is measured at the first frame's size (passes/post_pass.cpp), then settled by one of these.
    bool interopUndecided() const { return interopUndecided_; }
    void keepSharedInterop();
    void useMapInterop();
    // The texture pool's source of shared textures: null unless CUDA runs on the external path.
    fg::ExternalTextureSource* externalTextureSource();

    // `auto`'s choice for `base` (its effect field is set per effect): from this process's earlier
    // choice, else the cache file, else measure(effect) for each effect in `effects`, which is then
    // cached. `remeasure` ignores the file (once per key and process). Logs the choice once per key.
    PostBackendChoice autoChoice(const post::TimingKey& base, const std::vector<post::PostEffect>& effects,
                                 bool remeasure,
                                 const std::function<post::BackendTimes(post::PostEffect)>& measure);
    // The times behind autoChoice (cached, else measured and cached), logged; no choice is remembered.
    std::map<post::PostEffect, post::BackendTimes> effectTimes(const post::TimingKey& base,
                                                               const std::vector<post::PostEffect>& effects,
                                                               bool remeasure,
                                                               const std::function<post::BackendTimes(post::PostEffect)>& measure);
    // The measurement cache holding the timings (measuredCachePath()); tests may set it.
    std::filesystem::path cacheFile;

    unsigned long frameIndex = 0;  // counts built frames (addPostPasses)

    std::unique_ptr<cuda::PostInterop> interop;  // made when CUDA is first chosen (never without CUDA)

private:
    bool resolved_ = false;
    bool cuda_ = false;
    bool fallbackLogged_ = false;
    PostSettings::Backend requested_ = PostSettings::Backend::Auto;
    PostSettings::CudaInterop requestedInterop_ = PostSettings::CudaInterop::Auto;
    std::string interopPath_;
    bool interopUndecided_ = false;
    PostSettings::CudaInterop interopMadeFor_ = PostSettings::CudaInterop::Auto;
    bool cacheRead_ = false;
    post::TimingCache cache_;
    std::set<std::string> remeasured_;
    std::map<std::string, PostBackendChoice> decided_;  // by the key without its effect
};

}  // namespace lp
