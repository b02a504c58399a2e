// The log: a warning repeated back to back is printed once, then its count.
#include <gtest/gtest.h>

#include "engine/core/log.hpp"

using namespace lp;

TEST(Log, RepeatedWarningIsPrintedOnceAndCounted) {
    flushRepeatedWarnings();
    const int before = warningCount();
    ::testing::internal::CaptureStderr();
    for (int i = 0; i < 500; ++i) logWarn("the same thing went wrong");
    logWarn("something else");
    logWarn("the same thing went wrong");  // after other output: news again
    logWarn("the same thing went wrong");
    flushRepeatedWarnings();
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warningCount(), before + 503);
    EXPECT_EQ(err, "lightpass: warning: the same thing went wrong\n"
                   "lightpass: warning: the same thing went wrong (repeated 499 more times)\n"
                   "lightpass: warning: something else\n"
                   "lightpass: warning: the same thing went wrong\n"
                   "lightpass: warning: the same thing went wrong (repeated 1 more times)\n");
}
