// shaders/common/tonemap.glsl's ACES against Filament's, in double (tests/gl/tonemap_reference.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/tonemap_reference.hpp"

using namespace lp;
using namespace lp::test;

namespace {

// Grey levels 1e-4 .. 1e4 (log spaced) and colours: every hue in 15-degree steps at four
// saturations, each at nine brightnesses 2^-8 .. 2^8 (the red modifier and the glow act on
// saturated colours, the desaturations on all of them).
std::vector<glm::vec4> acesInputs(size_t* greyCount) {
    std::vector<glm::vec4> in;
    for (int i = 0; i <= 800; ++i) {
        const float g = float(std::pow(10.0, -4.0 + 8.0 * i / 800.0));
        in.push_back(glm::vec4(g, g, g, 0.0f));
    }
    *greyCount = in.size();
    for (int hueStep = 0; hueStep < 24; ++hueStep)
        for (double saturation : {0.25, 0.5, 0.8, 1.0})
            for (int ev = -8; ev <= 8; ev += 2) {
                const double h = hueStep / 24.0 * 6.0;  // HSV with value 1, then scaled
                const double f = h - std::floor(h);
                const double p = 1.0 - saturation, q = 1.0 - saturation * f, t = 1.0 - saturation * (1.0 - f);
                glm::dvec3 rgb;
                switch (int(h) % 6) {
                    case 0: rgb = {1, t, p}; break;
                    case 1: rgb = {q, 1, p}; break;
                    case 2: rgb = {p, 1, t}; break;
                    case 3: rgb = {p, q, 1}; break;
                    case 4: rgb = {t, p, 1}; break;
                    default: rgb = {1, p, q}; break;
                }
                in.push_back(glm::vec4(glm::vec3(rgb * std::exp2(double(ev))), 0.0f));
            }
    return in;
}

}  // namespace

// --tonemap aces is Filament's ACES (ToneMapper.cpp's ACESToneMapper inside its colour grading's
// Rec.2020 working space): the GLSL curve against the double reference at 801 grey levels 1e-4 .. 1e4
// and 864 colours (24 hues x 4 saturations x 9 brightnesses 2^-8 .. 2^8). Bound: |GLSL - double|
// <= 2e-5 per channel (float32 through six 3x3 matrices, atan2 and pow; 1.0e-6 on llvmpipe; an 8-bit
// step is 3.9e-3). Also: 0 -> 0 exactly; non-decreasing over the grey levels within float rounding
// (2e-6, where the curve has flattened near its 0.994 ceiling); middle grey 0.18 -> 0.1080 linear.
TEST(ShaderToneMap, AcesIsFilamentsAces) {
    size_t greys = 0;
    std::vector<glm::vec4> in = acesInputs(&greys);
    in.push_back(glm::vec4(0.0f));
    in.push_back(glm::vec4(0.18f, 0.18f, 0.18f, 0.0f));
    auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(applyToneMap(x.xyz, 1), 0.0);", in);
    double worst = 0.0;
    size_t worstAt = 0;
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::dvec3 ref = test::filamentAcesRef(glm::dvec3(in[i]));
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(out[i][c])) << "input " << i;
            const double err = std::abs(double(out[i][c]) - ref[c]);
            if (err > worst) worst = err, worstAt = i;
            EXPECT_NEAR(out[i][c], ref[c], 2e-5) << "input (" << in[i].x << ", " << in[i].y << ", " << in[i].z
                                                 << ") channel " << c;
        }
    }
    std::printf("  aces: worst |GLSL - Filament double| = %.3g at (%g, %g, %g)\n", worst, in[worstAt].x,
                in[worstAt].y, in[worstAt].z);
    for (size_t i = 1; i < greys; ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_GE(out[i][c], out[i - 1][c] - 2e-6f) << "grey " << in[i].x << " channel " << c;
    const glm::vec4 zero = out[in.size() - 2], grey = out[in.size() - 1];
    EXPECT_EQ(zero.x, 0.0f);
    EXPECT_EQ(zero.y, 0.0f);
    EXPECT_EQ(zero.z, 0.0f);
    const double greyRef = test::filamentAcesRef(glm::dvec3(0.18)).y;
    std::printf("  aces(0.18) = %.5f (Filament double %.5f), aces-legacy(0.18) = %.5f\n", grey.y, greyRef,
                test::acesLegacyRef(glm::dvec3(0.18)).y);
    EXPECT_NEAR(grey.y, greyRef, 2e-5);
    EXPECT_NEAR(greyRef, 0.1080, 5e-5);
}

// aces-legacy keeps the previous `aces` curve exactly (Narkowicz's fit without its 0.6 input scale,
// Filament's FILMIC): within 2e-5 of the double formula at 201 grey levels 1e-3 .. 1e3. At middle
// grey it is 0.98 EV brighter than Filament's ACES: aces reaches aces-legacy(0.18) = 0.2669 at an input
// between 2^0.95 and 2^1.0 times 0.18 (bisection on the double reference).
TEST(ShaderToneMap, AcesLegacyIsNarkowiczWithoutTheInputScale) {
    std::vector<glm::vec4> in;
    for (int i = 0; i <= 200; ++i) {
        const float g = float(std::pow(10.0, -3.0 + 6.0 * i / 200.0));
        in.push_back(glm::vec4(g, g, g, 0.0f));
    }
    auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(applyToneMap(x.xyz, 4), 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out[i][c], test::acesLegacyRef(glm::dvec3(in[i]))[c], 2e-5) << "grey " << in[i].x;
    const double legacyGrey = test::acesLegacyRef(glm::dvec3(0.18)).y;
    EXPECT_NEAR(legacyGrey, 0.2669, 5e-5);
    double lo = 0.18, hi = 0.18 * 4.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = std::sqrt(lo * hi);
        (test::filamentAcesRef(glm::dvec3(mid)).y < legacyGrey ? lo : hi) = mid;
    }
    const double ev = std::log2(lo / 0.18);
    std::printf("  aces-legacy(0.18) = aces(0.18 x 2^%.3f)\n", ev);
    EXPECT_GT(ev, 0.95);
    EXPECT_LT(ev, 1.0);
}
