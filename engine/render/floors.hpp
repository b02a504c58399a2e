#pragma once
// Floors: the least time a pass could take on this GPU. For a compute pass, the bytes it must move
// over the bandwidth a plain streaming copy achieves in GL compute on the same device.
#include <optional>
#include <string>

#include "engine/gl/shader.hpp"
#include "engine/graph/frame_graph.hpp"

namespace lp {

struct Bandwidth {
    double bytesPerSecond = 0.0;
    double copyMs = 0.0;  // median time of one copy
    size_t bytes = 0;     // moved per copy (read + write)
};

// Median over `repeats` copies of a width x height RGBA32F image, after warm-up; GL timer queries.
Bandwidth measureComputeBandwidth(const gl::ShaderLibrary& shaders, int width = 3840, int height = 2160, int repeats = 30);
// The same for the raster path: a full-screen triangle writing an RGBA32F target (write bytes only).
Bandwidth measureFragmentBandwidth(const gl::ShaderLibrary& shaders, int width = 3840, int height = 2160, int repeats = 30);

// A pass's floor from the kind it declared (fg::PassKind): raster work moves its bytes at the
// fragment fill rate, compute and CUDA at the compute copy bandwidth. "fragment fill" / "compute copy".
double passFloorMs(fg::PassKind kind, size_t bytes, const Bandwidth& compute, const Bandwidth& fragment);
const char* floorBasis(fg::PassKind kind);

// Both bandwidths of this GPU, measured once for a run's floors (render, bench, report).
struct FloorBandwidths {
    Bandwidth compute, fragment;
};
FloorBandwidths measureFloorBandwidths(const gl::ShaderLibrary& shaders, int width = 3840, int height = 2160, int repeats = 30);

// A pass's floor in the frame `graph` last compiled: the texture bytes it declared, the floor's time
// and its basis; none for a pass that moves no texture bytes (or is not in the graph).
struct PassFloor {
    size_t bytes = 0;
    double ms = 0.0;
    const char* basis = "";
};
std::optional<PassFloor> passFloor(const fg::FrameGraph& graph, const std::string& pass, const FloorBandwidths& bandwidths);

}  // namespace lp
