// The CUDA kernels against the CPU reference. Every test SKIPS (with the reason) where no
// CUDA device exists, e.g. CI machines with the toolkit but no GPU. Kernel tests use device
// buffers (no GL); the interop tests make their own headless GL context and need it on NVIDIA.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#ifdef LIGHTPASS_TEST_LINKS_VULKAN
#include <vulkan/vulkan.h>
#endif

#include "cuda/post_cuda.hpp"
#include "cuda/vulkan_semaphores.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/post/post_reference.hpp"
#include "tests/cuda/post_test_images.hpp"

using namespace lp;
using namespace lp::posttest;
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
    const ImageF hdr = randomHdr(kW, kH, 1);
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
    const ImageF hdr = randomHdr(kW, kH, 2);
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
    ImageF hdr = randomHdr(kW, kH, 3);
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
    const ImageF hdrIn = randomHdr(kW, kH, 4);
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
    const ImageF hdr = randomHdr(kW, kH, 6);
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain}) {
        const BloomParams p = params(25, m);
        const cuda::BloomAndComposite got = cuda::bloomCompositeOnDevice(hdr, p);
        const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Float);
        EXPECT_LE(maxRelError(got.bloom, bloom), 1e-5) << "method " << int(m);
        EXPECT_LE(maxRelError(got.hdr, post::compositeBloom(hdr, bloom, p.strength)), 1.0 / 1024.0) << int(m);
    }
}

// The fused path on GL textures: the bloom texture as bloom() writes it, the HDR texture as
// composite() would leave it, within 2 fp16 ulps of the CPU reference (separable); the mip chain,
// whose levels are fp16 there as in GLSL, within 4 of the reference's fp16 chain (see
// tests/cuda/test_mip_chain.cpp).
TEST(CudaInterop, FusedBloomCompositeOnGlTexturesMatchesReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
    const ImageF hdrIn = randomHdr(kW, kH, 7);
    cuda::PostInterop interop;
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain})
        for (int kernel : {25, 101}) {
            const BloomParams p = params(kernel, m);
            gl::Texture hdr = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.hdr");
            gl::Texture bloom = gl::makeTexture2D(GL_RGBA16F, kW, kH, 1, "test.bloom");
            glTextureSubImage2D(hdr.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
            interop.bloomComposite(hdr.id(), bloom.id(), kW, kH, p);
            ImageF gotBloom = makeImage(kW, kH), gotHdr = makeImage(kW, kH);
            glGetTextureImage(bloom.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotBloom.rgba.size() * 4), gotBloom.rgba.data());
            glGetTextureImage(hdr.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotHdr.rgba.size() * 4), gotHdr.rgba.data());
            const bool mip = m == BloomMethod::MipChain;
            const ImageF refBloom = post::bloomBuffer(hdrIn, p, mip ? Storage::Half : Storage::Float);
            const double bound = (mip ? 4.0 : 2.0) / 1024.0;
            EXPECT_LE(maxRelError(gotBloom, refBloom), bound) << "method " << int(m) << " kernel " << kernel;
            EXPECT_LE(maxRelError(gotHdr, post::compositeBloom(hdrIn, refBloom, p.strength)), bound)
                << "method " << int(m) << " kernel " << kernel;
            interop.forgetTexture(hdr.id());
            interop.forgetTexture(bloom.id());
        }
}

// Shared textures (external memory, no map/unmap), under each ordering: Vulkan semaphores (GL
// signals, CUDA waits, runs and signals, GL waits: no host wait) and host waits (the fallback).
// Skips, with the reason, where GL and CUDA cannot share memory (no GL_EXT_memory_object_fd, or the
// start-up round trip disagreed) or, for the semaphores, where Vulkan cannot make them here.
class CudaSharedTextures : public ::testing::TestWithParam<cuda::SharedSync> {
protected:
    void SetUp() override {
        if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
        ctx = gl::createHeadlessContext();
        if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
        interop = std::make_unique<cuda::PostInterop>();
        const std::string problem = interop->useSharedTextures(GetParam());
        if (!problem.empty()) GTEST_SKIP() << "shared textures unavailable here: " << problem;
        if (interop->sharedSync() != GetParam())
            GTEST_SKIP() << "Vulkan semaphores unavailable here: " << interop->semaphoreProblem();
        source = interop->sharedTextureSource();
        ASSERT_NE(source, nullptr);
    }
    void TearDown() override {
        interop.reset();
        ctx.reset();
    }
    std::shared_ptr<fg::ExternalTexture> make(GLenum format, const char* label) {
        std::shared_ptr<fg::ExternalTexture> t = source->make({kW, kH, format}, label);
        EXPECT_TRUE(t) << label;
        return t;
    }
    static void upload(const fg::ExternalTexture& t, const ImageF& img) {
        glTextureSubImage2D(t.texture(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, img.rgba.data());
    }
    // GL's view through a GPU copy into a fresh texture: glGetTextureImage on the shared texture
    // itself, once it was read back and then uploaded again, returns that upload on the H100 (driver
    // 580) however the hand-over is ordered, not what CUDA wrote since (CUDA's own view, readShared,
    // has it), so a second read-back of the same texture cannot be trusted.
    static ImageF download(const fg::ExternalTexture& t, GLenum format = GL_RGBA16F) {
        gl::Texture copy = gl::makeTexture2D(format, kW, kH, 1, "test.read_back");
        glCopyImageSubData(t.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, copy.id(), GL_TEXTURE_2D, 0, 0, 0, 0, kW, kH, 1);
        ImageF img = makeImage(kW, kH);
        glGetTextureImage(copy.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgba.size() * 4), img.rgba.data());
        return img;
    }
    std::unique_ptr<gl::GpuContext> ctx;
    std::unique_ptr<cuda::PostInterop> interop;
    fg::ExternalTextureSource* source = nullptr;
};

// Texels where two images differ (all four channels; exact: the values are fp16-representable).
int differingTexels(const ImageF& a, const ImageF& b) {
    int n = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        if (a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2] ||
            a.rgba[i + 3] != b.rgba[i + 3])
            ++n;
    return n;
}

// Bloom + composite on shared textures match the CPU reference within 2 fp16 ulps, nothing is
// registered for mapping, and each call reports how it ran.
TEST_P(CudaSharedTextures, BloomCompositeMatchesReferenceWithoutMapping) {
    const ImageF hdrIn = randomHdr(kW, kH, 8);
    const BloomParams p = params(5, BloomMethod::Separable);
    auto hdr = make(GL_RGBA16F, "test.shared_hdr"), bloom = make(GL_RGBA16F, "test.shared_bloom");
    ASSERT_TRUE(hdr && bloom);
    upload(*hdr, hdrIn);
    for (int i = 0; i < 2; ++i) {  // twice: the second call hands over again through the same semaphores
        if (i == 1) upload(*hdr, hdrIn);
        const cuda::PostTiming t = interop->bloomComposite(hdr->texture(), bloom->texture(), kW, kH, p);
        EXPECT_TRUE(t.shared);
        EXPECT_EQ(t.gpuOrdered, GetParam() == cuda::SharedSync::Semaphores);
        const ImageF refBloom = post::bloomBuffer(hdrIn, p, Storage::Float);
        EXPECT_LE(maxRelError(download(*bloom), refBloom), 2.0 / 1024.0) << "call " << i;
        EXPECT_LE(maxRelError(download(*hdr), post::compositeBloom(hdrIn, refBloom, p.strength)), 2.0 / 1024.0)
            << "call " << i;
    }
    EXPECT_EQ(interop->registeredCount(), 0);
}

// Toon in place on a shared HDR texture, reading shared RGBA32F G-buffer targets, after a bloom +
// composite on the same HDR texture (as in a frame): the depth step's outline on exactly columns 31
// and 32, the ramp against the CPU reference; then what CUDA reads of the inputs equals what GL
// uploaded, and CUDA's view of the result equals GL's read-back (which of the hand-overs failed,
// when the outline is wrong).
TEST_P(CudaSharedTextures, ToonMatchesReferenceWithoutMapping) {
    const ImageF hdrIn = randomHdr(kW, kH, 9);
    ImageF position = makeImage(kW, kH), normal = makeImage(kW, kH);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            position.rgba[(size_t(y) * kW + size_t(x)) * 4 + 2] = x < 32 ? -2.0f : -4.0f;
            normal.rgba[(size_t(y) * kW + size_t(x)) * 4 + 2] = 1.0f;
        }
    auto hdr = make(GL_RGBA16F, "test.shared_hdr"), bloom = make(GL_RGBA16F, "test.shared_bloom");
    ASSERT_TRUE(hdr && bloom);
    upload(*hdr, hdrIn);
    interop->bloomComposite(hdr->texture(), bloom->texture(), kW, kH, params(5, BloomMethod::Separable));
    (void)download(*hdr);
    auto pos = make(GL_RGBA32F, "test.shared_position");
    auto nrm = make(GL_RGBA32F, "test.shared_normal");
    ASSERT_TRUE(pos && nrm);
    upload(*hdr, hdrIn);
    upload(*pos, position);
    upload(*nrm, normal);
    post::ToonParams tp;
    const cuda::PostTiming t = interop->toon(hdr->texture(), pos->texture(), nrm->texture(), kW, kH, tp);
    EXPECT_TRUE(t.shared);
    EXPECT_EQ(t.gpuOrdered, GetParam() == cuda::SharedSync::Semaphores);
    const ImageF gotToon = download(*hdr);
    ImageF direct = makeImage(kW, kH);  // what the note in download() is about, shown, not asserted
    glGetTextureImage(hdr->texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(direct.rgba.size() * 4), direct.rgba.data());
    if (const int stale = differingTexels(direct, gotToon))
        std::printf("  note: glGetTextureImage of the shared texture itself differs from its GPU copy in %d of %d "
                    "texels (%d equal the upload before the toon)\n",
                    stale, kW * kH, kW * kH - differingTexels(direct, hdrIn));
    const ImageF refToon = post::toonImage(hdrIn, position, normal, tp);
    int outlineWrong = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            outlineWrong += (gotToon.rgba[(size_t(y) * kW + size_t(x)) * 4] == 0.0f) != (x == 31 || x == 32);
    EXPECT_EQ(outlineWrong, 0) << "texels where the outline (columns 31 and 32 only) is wrong";
    int mismatched = 0;
    for (size_t i = 0; i < gotToon.rgba.size(); ++i)
        if (i % 4 != 3 && std::fabs(gotToon.rgba[i] - refToon.rgba[i]) > (std::fabs(refToon.rgba[i]) + 1e-3) * 2.0 / 1024.0)
            ++mismatched;
    EXPECT_LE(mismatched, kW * kH / 100);
    EXPECT_GT(differingTexels(gotToon, hdrIn), kW * kH / 2) << "GL reads back the toon's input, not its result";
    EXPECT_EQ(differingTexels(interop->readShared(hdr->texture(), GL_RGBA16F, kW, kH), gotToon), 0)
        << "CUDA's view of the toon result differs from GL's read-back";
    EXPECT_EQ(differingTexels(interop->readShared(pos->texture(), GL_RGBA32F, kW, kH), position), 0)
        << "position as CUDA reads it differs from GL's upload";
    EXPECT_EQ(differingTexels(interop->readShared(nrm->texture(), GL_RGBA32F, kW, kH), normal), 0)
        << "normal as CUDA reads it differs from GL's upload";
    EXPECT_EQ(interop->registeredCount(), 0);
}

// Many hand-overs in a row without a host wait keep GL and CUDA in step: each composite adds the
// bloom (1) onto the previous call's result, and halfway GL overwrites the HDR texture (100) between
// two CUDA calls, so a lost, early or late hand-over in either direction changes the final value
// (exact in fp16: 100 + 10).
TEST_P(CudaSharedTextures, RepeatedHandOversKeepOrder) {
    ImageF hdrIn = makeImage(kW, kH, 1.0f), bloomIn = makeImage(kW, kH, 1.0f);
    auto hdr = make(GL_RGBA16F, "test.shared_hdr"), bloom = make(GL_RGBA16F, "test.shared_bloom");
    ASSERT_TRUE(hdr && bloom);
    upload(*hdr, hdrIn);
    upload(*bloom, bloomIn);
    constexpr int kCalls = 20;
    for (int i = 0; i < kCalls; ++i) {
        if (i == kCalls / 2) {
            const float hundred[4] = {100.0f, 100.0f, 100.0f, 1.0f};
            glClearTexImage(hdr->texture(), 0, GL_RGBA, GL_FLOAT, hundred);
        }
        interop->composite(hdr->texture(), bloom->texture(), kW, kH, 1.0f);  // hdr += bloom
    }
    const ImageF got = download(*hdr);
    for (size_t i = 0; i < got.rgba.size(); i += 4)
        ASSERT_EQ(got.rgba[i], 100.0f + float(kCalls / 2)) << "texel " << i / 4;
}

// The Vulkan side alone (runs everywhere, CUDA or not): the loader opens at run time or says why,
// and a device UUID no GPU has is refused with a reason, never a crash, so the interop falls back.
TEST(VulkanSemaphores, LoaderOpensAtRunTimeOrSaysWhy) {
    const std::string problem = cuda::vulkanLoaderProblem();
    if (!problem.empty()) GTEST_SKIP() << problem;
    EXPECT_GE(cuda::vulkanLoaderVersion(), 1u << 22);  // 1.0 in Vulkan's version encoding
#ifdef LIGHTPASS_TEST_LINKS_VULKAN
    uint32_t linked = 0;  // the loader this binary links (and its bundle carries) is the one opened
    ASSERT_EQ(vkEnumerateInstanceVersion(&linked), VK_SUCCESS);
    EXPECT_EQ(cuda::vulkanLoaderVersion(), linked);
#endif
}

TEST(VulkanSemaphores, UnknownDeviceUuidIsRefusedWithAReason) {
    cuda::DeviceUuid nobody;
    nobody.fill(0xEE);
    std::string problem;
    std::unique_ptr<cuda::VulkanSemaphoreDevice> device = cuda::VulkanSemaphoreDevice::open(nobody, problem);
    EXPECT_EQ(device, nullptr);
    EXPECT_FALSE(problem.empty());
    EXPECT_EQ(problem.find('\n'), std::string::npos) << "one line";
}

INSTANTIATE_TEST_SUITE_P(Sync, CudaSharedTextures,
                         ::testing::Values(cuda::SharedSync::Semaphores, cuda::SharedSync::HostWaits),
                         [](const ::testing::TestParamInfo<cuda::SharedSync>& i) {
                             return std::string(i.param == cuda::SharedSync::Semaphores ? "VulkanSemaphores"
                                                                                         : "HostWaits");
                         });
