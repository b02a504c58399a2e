#pragma once
// Whether a CUDA device can run the CUDA post effects here, and why not.
#include <string>

namespace lp::cuda {

struct DeviceInfo {
    bool available = false;
    std::string name;    // e.g. "NVIDIA H100 80GB HBM3"
    std::string reason;  // why not, when unavailable
    int computeMajor = 0, computeMinor = 0;
};

DeviceInfo queryDevice();

}  // namespace lp::cuda
