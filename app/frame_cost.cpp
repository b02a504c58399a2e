#include "app/frame_cost.hpp"

#include <cstdio>

#include "engine/gl/gpu_timer.hpp"

namespace lp::app {

FrameCost frameCost(const std::vector<double>& submitMs, const std::vector<double>& waitMs, double wallMs, double gpuMs) {
    FrameCost c;
    c.frames = int(submitMs.size());
    c.submitMs = gl::median(submitMs);
    c.waitMs = gl::median(waitMs);
    c.wallMs = wallMs;
    c.gpuMs = gpuMs;
    return c;
}

std::string frameCostLine(const FrameCost& c) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "cpu: %.3f ms submit + %.3f ms waiting for the GPU (median of %d frames); wall %.3f ms/frame = %.2fx GPU "
                  "%.3f ms: %s",
                  c.submitMs, c.waitMs, c.frames, c.wallMs, c.wallOverGpu(), c.gpuMs,
                  c.gpuBound() ? "the GPU is the bottleneck" : "the GPU waits for the CPU");
    return line;
}

nlohmann::json frameCostJson(const FrameCost& c) {
    return {{"frames", c.frames},         {"submit_median_ms", c.submitMs}, {"wait_median_ms", c.waitMs},
            {"wall_ms_per_frame", c.wallMs}, {"gpu_frame_median_ms", c.gpuMs}, {"wall_over_gpu", c.wallOverGpu()},
            {"gpu_bound", c.gpuBound()}};
}

}  // namespace lp::app
