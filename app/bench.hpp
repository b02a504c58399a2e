#pragma once
#include <string>
#include <vector>

#include "app/cli.hpp"

namespace lp::app {

// One axis of `lightpass bench --vary`: alternative flag lists, e.g. "--light-count 1,32,256" becomes
// {"--light-count 1", "--light-count 32", "--light-count 256"} and "--bloom|--no-bloom" two entries.
std::vector<std::vector<std::string>> parseVaryAxis(const std::string& spec);

// The cartesian product of every axis, each a flag list to append to the common flags.
std::vector<std::vector<std::string>> expandVariants(const std::vector<std::string>& specs);

// lightpass bench: one process, one scene load, every variant rendered and timed in turn (GPU ms per
// pass, median after warm-up, each pass against its floor), written as one JSON file. Ratios between
// variants of one run are what the results report.
int runBench(const Options& options, const std::vector<std::string>& args);

}  // namespace lp::app
