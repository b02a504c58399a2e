// post_cuda_bench: the CUDA post effects' benchmarks on a GPU (bench/post_interop.sh runs them).
// Not tests: they time, they do not check. Each prints one line per measurement in the form
// bench/summarize_post_interop.py reads:
//   kernels           the fused bloom + composite on RGBA16F CUDA arrays (no GL) against its floor:
//                     24 bytes a texel (the HDR read, the bloom and the HDR written, 8 bytes each) at
//                     the measured copy bandwidth; the separable bloom with the direct and the
//                     tensor-core blur and what auto picks, and the mip chain; also the bloom buffer
//                     alone (16 bytes a texel), lines "bloom_only_kernels"
//   mip-chain-tuning  what the mip chain's one-block tail and overlapping launches buy (lines
//                     "mip_chain_tuning"), and each launch of the default timed alone ("mip_chain_step")
//   copy-kernels      the bandwidth the floors assume: plain copies of an RGBA16F image through CUDA
//                     arrays and linear memory ("copy_kernels"), beside cudaMemcpy's
//   hand-over         what one hand-over to CUDA and back costs a GL frame by itself, under each
//                     ordering of shared textures, and one map/unmap call instead ("hand-over bench")
// Without a CUDA device (or, for hand-over, an NVIDIA GL context) it says why and exits 0.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cuda/post_cuda.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/shader.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/post/post_reference.hpp"

using namespace lp;
using cuda::BloomBlur;
using post::BloomMethod;
using post::BloomParams;

namespace {

BloomParams separable(int kernel) {
    BloomParams p;
    p.kernel = kernel;
    p.method = BloomMethod::Separable;
    p.strength = 0.5f;
    return p;
}

// A failing variant is reported and the others still run; the exit code says whether any failed.
int failures = 0;
void reportFailure(int w, int h, int kernel, const char* variant, const std::exception& e) {
    std::fprintf(stderr, "post_cuda_bench: %dx%d kernel %d %s: %s\n", w, h, kernel, variant, e.what());
    ++failures;
}

void kernels() {
    struct Variant {
        const char* name;
        BloomMethod method;
        BloomBlur blur;
    };
    const Variant variants[] = {{"direct", BloomMethod::Separable, BloomBlur::Direct},
                                {"tensor", BloomMethod::Separable, BloomBlur::TensorCore},
                                {"auto", BloomMethod::Separable, BloomBlur::Auto},
                                {"mipchain", BloomMethod::MipChain, BloomBlur::Auto}};
    for (bool composite : {true, false})
        for (auto [w, h] : {std::pair{1920, 1080}, std::pair{3840, 2160}})
            for (int kernel : {3, 5, 9, 17, 25, 50, 100})
                for (const Variant& v : variants) {
                    BloomParams p = separable(kernel);
                    p.method = v.method;
                    cuda::BloomKernelTime t;
                    try {
                        t = cuda::timeBloomCompositeKernels(w, h, p, v.blur, 60, composite);
                    } catch (const std::exception& e) {
                        reportFailure(w, h, kernel, v.name, e);
                        continue;
                    }
                    const double bytes = composite ? 24.0 : 16.0;
                    const double floorMs = bytes * double(w) * double(h) / t.copyBytesPerSecond * 1e3;
                    const char* ran = v.method == BloomMethod::MipChain ? "mipchain" : t.tensorCores ? "tensor" : "direct";
                    std::printf("%s size=%dx%d kernel=%d blur=%s ran=%s ms=%.5f floor_ms=%.5f copy_GBps=%.1f\n",
                                composite ? "bloom_kernels" : "bloom_only_kernels", w, h, kernel, v.name, ran,
                                t.medianMs, floorMs, t.copyBytesPerSecond * 1e-9);
                    std::fflush(stdout);
                }
}

// As the passes run it (default), and with one setting changed: without the tail and with a larger
// one, without programmatic dependent launches. (The losing layouts measured before,
// bench/results/post/2026-11-24_cuda-interop/README.md, were removed from the kernels.)
void mipChainTuning() {
    const cuda::MipChainTuning defaults;
    cuda::MipChainTuning noTail = defaults, bigTail = defaults, noOverlap = defaults;
    noTail.tailTexels = 0;
    bigTail.tailTexels = 16384;
    noOverlap.programmaticLaunch = false;
    const std::pair<const char*, cuda::MipChainTuning> variants[] = {
        {"default", defaults}, {"no_tail", noTail}, {"tail_16k", bigTail}, {"no_overlap", noOverlap}};
    for (auto [w, h] : {std::pair{1920, 1080}, std::pair{3840, 2160}})
        for (int kernel : {5, 100})
            for (const auto& [name, tuning] : variants) {
                BloomParams p = separable(kernel);
                p.method = BloomMethod::MipChain;
                cuda::BloomKernelTime t;
                std::vector<cuda::MipChainStep> steps;
                const bool timeSteps = std::strcmp(name, "default") == 0;
                try {
                    t = cuda::timeBloomCompositeKernels(w, h, p, BloomBlur::Auto, 60, true, tuning,
                                                        timeSteps ? &steps : nullptr);
                } catch (const std::exception& e) {
                    reportFailure(w, h, kernel, name, e);
                    continue;
                }
                const double floorMs = 24.0 * double(w) * double(h) / t.copyBytesPerSecond * 1e3;
                std::printf("mip_chain_tuning size=%dx%d kernel=%d variant=%s ms=%.5f floor_ms=%.5f\n", w, h, kernel, name,
                            t.medianMs, floorMs);
                for (const cuda::MipChainStep& s : steps)  // each launch alone: its ms and the bandwidth of its bytes
                    std::printf("mip_chain_step size=%dx%d kernel=%d variant=%s step=%s ms=%.5f MB=%.2f GBps=%.0f\n", w, h,
                                kernel, name, s.name.c_str(), s.ms, s.bytes * 1e-6,
                                s.ms > 0 ? s.bytes / (s.ms * 1e-3) * 1e-9 : 0.0);
                std::fflush(stdout);
            }
}

void copyKernels() {
    for (auto [w, h] : {std::pair{1920, 1080}, std::pair{3840, 2160}}) {
        const cuda::CopyKernelTimes t = cuda::timeHalf4Copies(w, h, 60);
        const double bytes = 16.0 * double(w) * double(h);
        const double floorMs = bytes / t.copyBytesPerSecond * 1e3;
        for (auto [kind, ms] : {std::pair{"array", t.arrayMs}, std::pair{"linear", t.linearMs}})
            std::printf("copy_kernels size=%dx%d kind=%s ms=%.5f GBps=%.1f floor_ms=%.5f copy_GBps=%.1f\n", w, h, kind,
                        ms, bytes / (ms * 1e-3) * 1e-9, floorMs, t.copyBytesPerSecond * 1e-9);
        std::fflush(stdout);
    }
}

// The frame is GL compute work on a 1920x1080 RGBA16F image in two halves; between them the variants
// hand over nothing, one composite of strength 0 on a 64x48 shared texture (a kernel of a few
// microseconds: the cost is the hand-over), or two. GPU ms from GL timestamps at the frame's ends,
// median of 100 frames after 20 (the host waits for each frame, so every frame starts on an idle GPU).
void handOver(cuda::SharedSync sync) {
    constexpr int kW = 64, kH = 48, kWorkW = 1920, kWorkH = 1080, kDispatchesPerHalf = 8;
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) {
        std::printf("hand-over bench skipped: the headless GL context is not NVIDIA (%s)\n", ctx->info().renderer.c_str());
        return;
    }
    auto interop = std::make_unique<cuda::PostInterop>();
    const std::string problem = interop->useSharedTextures(sync);
    if (!problem.empty()) {
        std::printf("hand-over bench skipped: shared textures unavailable here: %s\n", problem.c_str());
        return;
    }
    if (interop->sharedSync() != sync) {
        std::printf("hand-over bench skipped: Vulkan semaphores unavailable here: %s\n", interop->semaphoreProblem().c_str());
        return;
    }
    fg::ExternalTextureSource* source = interop->sharedTextureSource();
    gl::ShaderLibrary shaders;
    gl::Program work = shaders.computeFromSource("hand_over_bench.comp", R"(#version 450
layout(local_size_x = 16, local_size_y = 16) in;
layout(rgba16f, binding = 0) uniform image2D target;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    vec4 v = imageLoad(target, p);
    for (int i = 0; i < 16; ++i) v = fract(v * 1.0001 + vec4(0.001, 0.002, 0.003, 0.004));
    imageStore(target, p, v);
}
)");
    gl::Texture image = gl::makeTexture2D(GL_RGBA16F, kWorkW, kWorkH, 1, "bench.hand_over_work");
    std::shared_ptr<fg::ExternalTexture> hdr = source->make({kW, kH, GL_RGBA16F}, "bench.shared_hdr");
    std::shared_ptr<fg::ExternalTexture> bloom = source->make({kW, kH, GL_RGBA16F}, "bench.shared_bloom");
    if (!hdr || !bloom) {
        std::printf("hand-over bench skipped: the shared-texture source made no RGBA16F texture\n");
        return;
    }
    const std::vector<float> ones(size_t(kW) * kH * 4, 1.0f);
    glTextureSubImage2D(hdr->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, ones.data());
    glTextureSubImage2D(bloom->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, ones.data());
    gl::Query begin = gl::makeQuery(GL_TIMESTAMP), end = gl::makeQuery(GL_TIMESTAMP);
    auto half = [&] {
        glUseProgram(work.id());
        glBindImageTexture(0, image.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        for (int i = 0; i < kDispatchesPerHalf; ++i) {
            glDispatchCompute((kWorkW + 15) / 16, (kWorkH + 15) / 16, 1);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
        glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        glUseProgram(0);
    };
    // Plain GL textures: the interop registers and maps them per call instead (the map/unmap path).
    gl::Texture plainHdr = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "bench.plain_hdr");
    gl::Texture plainBloom = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "bench.plain_bloom");
    auto frameMs = [&](int handOvers, bool mapped = false) {
        std::vector<double> ms;
        for (int f = 0; f < 120; ++f) {
            glQueryCounter(begin.id(), GL_TIMESTAMP);
            half();
            for (int i = 0; i < handOvers; ++i) {
                if (mapped) interop->composite(plainHdr.id(), plainBloom.id(), kW, kH, 0.0f);
                else interop->composite(hdr->texture(), bloom->texture(), kW, kH, 0.0f);
            }
            half();
            glQueryCounter(end.id(), GL_TIMESTAMP);
            glFinish();
            GLuint64 t0 = 0, t1 = 0;
            glGetQueryObjectui64v(begin.id(), GL_QUERY_RESULT, &t0);
            glGetQueryObjectui64v(end.id(), GL_QUERY_RESULT, &t1);
            if (f >= 20) ms.push_back(double(t1 - t0) * 1e-6);
        }
        std::sort(ms.begin(), ms.end());
        return ms[ms.size() / 2];
    };
    const double none = frameMs(0), one = frameMs(1), two = frameMs(2), mapped = frameMs(1, true);
    const double noneAgain = frameMs(0);
    std::printf("  hand-over bench (%s): GL frame %.3f ms (again %.3f); one hand-over +%.3f ms; two +%.3f ms;"
                " one map/unmap call instead +%.3f ms\n",
                interop->syncName().c_str(), none, noneAgain, one - none, two - none, mapped - none);
    std::fflush(stdout);
}

int usage(std::FILE* to) {
    std::fprintf(to,
                 "usage: post_cuda_bench kernels|mip-chain-tuning|copy-kernels|hand-over|all\n"
                 "  kernels           fused bloom + composite and the bloom alone on CUDA arrays against the floor\n"
                 "  mip-chain-tuning  the mip chain's tail and overlapping launches, each launch alone\n"
                 "  copy-kernels      plain RGBA16F copies through CUDA arrays and linear memory\n"
                 "  hand-over         what one GL -> CUDA -> GL hand-over costs a GL frame, per ordering\n");
    return to == stdout ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) return usage(stderr);
    const std::string what = argv[1];
    if (what == "--help" || what == "-h") return usage(stdout);
    const bool all = what == "all";
    if (!all && what != "kernels" && what != "mip-chain-tuning" && what != "copy-kernels" && what != "hand-over") {
        std::fprintf(stderr, "post_cuda_bench: unknown benchmark '%s'\n", what.c_str());
        return usage(stderr);
    }
    const std::string device = cuda::postDeviceProblem();
    if (!device.empty()) {
        std::printf("post_cuda_bench: skipped, no CUDA device: %s\n", device.c_str());
        return 0;
    }
    try {
        if (all || what == "kernels") kernels();
        if (all || what == "mip-chain-tuning") mipChainTuning();
        if (all || what == "copy-kernels") copyKernels();
        if (all || what == "hand-over")
            for (cuda::SharedSync sync : {cuda::SharedSync::Semaphores, cuda::SharedSync::HostWaits}) handOver(sync);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "post_cuda_bench: %s\n", e.what());
        return 1;
    }
    return failures == 0 ? 0 : 1;
}
