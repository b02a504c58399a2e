#pragma once
// `--post-backend auto` per effect: which of CUDA and GLSL compute runs bloom, the composite and
// toon, from times measured at start-up on this GPU, and the cache that keeps those times between
// runs (the section "post_backend" of engine/core/measured_cache.hpp's file). No GL or CUDA here: passes/post_backend.cpp measures.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace lp::post {

enum class PostEffect { Bloom, Composite, Toon };
const char* postEffectName(PostEffect e);  // "bloom", "composite", "toon"
inline constexpr PostEffect kPostEffects[] = {PostEffect::Bloom, PostEffect::Composite, PostEffect::Toon};

// What a measurement depends on: the GPU and its driver, the image size, the bloom kernel and
// method, and how CUDA reaches the textures ("shared" or "map").
struct TimingKey {
    std::string gpu, driver;
    int width = 0, height = 0;
    int kernel = 0;
    std::string method;   // "separable" | "mip-chain"
    std::string interop;  // "shared" | "map"
    PostEffect effect = PostEffect::Bloom;
    std::string text() const;  // the cache's key: every field, '|'-separated
};

// Milliseconds per run of one effect (median of a few timed runs); negative: not measured.
struct BackendTimes {
    double cudaMs = -1.0, glslMs = -1.0;
    bool measured() const { return cudaMs >= 0.0 && glslMs >= 0.0; }
};

// CUDA when it measured strictly faster; GLSL otherwise (ties, or nothing measured: GLSL needs no
// interop and runs on every GPU).
bool cudaWins(const BackendTimes& t);

using TimingCache = std::map<std::string, BackendTimes>;  // by TimingKey::text()

struct CacheRead {
    TimingCache entries;
    std::string warning;  // set when the file exists but cannot be used (it is then remeasured)
};
// The post backend's section of the measurement cache `file` (lp::measuredCachePath()). A missing
// file is an empty cache without a warning; an unusable file, or a bad entry (negative or
// non-finite time), is an empty cache with a one-line warning naming the file. Never throws.
CacheRead readTimingCache(const std::filesystem::path& file);
// Replaces the section with all entries, other sections kept (a temporary file renamed into place,
// so a crash never leaves half a file); returns a one-line warning instead of throwing when it cannot.
std::string writeTimingCache(const std::filesystem::path& file, const TimingCache& entries);

}  // namespace lp::post
