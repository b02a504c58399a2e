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

TEST(ImageMetrics, AMaskLimitsEveryFigureToItsPixels) {
    // Pixel 0 agrees, pixel 1 (outside the mask) is far off, pixel 2 has twice the reference's light.
    ImageF ref{3, 1, {0.2f, 0.2f, 0.2f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 0.5f, 0.5f, 0.5f, 1.0f}};
    ImageF img = ref;
    img.rgba[4] = img.rgba[5] = img.rgba[6] = 9.0f;
    img.rgba[8] = img.rgba[9] = img.rgba[10] = 1.0f;
    const std::vector<uint8_t> mask{1, 0, 1};
    const ImageError e = compareHdr(img, ref, &mask);
    EXPECT_EQ(e.pixels, 2u);
    EXPECT_NEAR(e.rmse, std::sqrt(3 * 0.25 / 6.0), 1e-6);  // only pixel 2's three channels differ, by 0.5
    EXPECT_NEAR(e.maxAbs, 0.5, 1e-6);
    // Relative: sum |dY| / sum Y_ref = 0.5 / (0.2 + 0.5) (luminance weights sum to 1 on grey).
    EXPECT_NEAR(e.relativeError, 0.5 / 0.7, 1e-6);
    // Unmasked, pixel 1 dominates.
    EXPECT_NEAR(compareHdr(img, ref).relativeError, (8.0 + 0.5) / (0.2 + 1.0 + 0.5), 1e-6);
    EXPECT_EQ(compareHdr(img, ref).pixels, 3u);
    const std::vector<uint8_t> wrongSize{1, 1};
    EXPECT_THROW(compareHdr(img, ref, &wrongSize), Error);
}
