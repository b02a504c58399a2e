// The CPU-beside-GPU line of `render` and `bench` (app/frame_cost.hpp).
#include <gtest/gtest.h>

#include "app/frame_cost.hpp"

using namespace lp::app;

TEST(FrameCost, MediansAndTheWallOverGpuRatio) {
    const FrameCost c = frameCost({0.5, 0.3, 0.9}, {2.0, 0.0, 1.0}, 2.7, 2.5);
    EXPECT_EQ(c.frames, 3);
    EXPECT_DOUBLE_EQ(c.submitMs, 0.5);
    EXPECT_DOUBLE_EQ(c.waitMs, 1.0);
    EXPECT_NEAR(c.wallOverGpu(), 2.7 / 2.5, 1e-12);
    EXPECT_FALSE(c.gpuBound());  // 8% over the GPU's time: the GPU waited
}

TEST(FrameCost, WithinFivePercentOfGpuTimeIsGpuBound) {
    EXPECT_TRUE(frameCost({0.1}, {2.4}, 2.6, 2.5).gpuBound());
    EXPECT_TRUE(frameCost({0.1}, {2.4}, 2.625, 2.5).gpuBound());
    EXPECT_FALSE(frameCost({0.1}, {2.4}, 2.63, 2.5).gpuBound());
    EXPECT_FALSE(frameCost({}, {}, 1.0, 0.0).gpuBound());  // nothing timed on the GPU
}

TEST(FrameCost, OneLineAndJsonSayTheSame) {
    const FrameCost c = frameCost({0.25}, {2.0}, 3.27, 2.6);
    const std::string line = frameCostLine(c);
    EXPECT_EQ(line.find('\n'), std::string::npos);
    EXPECT_NE(line.find("0.250 ms submit"), std::string::npos) << line;
    EXPECT_NE(line.find("wall 3.270 ms/frame = 1.26x GPU 2.600 ms"), std::string::npos) << line;
    EXPECT_NE(line.find("the GPU waits for the CPU"), std::string::npos) << line;
    const nlohmann::json j = frameCostJson(c);
    EXPECT_DOUBLE_EQ(j["wall_ms_per_frame"].get<double>(), 3.27);
    EXPECT_FALSE(j["gpu_bound"].get<bool>());
}
