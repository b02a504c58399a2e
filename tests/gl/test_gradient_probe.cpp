// engine/gl/gradient_probe: what textureGrad reads on this driver, in compute and in the raster. The
// isotropic compute sample is GLSL's definition on any conformant driver; the anisotropic ones are
// reported, and the raster's level model must be one of the three the resolve knows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "engine/gl/gradient_probe.hpp"
#include "engine/gl/handles.hpp"

using namespace lp;

TEST(GradientProbe, IsotropicGradientsPickTheirLevelAndTheModelIsKnown) {
    const gl::ShaderLibrary shaders;
    const long liveBefore = gl::liveObjectCount();
    const gl::GradientSampling g = gl::probeGradientSampling(shaders);
    EXPECT_EQ(gl::liveObjectCount(), liveBefore);
    std::printf("compute: isotropic %.3f (2), anisotropic %.3f (2) and %.3f (1) -> %s; raster: lambda log2 3 read %.3f, "
                "ratio 32 read %.3f -> levels %s, ratio %s; varying gradients: summed error per pixel %.3f, per quad "
                "%.3f -> %s\n",
                g.computeIsotropic, g.computeSquare, g.computeStretched,
                g.computeFollowsGradients ? "follows the gradients" : "ignores the gradients", g.rasterFractional,
                g.rasterStretched, gl::anisotropicLevelsName(g.rasterLevels), g.rasterClampsRatio ? "clamped" : "not clamped",
                g.rasterPerPixelError, g.rasterPerQuadError, g.rasterLevelPerQuad ? "per quad" : "per pixel");
    EXPECT_NEAR(g.computeIsotropic, 2.0, 0.1);
    if (!g.anisotropyAvailable) return;
    // Whichever model, it explains what the raster read: within a tenth of a level.
    const double lambda = std::log2(3.0);
    const double expectedFractional = g.rasterLevels == gl::AnisotropicLevels::Floor     ? std::floor(lambda)
                                      : g.rasterLevels == gl::AnisotropicLevels::Nearest ? std::round(lambda)
                                                                                          : lambda;
    EXPECT_NEAR(g.rasterFractional, expectedFractional, 0.1);
    EXPECT_NEAR(g.rasterStretched, g.rasterClampsRatio ? 3.0 : 1.0, 0.1);
    // Where compute ignores the gradients (the only case the resolve uses the model), the chosen
    // footprint (per pixel or per quad) predicts the 64 pixels' levels within a tenth of a level on
    // average; the other misses by more (at pixel (1, 1) they are log2 3 levels apart). Where compute
    // follows them the model is unused, and a GPU's own anisotropic footprint need not fit it (the
    // H100's: summed error 74 per quad, 94 per pixel).
    if (!g.computeFollowsGradients) {
        const double chosen = g.rasterLevelPerQuad ? g.rasterPerQuadError : g.rasterPerPixelError;
        const double other = g.rasterLevelPerQuad ? g.rasterPerPixelError : g.rasterPerQuadError;
        EXPECT_LT(chosen, 0.1 * 64);
        EXPECT_GT(other, chosen + 1.0);
    } else {
        EXPECT_NEAR(g.computeSquare, 2.0, 0.25);
        EXPECT_NEAR(g.computeStretched, 1.0, 0.25);
    }
}
