#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/error.hpp"
#include "engine/render/image_metrics.hpp"

using namespace lp;

TEST(ImageMetrics, RmseAndPsnrOfAKnownDifference) {
    ImageF a{2, 1, {0.5f, 0.5f, 0.5f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f}};
    ImageF b = a;
    EXPECT_EQ(compareHdr(a, b).rmse, 0.0);
    EXPECT_TRUE(std::isinf(compareHdr(a, b).psnr));
    b.rgba[0] += 0.1f;  // one channel of six off by 0.1: MSE = 0.01 / 6
    ImageError e = compareHdr(b, a);
    EXPECT_NEAR(e.rmse, std::sqrt(0.01 / 6.0), 1e-7);
    EXPECT_NEAR(e.psnr, 10.0 * std::log10(6.0 / 0.01), 1e-4);
    EXPECT_NEAR(e.maxAbs, 0.1, 1e-6);
    b.rgba[4] = NAN;
    EXPECT_EQ(compareHdr(b, a).nonFinite, 1u);
    ImageF c{1, 1, {0, 0, 0, 1}};
    EXPECT_THROW(compareHdr(a, c), Error);
}
