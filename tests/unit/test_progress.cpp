// The progress reporter on a fake clock and a string stream: when it starts showing, the plain
// lines' format and count, the terminal redraw, the time-left estimate, quiet mode.
#include <gtest/gtest.h>

#include <sstream>

#include "engine/core/log.hpp"
#include "engine/core/progress.hpp"

using namespace lp;

namespace {
struct FakeClock {
    double now = 100.0;
    ProgressClock clock() {
        return [this] { return now; };
    }
};

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}
}  // namespace

TEST(Progress, TimeLeftIsTheAverageRateSoFar) {
    EXPECT_DOUBLE_EQ(progressSecondsLeft(6.0, 3, 10), 14.0);  // 2 s a step, 7 to go
    EXPECT_DOUBLE_EQ(progressSecondsLeft(6.0, 10, 10), 0.0);
    EXPECT_LT(progressSecondsLeft(6.0, 0, 10), 0.0);  // unknown before the first step
    EXPECT_EQ(progressTimeLeftText(14.0), "about 14 s left");
    EXPECT_EQ(progressTimeLeftText(13.2), "about 14 s left");  // never promises less than it knows
    EXPECT_EQ(progressTimeLeftText(185.0), "about 3 min 05 s left");
    EXPECT_EQ(progressTimeLeftText(-1.0), "");
}

TEST(Progress, TimeLeftLeavesTheFirstStepsOneOffCostOut) {
    // A first frame of 9 s (an IBL bake), then 0.5 s frames: after 3 of 10, 7 more at 0.5 s.
    EXPECT_DOUBLE_EQ(progressSecondsLeftAfterFirstStep(10.0, 9.0, 3, 10), 3.5);
    EXPECT_DOUBLE_EQ(progressSecondsLeftAfterFirstStep(9.0, 9.0, 1, 10), 81.0);  // nothing better known yet
}

TEST(Progress, LineTextHasPercentCountEstimateAndNote) {
    EXPECT_EQ(progressLineText("bench", 3, 10, 14.0, "--aa fxaa", false), "bench  30% 3/10, about 14 s left: --aa fxaa");
    EXPECT_EQ(progressLineText("bench", 5, 10, 4.0, "", true),
              "bench [############............]  50% 5/10, about 4 s left");
    EXPECT_EQ(progressLineText("bench", 0, 10, -1.0, "", false), "bench   0% 0/10");
}

TEST(Progress, PlainLinesStartAfterTwoSecondsOnePerTenth) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;  // not a terminal, 2 s
    {
        ProgressReporter p("render", 100, out, style, t.clock());
        for (int i = 1; i <= 100; ++i) {
            t.now += 0.125;  // 12.5 s in all
            p.step("frame " + std::to_string(i));
        }
    }
    const auto l = lines(out.str());
    // First at 2 s (step 16), then one per tenth from 20% to 90%, then the done line.
    ASSERT_EQ(l.size(), 10u) << out.str();
    EXPECT_EQ(l[0], "render  16% 16/100, about 11 s left: frame 16");
    EXPECT_EQ(l[1], "render  20% 20/100, about 10 s left: frame 20");
    EXPECT_EQ(l[8], "render  90% 90/100, about 2 s left: frame 90");
    EXPECT_EQ(l[9], "render done in 12.5 s (100/100)");
    EXPECT_EQ(out.str().find('\r'), std::string::npos);
}

TEST(Progress, ShortWorkShowsNothing) {
    FakeClock t;
    std::ostringstream out;
    {
        ProgressReporter p("sweep", 4, out, ProgressStyle{}, t.clock());
        for (int i = 0; i < 4; ++i) {
            t.now += 0.4;
            p.step();
        }
    }
    EXPECT_EQ(out.str(), "");
}

TEST(Progress, OneLongStepShowsNothingUntilItsEnd) {
    // A single 9 s step: nothing to draw before it ends, and its end is the end of the work.
    FakeClock t;
    std::ostringstream out;
    {
        ProgressReporter p("render", 1, out, ProgressStyle{}, t.clock());
        t.now += 9.0;
        p.step();
    }
    EXPECT_EQ(out.str(), "");
}

TEST(Progress, FromStartShowsEveryTenthAndTheEnd) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.showAfterSeconds = 0.0;  // --progress
    {
        ProgressReporter p("sweep", 4, out, style, t.clock());
        for (int i = 0; i < 4; ++i) {
            t.now += 0.5;
            p.step("value " + std::to_string(i));
        }
    }
    const auto l = lines(out.str());
    ASSERT_EQ(l.size(), 4u) << out.str();
    EXPECT_EQ(l[0], "sweep  25% 1/4, about 2 s left: value 0");
    EXPECT_EQ(l[2], "sweep  75% 3/4, about 1 s left: value 2");
    EXPECT_EQ(l[3], "sweep done in 2.0 s (4/4)");
}

TEST(Progress, PlainLinePerStepWhereAStepIsLong) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.plainLinePerStep = true;  // bench variants
    {
        ProgressReporter p("bench", 40, out, style, t.clock());
        for (int i = 0; i < 40; ++i) {
            t.now += 1.0;
            p.step("variant " + std::to_string(i));
        }
    }
    const auto l = lines(out.str());
    // Steps 2..40 (from 2 s on), then the done line.
    ASSERT_EQ(l.size(), 40u) << out.str();
    EXPECT_EQ(l[0], "bench   5% 2/40, about 38 s left: variant 1");
    EXPECT_EQ(l[1], "bench   7% 3/40, about 37 s left: variant 2");
    EXPECT_EQ(l[38], "bench 100% 40/40: variant 39");
    EXPECT_EQ(l[39], "bench done in 40.0 s (40/40)");
}

TEST(Progress, QuietShowsNothingAtAll) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.quiet = true;
    style.showAfterSeconds = 0.0;
    {
        ProgressReporter p("bench", 10, out, style, t.clock());
        for (int i = 0; i < 10; ++i) {
            t.now += 1.0;
            p.step("x");
        }
    }
    EXPECT_EQ(out.str(), "");
}

TEST(Progress, TerminalRedrawsOneLineInPlace) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.terminal = true;
    {
        ProgressReporter p("bake", 4, out, style, t.clock());
        for (int i = 0; i < 4; ++i) {
            t.now += 1.0;
            p.step();
        }
    }
    const std::string s = out.str();
    // Drawn at 2 s and 3 s, then the finished bar: every draw returns to the line's start and clears
    // it, and only the last ends the line.
    EXPECT_EQ(s, "\r\033[Kbake [############............]  50% 2/4, about 2 s left"
                 "\r\033[Kbake [##################......]  75% 3/4, about 1 s left"
                 "\r\033[Kbake [########################] 100% 4/4: done in 4.0 s\n");
}

TEST(Progress, TerminalRedrawsAtMostTenTimesASecond) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.terminal = true;
    style.showAfterSeconds = 0.0;
    {
        ProgressReporter p("frames", 1000, out, style, t.clock());
        for (int i = 0; i < 1000; ++i) {
            t.now += 0.001;  // 1 s of 1 ms frames
            p.step();
        }
    }
    size_t draws = 0;
    for (size_t at = out.str().find('\r'); at != std::string::npos; at = out.str().find('\r', at + 1)) ++draws;
    EXPECT_GE(draws, 9u);
    EXPECT_LE(draws, 12u);
}

TEST(Progress, WorkCutShortEndsTheBarWithoutClaimingDone) {
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.terminal = true;
    {
        ProgressReporter p("bench", 10, out, style, t.clock());
        for (int i = 0; i < 3; ++i) {
            t.now += 1.0;
            p.step();
        }
    }  // as an exception would leave it
    const std::string s = out.str();
    EXPECT_EQ(s.find("done"), std::string::npos) << s;
    EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, ALogLineClearsAnOpenBarFirst) {
    // The bar on stderr (where the log writes), left open mid-work: a warning starts on a clean line.
    FakeClock t;
    std::ostringstream out;
    ProgressStyle style;
    style.terminal = true;
    style.sharesLogStream = true;
    style.showAfterSeconds = 0.0;
    ProgressReporter p("frames", 4, out, style, t.clock());
    t.now += 1.0;
    p.step();
    ::testing::internal::CaptureStderr();
    logWarn("a warning while the bar is open");
    logWarn("and the next one");  // the line is clean already: nothing to clear
    flushRepeatedWarnings();
    EXPECT_EQ(::testing::internal::GetCapturedStderr(),
              "\r\033[Klightpass: warning: a warning while the bar is open\n"
              "lightpass: warning: and the next one\n");
    for (int i = 0; i < 3; ++i) p.step();
    p.finish();
    ::testing::internal::CaptureStderr();
    logWarn("after the bar ended");
    flushRepeatedWarnings();
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "lightpass: warning: after the bar ended\n");
}
