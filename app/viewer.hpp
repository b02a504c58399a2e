#pragma once
#include "app/cli.hpp"

namespace lp::app {
// The interactive window: the seeds' keys, a fly camera, per-pass timings in the title.
int runViewer(const Options& options);
}
