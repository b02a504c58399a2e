#pragma once
#include <string>
#include <vector>

#include "app/cli.hpp"

namespace lp::app {
// lightpass report: --scene/--model renders the frame and writes OUT/index.html (the graph, every
// view the frame has, per-pass GPU ms against floors, memory, device, command line); --sweep DIR
// writes the page of a sweep folder instead, --bench F.json that of a bench's JSON (no GPU needed
// for either). `args` are the command's arguments
// (after the program name), shown on the page.
int runReport(const Options& options, const std::vector<std::string>& args);
}  // namespace lp::app
