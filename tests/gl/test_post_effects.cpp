// Bloom and toon: the GLSL compute passes on the real driver against the CPU reference
// (engine/post/post_reference.cpp), plus analytic properties. Images are small (64x48) for llvmpipe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/gl/shader.hpp"
#include "engine/post/post_math.hpp"
#include "engine/post/post_reference.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/primitives.hpp"
#include "passes/bloom_pass.hpp"
#include "passes/toon_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;
using post::BloomMethod;
using post::BloomParams;
using post::Storage;

namespace {

constexpr int kW = 64, kH = 48;
// One fp16 ulp (2^-10 relative) per store in series: each stored intermediate may round one way on
// the GPU and the other on the CPU (float ordering, FMA, and the driver's float -> half conversion,
// which need not round to nearest even). The separable path stores 4 times in series (bright,
// horizontal, vertical, composite): 4 ulps. The mip chain stores up to 2 * levels + 1 times; its
// bound is 8 ulps (2^-7); measured on llvmpipe: 2.8e-3 separable, 3.9e-3 mip chain.
constexpr double kHalfRel = 1.0 / 256.0;
constexpr double kMipRel = 1.0 / 128.0;

ImageF makeImage(int w, int h, float fill = 0.0f) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(size_t(w) * size_t(h) * 4, fill);
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 1.0f;
    return img;
}

float& at(ImageF& img, int x, int y, int c) { return img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + size_t(c)]; }
float at(const ImageF& img, int x, int y, int c) {
    return img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + size_t(c)];
}
void setRgb(ImageF& img, int x, int y, float v) {
    for (int c = 0; c < 3; ++c) at(img, x, y, c) = v;
}

// HDR-like test image: mostly [0, 2], some texels up to 40 (what bloom picks up). Rounded to half,
// as it would be in the RGBA16F HDR buffer.
ImageF randomHdr(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> base(0.0f, 2.0f), bright(2.0f, 40.0f), pick(0.0f, 1.0f);
    ImageF img = makeImage(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) at(img, x, y, c) = post::roundToHalf(pick(rng) < 0.1f ? bright(rng) : base(rng));
    return img;
}

gl::Texture upload(const ImageF& img, GLenum format, const char* name) {
    gl::Texture t = gl::makeTexture2D(format, img.width, img.height, 1, name);
    glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, img.rgba.data());
    return t;
}

ImageF download(const gl::Texture& t) {
    ImageF img = makeImage(t.width, t.height);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // after image stores (outside a graph, the caller orders)
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgba.size() * sizeof(float)), img.rgba.data());
    return img;
}

struct GlslBloom {
    ImageF bloom, hdr;
};

GlslBloom runGlslBloom(const ImageF& hdrIn, const BloomParams& p) {
    gl::ShaderLibrary shaders;
    BloomPass state;
    gl::Texture hdr = upload(hdrIn, GL_RGBA16F, "test.hdr");
    gl::Texture bloom = gl::makeTexture2D(GL_RGBA16F, hdrIn.width, hdrIn.height, 1, "test.bloom");
    // The scratch the graph would lend from its pool.
    const BloomScratchDescs d = bloomScratchDescs(p, hdrIn.width, hdrIn.height);
    auto make = [](const fg::TextureDesc& desc, const char* name) {
        return desc.width > 0 ? gl::makeTexture2D(desc.format, desc.width, desc.height, desc.levels, name) : gl::Texture();
    };
    gl::Texture bright = make(d.bright, "test.bright"), blurH = make(d.blurH, "test.blur_h"), mips = make(d.mips, "test.mips");
    runBloomGlsl(state, shaders, {bright.id(), blurH.id(), mips.id()}, hdr.id(), bloom.id(), hdrIn.width, hdrIn.height, p);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);  // what the graph derives
    runBloomCompositeGlsl(state, shaders, hdr.id(), bloom.id(), hdrIn.width, hdrIn.height, p.strength);
    gl::checkErrors("bloom test");
    return {download(bloom), download(hdr)};
}

// Largest |got - ref| / (|ref| + floor) over RGB, and whether every value is finite.
double maxRelError(const ImageF& got, const ImageF& ref, double floor = 1e-3) {
    double worst = 0.0;
    for (size_t i = 0; i < got.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        worst = std::max(worst, std::fabs(double(got.rgba[i]) - double(ref.rgba[i])) / (std::fabs(double(ref.rgba[i])) + floor));
    }
    return worst;
}
double maxAbsError(const ImageF& got, const ImageF& ref) {
    double worst = 0.0;
    for (size_t i = 0; i < got.rgba.size(); ++i)
        if (i % 4 != 3) worst = std::max(worst, std::fabs(double(got.rgba[i]) - double(ref.rgba[i])));
    return worst;
}
bool allFinite(const ImageF& img) {
    for (float v : img.rgba)
        if (!std::isfinite(v)) return false;
    return true;
}

BloomParams bloomParams(int kernel, BloomMethod method = BloomMethod::Separable) {
    BloomParams p;
    p.method = method;
    p.kernel = kernel;
    p.threshold = 1.0f;
    p.knee = 0.5f;
    p.strength = 0.5f;
    return p;
}

}  // namespace

// Bound: for kernels 1, 5, 25, 101 the GLSL bloom buffer and composited HDR differ from the CPU
// reference (fp16 intermediates) by at most 4 fp16 ulps relative, |d| <= (|ref| + 1e-3) / 256;
// the same for the fragment-stage blur (bloom_blur.frag).
TEST(PostBloomGlsl, SeparableMatchesCpuReferenceForEveryKernelSize) {
    const ImageF hdr = randomHdr(kW, kH, 1);
    for (int kernel : {1, 5, 25, 101}) {
        const BloomParams p = bloomParams(kernel);
        GlslBloom gpu = runGlslBloom(hdr, p);
        ImageF refBloom = post::bloomBuffer(hdr, p, Storage::Half);
        ImageF refHdr = post::compositeBloom(hdr, refBloom, p.strength);
        const double eb = maxRelError(gpu.bloom, refBloom), eh = maxRelError(gpu.hdr, refHdr);
        std::printf("  separable kernel %3d: max rel error bloom %.2e, hdr %.2e; max abs bloom %.2e, hdr %.2e\n", kernel,
                    eb, eh, maxAbsError(gpu.bloom, refBloom), maxAbsError(gpu.hdr, refHdr));
        EXPECT_LE(eb, kHalfRel) << "kernel " << kernel;
        EXPECT_LE(eh, kHalfRel) << "kernel " << kernel;
        BloomParams frag = p;  // the fragment-stage blur (benchmark variant): same taps, same bound
        frag.fragmentBlur = true;
        EXPECT_LE(maxRelError(runGlslBloom(hdr, frag).bloom, refBloom), kHalfRel) << "fragment, kernel " << kernel;
    }
}

// Clamp-to-edge: a bright left column (bright-passed value v, threshold 0) blurred horizontally
// gives v * sum_{i >= x} w_i at column x <= r (every tap left of the image reads column 0), and 0
// beyond r; zero padding would give v * w_x. Bound: 4 fp16 ulps relative, and exactly 0 beyond r.
TEST(PostBloomGlsl, BordersAreClampToEdge) {
    const int kernel = 25;
    ImageF hdr = makeImage(kW, kH);
    for (int y = 0; y < kH; ++y) setRgb(hdr, 0, y, 5.0f);
    BloomParams p = bloomParams(kernel);
    p.threshold = 0.0f;
    p.knee = 0.0f;
    GlslBloom gpu = runGlslBloom(hdr, p);
    const std::vector<float> w = post::gaussianWeights(kernel);
    const int r = int(w.size()) - 1;
    for (int x = 0; x < kW; ++x) {
        double expect = 0.0;
        for (int i = x; i <= r; ++i) expect += 5.0 * double(w[size_t(i)]);
        for (int y : {0, kH / 2, kH - 1}) {
            if (x > r) EXPECT_EQ(at(gpu.bloom, x, y, 0), 0.0f) << x;
            else EXPECT_NEAR(at(gpu.bloom, x, y, 0), expect, (expect + 1e-3) * kHalfRel) << "x " << x << " y " << y;
        }
    }
}

// One +Inf and one NaN texel: every output is finite; the NaN texel acts as 0 (the result equals
// the reference with it zeroed, 4 ulps); the +Inf texel enters the blur as `highlight`, so a
// neighbour grows by at most strength * highlight * w0^2, and beyond the kernel radius the image
// equals the one without the Inf texel (4 ulps).
TEST(PostBloomGlsl, InfAndNanTexelsDoNotSpread) {
    const int kernel = 5;
    ImageF hdr = randomHdr(kW, kH, 2);
    ImageF clean = hdr;
    setRgb(hdr, 20, 20, std::numeric_limits<float>::infinity());
    setRgb(hdr, 44, 30, std::numeric_limits<float>::quiet_NaN());
    setRgb(clean, 20, 20, 0.0f);
    setRgb(clean, 44, 30, 0.0f);
    BloomParams p = bloomParams(kernel);
    p.highlight = 100.0f;
    GlslBloom gpu = runGlslBloom(hdr, p);
    ASSERT_TRUE(allFinite(gpu.bloom));
    ASSERT_TRUE(allFinite(gpu.hdr));
    const ImageF refClean = post::compositeBloom(clean, post::bloomBuffer(clean, p, Storage::Half), p.strength);
    const std::vector<float> w = post::gaussianWeights(kernel);
    const int r = int(w.size()) - 1;
    const double maxGain = p.strength * p.highlight * double(w[0]) * double(w[0]);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) {
                const double got = at(gpu.hdr, x, y, c), ref = at(refClean, x, y, c);
                const bool nearInf = std::abs(x - 20) <= r && std::abs(y - 20) <= r;
                if (x == 20 && y == 20) {
                    EXPECT_EQ(got, 65504.0) << "+Inf is clamped to the largest half";
                } else if (nearInf) {
                    EXPECT_LE(got, ref + maxGain + (ref + 1e-3) * kHalfRel) << x << "," << y;
                } else {
                    EXPECT_NEAR(got, ref, (std::fabs(ref) + 1e-3) * kHalfRel) << x << "," << y;
                }
            }
}

// A constant image c = 3 (threshold 1, knee 0.5: bright-passed to exactly 2) stays constant through
// the blur at every kernel size and both methods. Bound: 1 fp16 ulp (2^-10 relative) on the bloom
// buffer (2) and on the composite (3 + 0.5 * 2 = 4).
TEST(PostBloomGlsl, ConstantImageStaysConstant) {
    const ImageF hdr = makeImage(kW, kH, 3.0f);
    const double bright = post::brightPass({3, 3, 3}, 1.0f, 0.5f, 1000.0f).r;
    ASSERT_NEAR(bright, 2.0, 1e-5);
    for (BloomMethod m : {BloomMethod::Separable, BloomMethod::MipChain})
        for (int kernel : {1, 5, 25, 101}) {
            GlslBloom gpu = runGlslBloom(hdr, bloomParams(kernel, m));
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    ASSERT_NEAR(at(gpu.bloom, x, y, 1), bright, bright / 1024.0) << kernel << " at " << x << "," << y;
                    ASSERT_NEAR(at(gpu.hdr, x, y, 1), 3.0 + 0.5 * bright, 4.0 / 1024.0) << kernel;
                }
        }
}

// Bound: the GLSL mip chain (Jimenez 2014) matches the CPU reference within 8 fp16 ulps relative
// (2^-7, see kMipRel); kernels 5, 25, 101 (3, 5 and 5 levels on 64x48); Karis on and off.
TEST(PostBloomGlsl, MipChainMatchesCpuReference) {
    const ImageF hdr = randomHdr(kW, kH, 3);
    for (bool karis : {true, false})
        for (int kernel : {5, 25, 101}) {
            BloomParams p = bloomParams(kernel, BloomMethod::MipChain);
            p.karis = karis;
            GlslBloom gpu = runGlslBloom(hdr, p);
            ImageF ref = post::bloomBuffer(hdr, p, Storage::Half);
            const double e = maxRelError(gpu.bloom, ref);
            std::printf("  mip chain kernel %3d karis %d: max rel error %.2e, abs %.2e\n", kernel, int(karis), e,
                        maxAbsError(gpu.bloom, ref));
            EXPECT_LE(e, kMipRel) << "kernel " << kernel;
        }
}

// Energy: with levels at least 8 texels wide, the mip chain keeps the bright pass's total (sum over
// texels) of a centred blob within 1% (the filters have unit sum and are mean-preserving over the
// stride-2 phases). Clamp-to-edge on tiny levels replicates the dark border: with 5 levels on 64x64
// (coarsest 2x2) the CPU reference keeps 96%. Karis averaging cuts a lone firefly's bloom energy
// by more than half.
TEST(PostBloomGlsl, MipChainKeepsEnergyAndKarisTamesFireflies) {
    const int w = 64, h = 64;
    ImageF blob = makeImage(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double d2 = (x - 31.5) * (x - 31.5) + (y - 31.5) * (y - 31.5);
            setRgb(blob, x, y, post::roundToHalf(float(8.0 * std::exp(-d2 / (2.0 * 9.0)))));
        }
    BloomParams p = bloomParams(5, BloomMethod::MipChain);  // 3 levels: 32, 16, 8 texels wide
    p.threshold = 0.0f;
    p.knee = 0.0f;
    p.karis = false;  // Karis weighting deliberately loses energy at bright peaks
    auto total = [](const ImageF& img) {
        double s = 0.0;
        for (size_t i = 0; i < img.rgba.size(); i += 4) s += img.rgba[i];
        return s;
    };
    const double brightTotal = total(post::brightPassImage(blob, p, Storage::Float));
    const double bloomTotal = total(runGlslBloom(blob, p).bloom);
    const double cpuTotal = total(post::bloomBuffer(blob, p, Storage::Float));
    std::printf("  mip chain energy: bloom / bright = %.4f (GLSL), %.4f (CPU)\n", bloomTotal / brightTotal, cpuTotal / brightTotal);
    EXPECT_NEAR(bloomTotal / brightTotal, 1.0, 0.01);
    EXPECT_NEAR(cpuTotal / brightTotal, 1.0, 0.01);

    ImageF firefly = makeImage(w, h, 0.5f);
    setRgb(firefly, 30, 30, 1000.0f);
    p.threshold = 1.0f;
    p.karis = true;
    const double withKaris = total(runGlslBloom(firefly, p).bloom);
    p.karis = false;
    const double without = total(runGlslBloom(firefly, p).bloom);
    std::printf("  firefly bloom energy: Karis %.1f, plain %.1f\n", withKaris, without);
    EXPECT_LT(withKaris, 0.5 * without);
}

namespace {

struct ToonInputs {
    ImageF hdr, position, normal;
};

// Covered everywhere, eye depth 2 left of column `step` and 4 from it on, normals facing the camera.
ToonInputs depthStep(int step) {
    ToonInputs in{makeImage(kW, kH, 0.5f), makeImage(kW, kH), makeImage(kW, kH)};
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            at(in.position, x, y, 2) = x < step ? -2.0f : -4.0f;
            at(in.position, x, y, 3) = 1.0f;
            at(in.normal, x, y, 2) = 1.0f;
        }
    return in;
}

ImageF runGlslToon(const ToonInputs& in, const post::ToonParams& p) {
    gl::ShaderLibrary shaders;
    ToonPass state;
    gl::Texture hdr = upload(in.hdr, GL_RGBA16F, "test.hdr");
    gl::Texture pos = upload(in.position, GL_RGBA32F, "test.position");
    gl::Texture nrm = upload(in.normal, GL_RGBA32F, "test.normal");
    // The toon reads coverage from the G-buffer depth: 1 (far plane) where position.w = 0.
    ImageF depthImage = makeImage(in.position.width, in.position.height);
    for (int y = 0; y < depthImage.height; ++y)
        for (int x = 0; x < depthImage.width; ++x) at(depthImage, x, y, 0) = at(in.position, x, y, 3) > 0.0f ? 0.5f : 1.0f;
    gl::Texture depth = upload(depthImage, GL_R32F, "test.depth");
    ToonGBufferTextures g;
    g.depth = depth.id();
    g.normal = nrm.id();
    g.position = pos.id();
    runToonGlsl(state, shaders, hdr.id(), g, in.hdr.width, in.hdr.height, p);
    gl::checkErrors("toon test");
    return download(hdr);
}

}  // namespace

// A depth step 2 -> 4 at column 32: the depth edge reads (4 - 2) / 4 = 0.5 > 0.2 on columns 31 and 32
// and exactly 0 elsewhere, so the outline is exactly columns 31 and 32 on every row, in the CPU
// reference and on the GPU (black there, never black elsewhere).
TEST(PostToonGlsl, EdgesExactlyOnADepthStep) {
    ToonInputs in = depthStep(32);
    post::ToonParams p;
    p.depthEdge = 0.2f;
    const std::vector<unsigned char> edges = post::toonEdges(in.position, in.normal, p);
    const ImageF gpu = runGlslToon(in, p);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool expected = x == 31 || x == 32;
            EXPECT_EQ(bool(edges[size_t(y) * kW + size_t(x)]), expected) << x << "," << y;
            EXPECT_EQ(at(gpu, x, y, 0) == 0.0f, expected) << x << "," << y;
        }
}

// Normal edges: a crease where the normal turns by 90 degrees reads sin(45) = 0.71 > 0.5 (outline);
// one of 30 degrees reads sin(15) = 0.26 < 0.5 (no outline), with the depth flat.
TEST(PostToonGlsl, NormalCreaseThresholdIsHalfAngleSine) {
    for (double degrees : {90.0, 30.0}) {
        ToonInputs in = depthStep(0);  // flat at depth 4
        const double a = degrees * M_PI / 180.0;
        for (int y = 0; y < kH; ++y)
            for (int x = 32; x < kW; ++x) {
                at(in.normal, x, y, 0) = float(std::sin(a));
                at(in.normal, x, y, 2) = float(std::cos(a));
            }
        post::ToonParams p;
        const ImageF gpu = runGlslToon(in, p);
        const std::vector<unsigned char> edges = post::toonEdges(in.position, in.normal, p);
        const bool expected = degrees > 60.0;
        EXPECT_EQ(bool(edges[size_t(10) * kW + 31]), expected) << degrees;
        EXPECT_EQ(at(gpu, 31, 10, 0) == 0.0f, expected) << degrees;
        EXPECT_EQ(at(gpu, 10, 10, 0) == 0.0f, false) << degrees;
    }
}

namespace {
// Outline mask of the GLSL toon (black texels of a grey image) and of the CPU reference; the first
// texel where they differ from `expected`, or "" where both match it everywhere.
std::string firstWrongOutline(const ToonInputs& in, const post::ToonParams& p, const std::function<bool(int, int)>& expected) {
    const ImageF gpu = runGlslToon(in, p);
    const std::vector<unsigned char> cpu = post::toonEdges(in.position, in.normal, p);
    for (int y = 0; y < in.hdr.height; ++y)
        for (int x = 0; x < in.hdr.width; ++x) {
            const bool want = expected(x, y);
            const bool glsl = gpu.rgba[(size_t(y) * size_t(gpu.width) + size_t(x)) * 4] == 0.0f;
            const bool reference = cpu[size_t(y) * size_t(in.hdr.width) + size_t(x)] != 0;
            if (glsl != want || reference != want) {
                char what[160];
                std::snprintf(what, sizeof what, "texel (%d, %d): outline expected %d, GLSL %d, CPU reference %d", x, y,
                              int(want), int(glsl), int(reference));
                return what;
            }
        }
    return "";
}
}  // namespace

// A depth step the relative size of the Cornell box's tall block against the back wall (front face
// at 1.07 m, wall at 1.36 m: (1.36 - 1.07) / 1.36 = 0.21), at 0.5, 5, 50 and 500 times that
// distance, across columns (the block's side) and across rows (its top), with the default
// thresholds: outlined exactly on the two texels either side of the step (the edge reads 0.21 on
// both, 0 elsewhere), on the GLSL path and in the CPU reference. The old measure (|Sobel(z)| / 8 / z
// over 0.2) read 0.14 and 0.11 there: no outline.
TEST(PostToonGlsl, RelativeDepthStepIsOutlinedAtAnyDistance) {
    const post::ToonParams defaults;
    for (double scale : {0.5, 5.0, 50.0, 500.0})
        for (bool rows : {false, true}) {
            ToonInputs in = depthStep(0);
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x)
                    at(in.position, x, y, 2) = -float(scale * ((rows ? y < 24 : x < 32) ? 1.07 : 1.36));
            const std::string wrong = firstWrongOutline(in, defaults, [&](int x, int y) {
                return rows ? (y == 23 || y == 24) : (x == 31 || x == 32);
            });
            EXPECT_EQ(wrong, "") << "step at " << scale << " x the Cornell distance, across " << (rows ? "rows" : "columns");
        }
}

// No false edges: a flat floor seen at a grazing angle, the camera 1 m above it looking 30 degrees
// down, the image's top edge 1 degree below the horizon (rows from 1 m to 33 m away), its G-buffer
// from the analytic ray-plane hits: no outline at the default threshold, nor at a tenth of it, on
// the GLSL path and in the CPU reference (the old measure, |Sobel(z)| / 8 / z over 0.2, outlined its
// four farthest rows).
TEST(PostToonGlsl, GrazingPlaneHasNoOutline) {
    ToonInputs in = depthStep(0);
    const double height = 1.0, pitch = 30.0 * M_PI / 180.0;
    // Vertical field of view such that the top row's ray meets the floor 1 degree below the horizon.
    const double topAngle = 1.0 * M_PI / 180.0, halfFov = pitch - topAngle;
    const double tanHalf = std::tan(halfFov), aspect = double(kW) / double(kH);
    const glm::dvec3 forward(0.0, -std::sin(pitch), -std::cos(pitch)), up(0.0, std::cos(pitch), -std::sin(pitch));
    const glm::dvec3 floorNormal(0.0, 1.0, 0.0);  // world: camera at (0, height, 0), floor y = 0
    double nearest = 1e30, farthest = 0.0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const double sx = ((x + 0.5) / kW * 2.0 - 1.0) * tanHalf * aspect, sy = (1.0 - (y + 0.5) / kH * 2.0) * tanHalf;
            const glm::dvec3 dir = forward + sy * up + sx * glm::dvec3(1.0, 0.0, 0.0);
            const double t = height / -dir.y;
            // Eye space: x right, y = up, -z = forward; the hit at t * (sx, sy, -1).
            at(in.position, x, y, 0) = float(t * sx);
            at(in.position, x, y, 1) = float(t * sy);
            at(in.position, x, y, 2) = float(-t);
            nearest = std::min(nearest, t);
            farthest = std::max(farthest, t);
            const glm::dvec3 n(0.0, glm::dot(floorNormal, up), -glm::dot(floorNormal, forward));  // eye-space normal
            at(in.normal, x, y, 0) = 0.0f;
            at(in.normal, x, y, 1) = float(n.y);
            at(in.normal, x, y, 2) = float(n.z);
        }
    EXPECT_LT(nearest, 1.1);
    EXPECT_GT(farthest, 30.0);
    for (float threshold : {post::ToonParams{}.depthEdge, post::ToonParams{}.depthEdge / 10.0f}) {
        post::ToonParams p;
        p.depthEdge = threshold;
        EXPECT_EQ(firstWrongOutline(in, p, [](int, int) { return false; }), "") << "threshold " << threshold;
    }
}

// The ramp: luminance L maps to the band centre tq = (band + 0.5) / levels of t = L / (1 + L),
// Lq = tq / (1 - tq). GPU vs CPU within 1 fp16 ulp relative, skipping texels whose t * levels lies
// within 1e-4 of a band boundary (float ordering may pick either band there); and the analytic
// value for L = 1, levels 4: t = 0.5 -> band 2 -> Lq = 0.625 / 0.375 = 5/3.
TEST(PostToonGlsl, RampMatchesCpuReference) {
    ToonInputs in = depthStep(0);
    in.hdr = randomHdr(kW, kH, 4);
    post::ToonParams p;
    p.levels = 4;
    const ImageF gpu = runGlslToon(in, p);
    const ImageF ref = post::toonImage(in.hdr, in.position, in.normal, p);
    int compared = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            post::Rgb c{at(in.hdr, x, y, 0), at(in.hdr, x, y, 1), at(in.hdr, x, y, 2)};
            const double L = post::luminance(c), tl = L / (1.0 + L) * p.levels;
            if (std::fabs(tl - std::round(tl)) < 1e-4) continue;
            ++compared;
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(at(gpu, x, y, k), at(ref, x, y, k), (std::fabs(at(ref, x, y, k)) + 1e-4) / 1024.0);
        }
    EXPECT_GT(compared, kW * kH * 9 / 10);
    const float k = post::toonScale(1.0f, 4);
    EXPECT_NEAR(k, 5.0 / 3.0, 1e-6);
}

namespace {
// A lit sphere against a plain background: small and fast on llvmpipe (no shadows, no environment).
Scene sphereScene() {
    Scene s;
    ModelInstance m;
    m.name = "sphere";
    m.primitive = "sphere";
    m.mesh = makeSphere(0.5f, 24, 12);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = glm::vec3(0.8f);
        mat.specular = glm::vec3(0.5f);
        mat.shininess = 64.0f;
    }
    s.models.push_back(std::move(m));
    DirectionalLight light;
    light.direction = glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
    light.intensity = 6.0f;
    light.castsShadows = false;
    s.directionalLights.push_back(light);
    s.camera.position = glm::vec3(0.0f, 0.0f, 2.5f);
    s.camera.target = glm::vec3(0.0f);
    s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 20.0f;
    return s;
}
}  // namespace

// End to end: a lit sphere with both effects (flags set as the CLI does) renders through the frame
// graph to a finite HDR buffer for both bloom methods; the toon silhouette makes some texels exactly
// black, and the bloom-only view shows a non-empty bloom buffer.
TEST(PostRenderer, SphereWithBloomAndToonIsFinite) {
    Scene scene = sphereScene();
    Renderer r(scene);
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.keepHdr = true;
    s.post.bloom = true;
    s.post.toon = true;
    s.post.bloomThreshold = 0.3f;
    s.post.backend = PostSettings::Backend::Glsl;
    for (auto method : {PostSettings::BloomMethod::Separable, PostSettings::BloomMethod::MipChain}) {
        s.post.bloomMethod = method;
        r.render(s);
        ImageF hdr = r.readHdr();
        int black = 0;
        for (size_t i = 0; i < hdr.rgba.size(); i += 4) {
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(hdr.rgba[i + size_t(c)]));
            black += hdr.rgba[i] == 0.0f && hdr.rgba[i + 1] == 0.0f && hdr.rgba[i + 2] == 0.0f;
        }
        EXPECT_GT(black, 0) << "toon outlines";
    }
    s.post.toon = false;
    s.post.bloomOnly = true;
    r.render(s);
    ImageF bloom = r.readHdr();
    double sum = 0.0;
    for (size_t i = 0; i < bloom.rgba.size(); i += 4) sum += bloom.rgba[i];
    EXPECT_GT(sum, 0.0);
}
