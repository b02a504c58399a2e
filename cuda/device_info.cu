#include "cuda/device_info.hpp"

#include <cuda_runtime.h>

namespace lp::cuda {

DeviceInfo queryDevice() {
    DeviceInfo info;
    int count = 0;
    cudaError_t err = cudaGetDeviceCount(&count);
    if (err != cudaSuccess) {
        info.reason = std::string("cudaGetDeviceCount: ") + cudaGetErrorString(err);
        cudaGetLastError();
        return info;
    }
    if (count == 0) {
        info.reason = "no CUDA device";
        return info;
    }
    cudaDeviceProp prop{};
    err = cudaGetDeviceProperties(&prop, 0);
    if (err != cudaSuccess) {
        info.reason = std::string("cudaGetDeviceProperties: ") + cudaGetErrorString(err);
        return info;
    }
    info.available = true;
    info.name = prop.name;
    info.computeMajor = prop.major;
    info.computeMinor = prop.minor;
    return info;
}

}  // namespace lp::cuda
