// The viewer's comparison with the path tracer (app/viewer_compare.hpp): its numbers and when it runs.
#include <gtest/gtest.h>

#include <cmath>

#include "app/viewer_compare.hpp"

using namespace lp;
using namespace lp::app;

namespace {
ImageF grey(int w, int h, float v) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(size_t(w) * size_t(h) * 4, v);
    return img;
}
}  // namespace

TEST(ViewerCompare, RelativeErrorIsOverLitPixelsAndExposureBringsTheTruthToGrey) {
    // Truth: half the pixels 0.5, half black; raster: 0.6 everywhere. The lit half is 20% too bright;
    // the black half is below the floor and not counted.
    ImageF truth = grey(4, 2, 0.5f), raster = grey(4, 2, 0.6f);
    for (size_t i = 0; i < 4 * 4; ++i) truth.rgba[i] = 0.0f;  // the first row
    const TruthComparisonStats s = compareWithTruth(raster, truth, 1e-3f);
    EXPECT_NEAR(s.meanRelativeError, 0.2, 1e-6);
    // RMSE over every pixel's RGB: errors 0.6 (black row) and 0.1.
    EXPECT_NEAR(s.rmse, std::sqrt((0.36 + 0.01) / 2.0), 1e-6);
    // Mean log luminance: half at log(0.5), half at the 1e-6 floor; exposure = log2(0.18) - that / ln 2.
    const double meanLog = 0.5 * std::log(0.5) + 0.5 * std::log(1e-6);
    EXPECT_NEAR(s.exposureEv, std::log2(0.18) - meanLog / std::log(2.0), 1e-4);
    EXPECT_THROW(compareWithTruth(grey(2, 2, 1.0f), grey(4, 2, 1.0f), 1e-3f), Error);
}

TEST(ViewerCompare, RunsInTheFinalRasterViewOnly) {
    RenderSettings s;
    EXPECT_EQ(truthComparisonUnavailable(s), "");
    s.view = DebugView::Normals;
    EXPECT_NE(truthComparisonUnavailable(s).find("only in the final view"), std::string::npos);
    s.view = DebugView::Final;
    s.renderPath = RenderPath::PathTraced;
    EXPECT_NE(truthComparisonUnavailable(s).find("path tracer's already"), std::string::npos);
    // A tile is half the viewport each way, never empty.
    EXPECT_EQ(comparisonTile({10, 20, 601, 341}).width, 300);
    EXPECT_EQ(comparisonTile({10, 20, 601, 341}).height, 170);
    EXPECT_EQ(comparisonTile({0, 0, 1, 1}).width, 1);
}
