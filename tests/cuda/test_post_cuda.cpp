// The CUDA kernels against the CPU reference. Every test SKIPS (with the reason) where no
// CUDA device exists, e.g. CI machines with the toolkit but no GPU. Kernel tests use device
// buffers (no GL); the interop tests make their own headless GL context and need it on NVIDIA.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "cuda/post_cuda.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/post/post_reference.hpp"

using namespace lp;
using post::BloomMethod;
using post::BloomParams;
using post::Storage;

namespace {

constexpr int kW = 64, kH = 48;

ImageF makeImage(int w, int h, float fill = 0.0f) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(size_t(w) * size_t(h) * 4, fill);
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 1.0f;
    return img;
}

ImageF randomHdr(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> base(0.0f, 2.0f), bright(2.0f, 40.0f), pick(0.0f, 1.0f);
    ImageF img = makeImage(kW, kH);
    for (size_t i = 0; i < img.rgba.size(); ++i)
        if (i % 4 != 3) img.rgba[i] = post::roundToHalf(pick(rng) < 0.1f ? bright(rng) : base(rng));
    return img;
}

double maxRelError(const ImageF& got, const ImageF& ref, double floor = 1e-3) {
    double worst = 0.0;
    for (size_t i = 0; i < got.rgba.size(); ++i)
        if (i % 4 != 3)
            worst = std::max(worst, std::fabs(double(got.rgba[i]) - double(ref.rgba[i])) / (std::fabs(double(ref.rgba[i])) + floor));
    return worst;
}

bool skipWithoutDevice() {
    const std::string problem = cuda::postDeviceProblem();
    if (problem.empty()) return false;
    std::printf("  no CUDA device here (%s): CUDA tests skipped\n", problem.c_str());
    return true;
}

BloomParams params(int kernel, BloomMethod m) {
    BloomParams p;
    p.kernel = kernel;
    p.method = m;
    p.strength = 0.5f;
    return p;
}

}  // namespace

// Bound: fp32 device buffers vs the fp32 CPU reference (same per-texel code, post_math.hpp):
// |d| <= 1e-5 (|ref| + 1e-3), for kernels 1, 5, 25, 101 and both methods (FMA contraction and
// summation order are the only differences).
TEST(CudaKernels, BloomMatchesCpuReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    const ImageF hdr = randomHdr(1);
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain})
        for (int kernel : {1, 5, 25, 101}) {
            const BloomParams p = params(kernel, m);
            const ImageF gpu = cuda::bloomOnDevice(hdr, p);
            const ImageF ref = post::bloomBuffer(hdr, p, Storage::Float);
            EXPECT_LE(maxRelError(gpu, ref), 1e-5) << "kernel " << kernel << " method " << int(m);
        }
}

// Composite and toon: fp32 device results vs the reference's fp16-stored HDR: 1 fp16 ulp relative.
TEST(CudaKernels, CompositeAndToonMatchCpuReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    const ImageF hdr = randomHdr(2);
    const BloomParams p = params(25, BloomMethod::Separable);
    const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Float);
    EXPECT_LE(maxRelError(cuda::compositeOnDevice(hdr, bloom, p.strength), post::compositeBloom(hdr, bloom, p.strength)),
              1.0 / 1024.0);
    ImageF position = makeImage(kW, kH), normal = makeImage(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            float* q = &position.rgba[(size_t(y) * kW + size_t(x)) * 4];
            q[2] = x < 32 ? -2.0f : -4.0f;
            normal.rgba[(size_t(y) * kW + size_t(x)) * 4 + 2] = 1.0f;
        }
    post::ToonParams t;
    const ImageF gpu = cuda::toonOnDevice(hdr, position, normal, t);
    const ImageF ref = post::toonImage(hdr, position, normal, t);
    for (int y = 0; y < kH; ++y)  // outline exactly on columns 31 and 32 (see the GLSL test)
        for (int x = 0; x < kW; ++x)
            EXPECT_EQ(gpu.rgba[(size_t(y) * kW + size_t(x)) * 4] == 0.0f, x == 31 || x == 32) << x << "," << y;
    int mismatched = 0;  // texels on a band boundary may fall either way (float ordering)
    for (size_t i = 0; i < gpu.rgba.size(); ++i)
        if (i % 4 != 3 && std::fabs(gpu.rgba[i] - ref.rgba[i]) > (std::fabs(ref.rgba[i]) + 1e-4) / 1024.0) ++mismatched;
    EXPECT_LE(mismatched, kW * kH / 100);
}

// +Inf and NaN texels: every output of the device bloom is finite.
TEST(CudaKernels, InfAndNanDoNotSpread) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    ImageF hdr = randomHdr(3);
    hdr.rgba[(size_t(20) * kW + 20) * 4] = std::numeric_limits<float>::infinity();
    hdr.rgba[(size_t(30) * kW + 40) * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain}) {
        const ImageF b = cuda::bloomOnDevice(hdr, params(25, m));
        for (float v : b.rgba) ASSERT_TRUE(std::isfinite(v));
    }
}

// Interop: the GL textures path (register once, map, surfaces) matches the CPU reference within
// 2 fp16 ulps, and a texture is registered once however often it is used.
TEST(CudaInterop, BloomOnGlTexturesMatchesReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
    const ImageF hdrIn = randomHdr(4);
    const BloomParams p = params(25, BloomMethod::Separable);
    gl::Texture hdr = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.hdr");
    gl::Texture bloom = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.bloom");
    glTextureSubImage2D(hdr.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
    cuda::PostInterop interop;
    for (int i = 0; i < 3; ++i) interop.bloom(hdr.id(), bloom.id(), kW, kH, p);
    EXPECT_EQ(interop.registeredCount(), 2);
    ImageF got = makeImage(kW, kH);
    glGetTextureImage(bloom.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(got.rgba.size() * 4), got.rgba.data());
    EXPECT_LE(maxRelError(got, post::bloomBuffer(hdrIn, p, Storage::Float)), 2.0 / 1024.0);
}

// The tiled blur at sizes that are not multiples of its 32 x 64 tiles, on images narrower than
// its radius (kernel 101 on 7 px): same clamped borders, same bound as above.
TEST(CudaKernels, TiledBlurMatchesReferenceOnOddSizes) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> v(0.0f, 8.0f);
    for (auto [w, h] : {std::pair{7, 3}, std::pair{33, 65}, std::pair{130, 1}, std::pair{1, 70}}) {
        ImageF hdr = makeImage(w, h);
        for (size_t i = 0; i < hdr.rgba.size(); ++i)
            if (i % 4 != 3) hdr.rgba[i] = post::roundToHalf(v(rng));
        for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain})
            for (int kernel : {1, 5, 101}) {
                const BloomParams p = params(kernel, m);
                EXPECT_LE(maxRelError(cuda::bloomOnDevice(hdr, p), post::bloomBuffer(hdr, p, Storage::Float)), 1e-5)
                    << w << "x" << h << " kernel " << kernel << " method " << int(m);
            }
    }
}

// The fused bloom + composite (what the passes run when bloom_composite follows bloom) gives the
// bloom buffer of bloomBuffer (1e-5 relative) and the composite of compositeBloom (1 fp16 ulp).
TEST(CudaKernels, FusedBloomCompositeMatchesSeparateSteps) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    const ImageF hdr = randomHdr(6);
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain}) {
        const BloomParams p = params(25, m);
        const cuda::BloomAndComposite got = cuda::bloomCompositeOnDevice(hdr, p);
        const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Float);
        EXPECT_LE(maxRelError(got.bloom, bloom), 1e-5) << "method " << int(m);
        EXPECT_LE(maxRelError(got.hdr, post::compositeBloom(hdr, bloom, p.strength)), 1.0 / 1024.0) << int(m);
    }
}

// The fused path on GL textures: the bloom texture as bloom() writes it, the HDR texture as
// composite() would leave it, within 2 fp16 ulps of the CPU reference.
TEST(CudaInterop, FusedBloomCompositeOnGlTexturesMatchesReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
    const ImageF hdrIn = randomHdr(7);
    const BloomParams p = params(25, BloomMethod::Separable);
    gl::Texture hdr = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.hdr");
    gl::Texture bloom = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.bloom");
    glTextureSubImage2D(hdr.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
    cuda::PostInterop interop;
    interop.bloomComposite(hdr.id(), bloom.id(), kW, kH, p);
    ImageF gotBloom = makeImage(kW, kH), gotHdr = makeImage(kW, kH);
    glGetTextureImage(bloom.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotBloom.rgba.size() * 4), gotBloom.rgba.data());
    glGetTextureImage(hdr.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotHdr.rgba.size() * 4), gotHdr.rgba.data());
    const ImageF refBloom = post::bloomBuffer(hdrIn, p, Storage::Float);
    EXPECT_LE(maxRelError(gotBloom, refBloom), 2.0 / 1024.0);
    EXPECT_LE(maxRelError(gotHdr, post::compositeBloom(hdrIn, refBloom, p.strength)), 2.0 / 1024.0);
}

// Shared textures (external memory, no map/unmap): bloom + composite and toon on textures the
// shared-texture source made match the CPU reference within 2 fp16 ulps, nothing is registered for
// mapping, and each call reports that it ran shared. Skips, with the reason, where GL and CUDA
// cannot share memory (no GL_EXT_memory_object_fd, or the start-up round trip disagreed).
TEST(CudaSharedTextures, BloomCompositeAndToonMatchReferenceWithoutMapping) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
    cuda::PostInterop interop;
    const std::string problem = interop.useSharedTextures();
    if (!problem.empty()) GTEST_SKIP() << "shared textures unavailable here: " << problem;
    fg::ExternalTextureSource* source = interop.sharedTextureSource();
    ASSERT_NE(source, nullptr);
    const ImageF hdrIn = randomHdr(8);
    const BloomParams p = params(5, BloomMethod::Separable);
    std::shared_ptr<fg::ExternalTexture> hdr = source->make({kW, kH, GL_RGBA16F}, "test.shared_hdr");
    std::shared_ptr<fg::ExternalTexture> bloom = source->make({kW, kH, GL_RGBA16F}, "test.shared_bloom");
    ASSERT_TRUE(hdr && bloom);
    glTextureSubImage2D(hdr->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
    const cuda::PostTiming t = interop.bloomComposite(hdr->texture(), bloom->texture(), kW, kH, p);
    EXPECT_TRUE(t.shared);
    EXPECT_EQ(interop.registeredCount(), 0);
    ImageF gotBloom = makeImage(kW, kH), gotHdr = makeImage(kW, kH);
    glGetTextureImage(bloom->texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotBloom.rgba.size() * 4), gotBloom.rgba.data());
    glGetTextureImage(hdr->texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotHdr.rgba.size() * 4), gotHdr.rgba.data());
    const ImageF refBloom = post::bloomBuffer(hdrIn, p, Storage::Float);
    EXPECT_LE(maxRelError(gotBloom, refBloom), 2.0 / 1024.0);
    EXPECT_LE(maxRelError(gotHdr, post::compositeBloom(hdrIn, refBloom, p.strength)), 2.0 / 1024.0);

    // Toon in place on a shared HDR texture, reading shared RGBA32F G-buffer targets.
    ImageF position = makeImage(kW, kH), normal = makeImage(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            position.rgba[(size_t(y) * kW + size_t(x)) * 4 + 2] = x < 32 ? -2.0f : -4.0f;
            normal.rgba[(size_t(y) * kW + size_t(x)) * 4 + 2] = 1.0f;
        }
    std::shared_ptr<fg::ExternalTexture> pos = source->make({kW, kH, GL_RGBA32F}, "test.shared_position");
    std::shared_ptr<fg::ExternalTexture> nrm = source->make({kW, kH, GL_RGBA32F}, "test.shared_normal");
    glTextureSubImage2D(hdr->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
    glTextureSubImage2D(pos->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, position.rgba.data());
    glTextureSubImage2D(nrm->texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, normal.rgba.data());
    post::ToonParams tp;
    EXPECT_TRUE(interop.toon(hdr->texture(), pos->texture(), nrm->texture(), kW, kH, tp).shared);
    ImageF gotToon = makeImage(kW, kH);
    glGetTextureImage(hdr->texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotToon.rgba.size() * 4), gotToon.rgba.data());
    const ImageF refToon = post::toonImage(hdrIn, position, normal, tp);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            EXPECT_EQ(gotToon.rgba[(size_t(y) * kW + size_t(x)) * 4] == 0.0f, x == 31 || x == 32) << x << "," << y;
    int mismatched = 0;
    for (size_t i = 0; i < gotToon.rgba.size(); ++i)
        if (i % 4 != 3 && std::fabs(gotToon.rgba[i] - refToon.rgba[i]) > (std::fabs(refToon.rgba[i]) + 1e-3) * 2.0 / 1024.0)
            ++mismatched;
    EXPECT_LE(mismatched, kW * kH / 100);
    EXPECT_EQ(interop.registeredCount(), 0);
}
