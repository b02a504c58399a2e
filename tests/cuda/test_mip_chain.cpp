// The CUDA mip-chain bloom (cuda/bloom_mip_chain.cu) against the CPU reference: on RGBA16F CUDA
// arrays (the passes' path: fp16 levels, as the GLSL path's RGBA16F mips, so against the
// reference's Storage::Half) and on fp32 device buffers (against Storage::Float), on sizes off its
// 32x16 / 64x32 tiles, with and without the one-block tail of small levels, with one level only
// (kernel <= 2, images narrower than two texels) and on images smaller than the chain. Skips where
// no CUDA device exists.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "cuda/post_cuda.hpp"
#include "engine/post/post_reference.hpp"
#include "tests/cuda/post_test_images.hpp"

using namespace lp;
using namespace lp::posttest;
using post::BloomMethod;
using post::BloomParams;
using post::Storage;

namespace {

BloomParams mipChain(int kernel, bool karis = true) {
    BloomParams p;
    p.kernel = kernel;
    p.method = BloomMethod::MipChain;
    p.strength = 0.5f;
    p.karis = karis;
    return p;
}

}  // namespace

// Bound: 4 fp16 ulps relative (4 / 1024; GLSL's mip chain is held to 8). The kernels and the
// reference round every level to fp16 alike; fp32 FMA contraction and summation order may flip a
// level's rounding by one ulp, which reaches the bloom diluted, plus the bloom's and the
// composite's own roundings.
TEST(CudaMipChain, HalfArraysMatchReferenceOnOddSizes) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    struct Case {
        int w, h;
        std::vector<int> kernels;
    };
    const Case cases[] = {
        {1301, 611, {2, 5, 25, 100}},  // 100: tile kernels for levels 1-2, the tail from level 3; 5: no tail
        {97, 45, {1, 5, 101}},         // the tail from level 1
        {64, 48, {5, 25, 101}},
        {33, 65, {5, 101}},
        {7, 3, {5, 101}},              // one level (3 / 2 = 1 row)
        {130, 1, {5, 101}},
        {1, 70, {5, 101}},
        {2, 2, {101}},
    };
    unsigned seed = 50;
    for (const Case& c : cases) {
        const ImageF hdr = randomHdr(c.w, c.h, seed++);
        for (int kernel : c.kernels)
            for (bool karis : {true, false}) {
                if (!karis && kernel != 101 && kernel != 100) continue;
                const BloomParams p = mipChain(kernel, karis);
                const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Half);
                const cuda::BloomAndComposite got = cuda::bloomCompositeOnHalfArrays(hdr, p);
                EXPECT_LE(maxRelError(got.bloom, bloom), 4.0 / 1024.0)
                    << c.w << "x" << c.h << " kernel " << kernel << " karis " << karis;
                EXPECT_LE(maxRelError(got.hdr, post::compositeBloom(hdr, bloom, p.strength)), 4.0 / 1024.0)
                    << c.w << "x" << c.h << " kernel " << kernel << " karis " << karis;
                if (kernel == 100 || kernel == 101) {  // the bloom alone (not in place): same bloom, HDR untouched
                    const cuda::BloomAndComposite alone = cuda::bloomCompositeOnHalfArrays(hdr, p, cuda::BloomBlur::Auto, false);
                    EXPECT_LE(maxRelError(alone.bloom, bloom), 4.0 / 1024.0) << c.w << "x" << c.h << " kernel " << kernel;
                    EXPECT_EQ(maxRelError(alone.hdr, hdr), 0.0) << c.w << "x" << c.h << " kernel " << kernel;
                }
            }
    }
}

// The other paths the benchmark measures: without the one-block tail (every level its own
// launches, down to 1 x 1), with every level from 1 on in the tail, and without programmatic
// dependent launches; on an odd size and on one smaller than a tile; same bound as above.
TEST(CudaMipChain, EveryTuningMatchesReference) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    cuda::MipChainTuning noTail, allTail, noOverlap, noTailNoOverlap;
    noTail.tailTexels = 0;
    allTail.tailTexels = 1 << 30;
    noOverlap.programmaticLaunch = false;
    noTailNoOverlap.tailTexels = 0;
    noTailNoOverlap.programmaticLaunch = false;
    unsigned seed = 70;
    for (auto [w, h] : {std::pair{700, 390}, std::pair{29, 13}})
        for (int kernel : {5, 100}) {
            const ImageF hdr = randomHdr(w, h, seed++);
            const BloomParams p = mipChain(kernel);
            const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Half);
            const ImageF composite = post::compositeBloom(hdr, bloom, p.strength);
            for (const auto& [name, tuning] :
                 {std::pair{"default", cuda::MipChainTuning{}}, std::pair{"no tail", noTail},
                  std::pair{"all in the tail", allTail}, std::pair{"no overlap", noOverlap},
                  std::pair{"no tail, no overlap", noTailNoOverlap}}) {
                const cuda::BloomAndComposite got = cuda::bloomCompositeOnHalfArrays(hdr, p, cuda::BloomBlur::Auto, true, tuning);
                EXPECT_LE(maxRelError(got.bloom, bloom), 4.0 / 1024.0) << name << " " << w << "x" << h << " kernel " << kernel;
                EXPECT_LE(maxRelError(got.hdr, composite), 4.0 / 1024.0) << name << " " << w << "x" << h << " kernel " << kernel;
            }
        }
}

// fp32 device buffers, the fused bloom + composite in place, on an image of many tiles: the bloom
// within 1e-5 of the fp32 reference, the composite within 1 fp16 ulp (as the other CUDA tests).
TEST(CudaMipChain, BuffersMatchFp32ReferenceOnALargeImage) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    const ImageF hdr = randomHdr(1301, 611, 60);
    for (int kernel : {5, 100}) {
        const BloomParams p = mipChain(kernel);
        const ImageF bloom = post::bloomBuffer(hdr, p, Storage::Float);
        const cuda::BloomAndComposite got = cuda::bloomCompositeOnDevice(hdr, p);
        EXPECT_LE(maxRelError(got.bloom, bloom), 1e-5) << "kernel " << kernel;
        EXPECT_LE(maxRelError(got.hdr, post::compositeBloom(hdr, bloom, p.strength)), 1.0 / 1024.0) << "kernel " << kernel;
        EXPECT_LE(maxRelError(cuda::bloomOnDevice(hdr, p), bloom), 1e-5) << "kernel " << kernel << " bloom alone";
    }
}

// A constant image stays constant through the fp16 chain (every filter has unit sum): c = 3
// bright-passes to 2; bloom 2 and composite 3 + 0.5 * 2 = 4 within 1 fp16 ulp.
TEST(CudaMipChain, ConstantImageStaysConstantOnHalfArrays) {
    if (skipWithoutDevice()) GTEST_SKIP() << "no CUDA device: " << cuda::postDeviceProblem();
    ImageF hdr;
    hdr.width = 300;
    hdr.height = 170;
    hdr.rgba.assign(size_t(hdr.width) * size_t(hdr.height) * 4, 3.0f);
    for (int kernel : {5, 100}) {
        const cuda::BloomAndComposite got = cuda::bloomCompositeOnHalfArrays(hdr, mipChain(kernel));
        for (size_t i = 0; i < got.bloom.rgba.size(); i += 4) {
            ASSERT_NEAR(got.bloom.rgba[i + 1], 2.0, 2.0 / 1024.0) << "kernel " << kernel << " texel " << i / 4;
            ASSERT_NEAR(got.hdr.rgba[i + 1], 4.0, 4.0 / 1024.0) << "kernel " << kernel << " texel " << i / 4;
        }
    }
}
