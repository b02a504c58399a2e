#pragma once
// Importance sampling of an equirectangular environment map for the path tracer
// (shaders/common/path_trace_environment.glsl reads these tables; docs/path-tracer.md). A piecewise-
// constant 2D distribution over cells of the map, each cell's weight its mean luminance times sin θ
// (the solid angle a row of cells spans), sampled row by the marginal CDF and column by the row's
// conditional CDF, uniformly inside the cell. The map stays the radiance; only where samples go
// follows these cells, so a coarser grid costs variance, never bias.
#include <vector>

#include <glm/glm.hpp>

#include "engine/io/image_io.hpp"

namespace lp {

struct EnvironmentDistribution {
    int width = 0, height = 0;     // cells (the map's size, or box-averaged down to at most kMaxWidth)
    std::vector<float> marginal;   // height + 1 entries: CDF over rows, 0 .. 1
    std::vector<float> conditional;  // height x (width + 1): each row's CDF over its cells, 0 .. 1
    std::vector<float> cellPdf;    // width x height: density over the unit (u, v) square of each cell
    bool empty() const { return width == 0; }
};

// Cells at most this wide (and half as tall): a 4096-wide map is averaged 8:1, keeping the tables
// (about 3 floats a cell) under 2 MB while a 2-texel lamp still gets cells of its own size.
inline constexpr int kEnvironmentCellsMaxWidth = 512;

// The distribution of `map` (RGBA float, row 0 at +Y, as loaded). Empty when the map has no light
// (every texel black or not finite): the tracer then samples the BRDF alone.
EnvironmentDistribution buildEnvironmentDistribution(const ImageF& map, int maxWidth = kEnvironmentCellsMaxWidth);

// The same sampling and density as the GLSL, for tests: a direction in the map's frame (before the
// environment's rotation) from two uniform numbers, its density over solid angle, and the density of
// any direction.
struct EnvironmentSample {
    glm::vec3 direction{0.0f};
    float pdf = 0.0f;  // per steradian
};
EnvironmentSample sampleEnvironment(const EnvironmentDistribution& d, glm::vec2 u);
float environmentPdf(const EnvironmentDistribution& d, glm::vec3 direction);

// ibl.glsl's equirectUv and equirectDirection on the CPU (u from atan(x, -z), v = 0 at +Y).
glm::vec2 equirectUvOf(glm::vec3 direction);
glm::vec3 equirectDirectionOf(glm::vec2 uv);

}  // namespace lp
