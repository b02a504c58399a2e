#pragma once
// What a frame costs the CPU beside what it costs the GPU, for `render` and `bench`: one line each.
// The frame keeps the GPU busy when wall time per frame is within 5% of GPU time per frame; above
// that the GPU waits for the CPU (submission) between frames.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lp::app {

struct FrameCost {
    int frames = 0;
    double submitMs = 0.0;  // median CPU ms building, compiling and submitting a frame's graph
    double waitMs = 0.0;    // median CPU ms a frame waited for older frames' GPU results
    double wallMs = 0.0;    // wall ms per frame over the timed frames, the GPU's last work included
    double gpuMs = 0.0;     // median GPU ms of the whole frame (timer queries)
    double wallOverGpu() const { return gpuMs > 0.0 ? wallMs / gpuMs : 0.0; }
    bool gpuBound() const { return gpuMs > 0.0 && wallMs <= 1.05 * gpuMs; }
};

FrameCost frameCost(const std::vector<double>& submitMs, const std::vector<double>& waitMs, double wallMs, double gpuMs);
// "cpu: 0.41 ms submit + 2.20 ms waiting for the GPU (median of 60 frames); wall 2.65 ms/frame =
// 1.02x GPU 2.60 ms: the GPU is the bottleneck"
std::string frameCostLine(const FrameCost& cost);
nlohmann::json frameCostJson(const FrameCost& cost);

}  // namespace lp::app
