// Position rebuilt from depth, standard vs reversed-Z, against the double-precision position: the
// depth is rounded to float as a D32F buffer stores it, then the GLSL rebuilds eye z.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/gl/gl_fixture.hpp"

using lp::test::runGlsl;

namespace {
const double kNear = 0.05, kFar = 500.0;

// Window depth in [0, 1] of eye distance z, computed in double and stored as float (D32F).
float standardDepth(double z) {
    double ndc = ((kFar + kNear) / (kFar - kNear)) - (2.0 * kFar * kNear / (kFar - kNear)) / z;
    return float(ndc * 0.5 + 0.5);
}
float reversedDepth(double z) { return float(kNear * (kFar - z) / (z * (kFar - kNear))); }

struct Errors {
    double nearRel = 0, farRel = 0;
};

Errors measure(bool reversed) {
    std::vector<glm::vec4> in;
    std::vector<double> truth;
    for (int i = 0; i <= 400; ++i) {  // distances from near to far, log-spaced
        double z = kNear * std::pow(kFar / kNear, i / 400.0);
        truth.push_back(z);
        in.push_back(glm::vec4(reversed ? reversedDepth(z) : standardDepth(z), 0, 0, 0));
    }
    char body[256];
    std::snprintf(body, sizeof body, "return vec4(%s(x.x, %.9f, %.9f));",
                  reversed ? "eyeZFromReversedDepth" : "eyeZFromStandardDepth", kNear, kFar);
    auto out = runGlsl({"common/depth_reconstruct.glsl"}, body, in);
    Errors e;
    for (size_t i = 0; i < truth.size(); ++i) {
        EXPECT_TRUE(std::isfinite(out[i].x));
        double rel = std::abs(-double(out[i].x) - truth[i]) / truth[i];
        (truth[i] < 1.0 ? e.nearRel : e.farRel) = std::max(truth[i] < 1.0 ? e.nearRel : e.farRel, rel);
    }
    return e;
}
}  // namespace

// near 0.05, far 500, D32F. Standard depth crowds the far range into floats just below 1: its far
// relative error (measured 5e-4 on llvmpipe) is orders of magnitude worse than reversed-Z's, whose
// dense floats near 0 hold the far range (measured 1.3e-7). Bounds: standard near <= 1e-5, far
// <= 5e-3; reversed-Z <= 1e-5 near and far; and standard/reversed far error >= 10.
TEST(DepthReconstruct, ReversedZKeepsPrecisionToTheFarPlane) {
    Errors standard = measure(false), reversed = measure(true);
    std::printf("  standard depth:  near rel %.3g, far rel %.3g\n  reversed-Z:      near rel %.3g, far rel %.3g\n",
                standard.nearRel, standard.farRel, reversed.nearRel, reversed.farRel);
    EXPECT_LT(standard.nearRel, 1e-5);
    EXPECT_LT(standard.farRel, 5e-3);
    EXPECT_LT(reversed.nearRel, 1e-5);
    EXPECT_LT(reversed.farRel, 1e-5);
    EXPECT_GT(standard.farRel, 10.0 * reversed.farRel);
}

TEST(DepthReconstruct, EyePositionFromZ) {
    // The centre pixel lies on the view axis; the top-right corner at (aspect, 1) * tan * distance.
    auto out = runGlsl({"common/depth_reconstruct.glsl"}, "return vec4(eyePositionFromZ(x.xy, -2.0, 0.5, 1.5), 0.0);",
                       {glm::vec4(0.5f, 0.5f, 0, 0), glm::vec4(1.0f, 1.0f, 0, 0)});
    EXPECT_NEAR(out[0].x, 0.0f, 1e-6f);
    EXPECT_NEAR(out[0].y, 0.0f, 1e-6f);
    EXPECT_NEAR(out[1].x, 1.5f, 1e-6f);
    EXPECT_NEAR(out[1].y, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(out[1].z, -2.0f);
}
