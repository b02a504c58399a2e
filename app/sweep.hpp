#pragma once
#include "app/cli.hpp"

namespace lp::app {
// lightpass sweep: every value of each chosen quality knob, GPU ms per pass and error against the
// knob's best value, as CSV + Markdown (+ images for FLIP and plots by bench/sweep_report.py).
int runSweep(const Options& options);
}
