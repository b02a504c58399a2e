// The GL tests' image comparison says which texel differs (tests/gl/render_fixture.hpp).
#include <cmath>
#include <limits>

#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {
ImageF grey(int w, int h, float v) { return ImageF{w, h, std::vector<float>(size_t(w) * h * 4, v)}; }
}  // namespace

TEST(ImagesNear, NamesTheFirstDifferingTexelTheCountAndTheLargestError) {
    const ImageF a = grey(3, 2, 0.5f);
    ImageF b = a;
    b.rgba[(1 * 3 + 2) * 4 + 1] = 0.75f;  // texel (2, 1), green
    b.rgba[(0 * 3 + 1) * 4 + 3] = 0.52f;  // texel (1, 0), alpha: within the tolerance
    EXPECT_TRUE(test::imagesNear(a, a, 0.0f));
    EXPECT_TRUE(test::imagesNear(a, b, 0.3f));
    const testing::AssertionResult r = test::imagesNear(a, b, 0.01f, "b against a");
    ASSERT_FALSE(r);
    const std::string message = r.message();
    EXPECT_NE(message.find("b against a: 2 of 24 values differ by more than 0.01"), std::string::npos) << message;
    EXPECT_NE(message.find("first at texel (1, 0) channel 3"), std::string::npos) << message;
    EXPECT_NE(message.find("largest error 0.25 at texel (2, 1) channel 1"), std::string::npos) << message;
}

TEST(ImagesNear, NanNeverMatchesAndSizesMustAgree) {
    const ImageF a = grey(2, 2, 1.0f);
    ImageF b = a;
    b.rgba[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(test::imagesNear(a, b, 1e9f));
    EXPECT_FALSE(test::imagesNear(b, b, 0.0f));
    const testing::AssertionResult r = test::imagesNear(a, grey(2, 3, 1.0f), 0.0f);
    ASSERT_FALSE(r);
    EXPECT_NE(std::string(r.message()).find("sizes differ (2x2 and 2x3)"), std::string::npos) << r.message();
}
