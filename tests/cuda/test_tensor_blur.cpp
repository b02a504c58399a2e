// The separable bloom blur on the tensor cores (cuda/bloom.cu, tensorBlurKernel) against the CPU
// reference, at every chunk count it instantiates, on sizes that are not multiples of its 64-column
// stripes and 16-row chunks, and on an image large enough for segments of several chunks. Skips
// where no CUDA device exists; the tensor-core tests also where the device has no mma.sync (sm < 80).
#include <gtest/gtest.h>
#include <cuda_runtime_api.h>

#include <cmath>
#include <random>
#include <string>

#include "cuda/post_cuda.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/post/post_reference.hpp"
#include "tests/cuda/post_test_images.hpp"

using namespace lp;
using namespace lp::posttest;
using cuda::BloomBlur;
using post::BloomMethod;
using post::BloomParams;
using post::Storage;

namespace {

BloomParams separable(int kernel) {
    BloomParams p;
    p.kernel = kernel;
    p.method = BloomMethod::Separable;
    p.strength = 0.5f;
    return p;
}

int computeCapabilityMajor() {
    int device = 0, major = 0;
    if (cudaGetDevice(&device) != cudaSuccess || cudaDeviceGetAttribute(&major, cudaDevAttrComputeCapabilityMajor, device) != cudaSuccess)
        return 0;
    return major;
}

// Why the tensor-core blur cannot be tested here, or empty.
std::string tensorBlurProblem() {
    const std::string device = cuda::postDeviceProblem();
    if (!device.empty()) return "no CUDA device: " + device;
    if (!cuda::bloomBlurUsesTensorCores(101, BloomBlur::TensorCore))
        return "no tensor-core blur on this device (compute capability " + std::to_string(computeCapabilityMajor()) + ".x)";
    return {};
}

}  // namespace

// Auto takes the tensor cores on sm_80+ from kernel 87 (radius 43, where they were measured faster
// on the H100) and the direct blur below; TensorCore wherever the device has them; Direct never.
TEST(CudaTensorBlur, AutoChoosesTheTensorCoresWhereTheDeviceHasThem) {
    const std::string device = cuda::postDeviceProblem();
    if (!device.empty()) GTEST_SKIP() << "no CUDA device: " << device;
    const bool sm80 = computeCapabilityMajor() >= 8;
    for (int kernel : {1, 5, 25, 51, 85, 87, 100, 101}) {
        EXPECT_EQ(cuda::bloomBlurUsesTensorCores(kernel, BloomBlur::Auto), sm80 && kernel >= 87) << kernel;
        EXPECT_EQ(cuda::bloomBlurUsesTensorCores(kernel, BloomBlur::TensorCore), sm80) << kernel;
        EXPECT_FALSE(cuda::bloomBlurUsesTensorCores(kernel, BloomBlur::Direct)) << kernel;
    }
}

// Every instantiation (2, 4, 6, 8 input chunks: radius <= 8, 24, 40, 50) and radii between them,
// on odd sizes (narrower and shorter than a stripe, a chunk and the radius; one row; one column):
// the tensor-core blur and the direct blur both within 1e-5 of the fp32 reference.
TEST(CudaTensorBlur, MatchesReferenceAtEveryChunkCountOnOddSizes) {
    const std::string problem = tensorBlurProblem();
    if (!problem.empty()) GTEST_SKIP() << problem;
    unsigned seed = 10;
    for (auto [w, h] : {std::pair{7, 3}, std::pair{33, 65}, std::pair{130, 1}, std::pair{1, 70}, std::pair{97, 45}}) {
        const ImageF hdr = randomHdr(w, h, seed++);
        for (int kernel : {1, 5, 17, 25, 33, 49, 51, 81, 101}) {
            const BloomParams p = separable(kernel);
            const ImageF ref = post::bloomBuffer(hdr, p, Storage::Float);
            EXPECT_LE(maxRelError(cuda::bloomOnDevice(hdr, p, BloomBlur::TensorCore), ref), 1e-5)
                << w << "x" << h << " kernel " << kernel << " tensor cores";
            EXPECT_LE(maxRelError(cuda::bloomOnDevice(hdr, p, BloomBlur::Direct), ref), 1e-5)
                << w << "x" << h << " kernel " << kernel << " direct";
        }
    }
}

// An image of many stripes and segments of several 16-row chunks each (the window slides across
// chunk after chunk), through the fused bloom + composite as the passes run it: the bloom within
// 1e-5 and the composite within 1 fp16 ulp of the reference, at kernel 25 and 101 (radius 50).
TEST(CudaTensorBlur, FusedCompositeMatchesReferenceOnALargeImage) {
    const std::string problem = tensorBlurProblem();
    if (!problem.empty()) GTEST_SKIP() << problem;
    const ImageF hdr = randomHdr(1301, 611, 20);
    for (int kernel : {25, 101}) {
        const BloomParams p = separable(kernel);
        const cuda::BloomAndComposite got = cuda::bloomCompositeOnDevice(hdr, p, BloomBlur::TensorCore);
        const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Float);
        EXPECT_LE(maxRelError(got.bloom, bloom), 1e-5) << "kernel " << kernel;
        EXPECT_LE(maxRelError(got.hdr, post::compositeBloom(hdr, bloom, p.strength)), 1.0 / 1024.0) << "kernel " << kernel;
    }
}

// Extremes: texels at the largest half (65504, where fp16 hi parts must not overflow), tiny values
// (fp16 subnormals and below), zeros and a highlight ceiling above every texel.
TEST(CudaTensorBlur, MatchesReferenceAtTheEndsOfTheHalfRange) {
    const std::string problem = tensorBlurProblem();
    if (!problem.empty()) GTEST_SKIP() << problem;
    ImageF hdr = randomHdr(80, 40, 30);
    for (size_t i = 0; i < hdr.rgba.size(); i += 4) {
        const size_t texel = i / 4;
        if (texel % 7 == 0) hdr.rgba[i] = post::kHalfMax;
        if (texel % 5 == 0)  // a few ulps above the threshold: the soft knee lets ~2e-5 through (fp16 subnormal)
            for (int c = 0; c < 3; ++c) hdr.rgba[i + size_t(c)] = 1.0f + 1.2e-7f * float(texel % 4);
        if (texel % 3 == 0) hdr.rgba[i + 2] = 0.0f;
    }
    BloomParams p = separable(101);
    p.highlight = 1e6f;
    p.threshold = 1.0f;
    p.knee = 1e-4f;
    const ImageF ref = post::bloomBuffer(hdr, p, Storage::Float);
    EXPECT_LE(maxRelError(cuda::bloomOnDevice(hdr, p, BloomBlur::TensorCore), ref), 1e-5);
}

// On GL textures (RGBA16F, what the passes run): the fp16-output variant, texels and intermediate
// in fp16 and only the weights split, through the fused bloom + composite in place. Its bound: one
// fp16 rounding of the texel, one of the intermediate and the store's own, 3 half-ulps relative,
// checked as 1.6 / 1024 (the interop tests allow 2), on a size with partial stripes and chunks and
// on one with segments of several chunks.
TEST(CudaTensorBlur, HalfTexturesMatchReferenceWithinOneAndAHalfUlps) {
    const std::string problem = tensorBlurProblem();
    if (!problem.empty()) GTEST_SKIP() << problem;
    std::unique_ptr<gl::GpuContext> ctx = gl::createHeadlessContext();
    if (!ctx->isNvidia()) GTEST_SKIP() << "the headless GL context is not NVIDIA (" << ctx->info().renderer << ")";
    cuda::PostInterop interop;
    unsigned seed = 40;
    for (auto [w, h] : {std::pair{97, 45}, std::pair{700, 900}}) {
        const ImageF hdrIn = randomHdr(w, h, seed++);
        for (int kernel : {3, 5, 25, 51, 101}) {
            const BloomParams p = separable(kernel);
            gl::Texture hdr = gl::makeTexture2D(GL_RGBA16F, w, h, 1, "test.hdr");
            gl::Texture bloom = gl::makeTexture2D(GL_RGBA16F, w, h, 1, "test.bloom");
            glTextureSubImage2D(hdr.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, hdrIn.rgba.data());
            interop.bloomComposite(hdr.id(), bloom.id(), w, h, p);
            ImageF gotBloom = hdrIn, gotHdr = hdrIn;
            glGetTextureImage(bloom.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotBloom.rgba.size() * 4), gotBloom.rgba.data());
            glGetTextureImage(hdr.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(gotHdr.rgba.size() * 4), gotHdr.rgba.data());
            const ImageF refBloom = post::bloomBuffer(hdrIn, p, Storage::Float);
            EXPECT_LE(maxRelError(gotBloom, refBloom), 1.6 / 1024.0) << w << "x" << h << " kernel " << kernel;
            EXPECT_LE(maxRelError(gotHdr, post::compositeBloom(hdrIn, refBloom, p.strength)), 2.0 / 1024.0)
                << w << "x" << h << " kernel " << kernel;
            interop.forgetTexture(hdr.id());
            interop.forgetTexture(bloom.id());
        }
    }
}
