#include "passes/path_trace_environment.hpp"

#include <algorithm>
#include <cmath>

namespace lp {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Index i with cdf[i] <= x < cdf[i + 1] among n cells (cdf has n + 1 entries); zero-width cells are
// never chosen (upper_bound skips past equal entries).
int findCell(const float* cdf, int n, float x) {
    const float* at = std::upper_bound(cdf, cdf + n + 1, x);
    return std::clamp(int(at - cdf) - 1, 0, n - 1);
}
}  // namespace

glm::vec2 equirectUvOf(glm::vec3 d) {
    return glm::vec2(float(std::atan2(double(d.x), double(-d.z)) / (2.0 * kPi) + 0.5),
                     float(std::acos(std::clamp(double(d.y), -1.0, 1.0)) / kPi));
}

glm::vec3 equirectDirectionOf(glm::vec2 uv) {
    const double phi = (double(uv.x) - 0.5) * 2.0 * kPi, theta = double(uv.y) * kPi;
    return glm::vec3(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::cos(phi)));
}

EnvironmentDistribution buildEnvironmentDistribution(const ImageF& map, int maxWidth) {
    EnvironmentDistribution d;
    if (map.width <= 0 || map.height <= 0) return d;
    // Cells: the map box-averaged by a whole factor so that they are at most maxWidth wide.
    const int factor = std::max(1, (map.width + maxWidth - 1) / std::max(maxWidth, 1));
    const int w = std::max(1, map.width / factor), h = std::max(1, map.height / factor);
    // A cell's luminance: the mean over its texels and the ring of texels around them, the support of
    // the bilinear filter the tracer reads the map with. A lamp's filtered light reaches half a texel
    // into the neighbouring cells; with their own (dim) luminance alone they would be sampled rarely
    // while that light is bright, and the few samples that land there would be fireflies.
    std::vector<double> weight(size_t(w) * size_t(h), 0.0), count(size_t(w) * size_t(h), 0.0);
    auto cellsTouching = [factor](int texel, int cells, int out[3]) {  // the cells whose support holds it
        int n = 0;
        const int c = std::min(texel / factor, cells - 1);
        out[n++] = c;
        if (texel % factor == 0 && texel / factor <= cells - 1) out[n++] = c - 1;  // the left / top ring
        if (texel % factor == factor - 1 || texel / factor > cells - 1) out[n++] = c + 1;  // the right / bottom ring
        return n;
    };
    for (int y = 0; y < map.height; ++y) {
        int rows[3];
        const int nr = cellsTouching(y, h, rows);
        for (int x = 0; x < map.width; ++x) {
            const float* t = &map.rgba[(size_t(y) * size_t(map.width) + size_t(x)) * 4];
            double lum = 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2];
            if (!std::isfinite(lum) || lum < 0.0) lum = 0.0;
            int columns[3];
            const int nc = cellsTouching(x, w, columns);
            for (int i = 0; i < nr; ++i) {
                if (rows[i] < 0 || rows[i] >= h) continue;  // v clamps at the poles
                for (int j = 0; j < nc; ++j) {
                    const int cx = (columns[j] + w) % w;  // u wraps around
                    weight[size_t(rows[i]) * size_t(w) + size_t(cx)] += lum;
                    count[size_t(rows[i]) * size_t(w) + size_t(cx)] += 1.0;
                }
            }
        }
    }
    // Each cell's weight: that mean luminance times the sine at its centre row, the solid angle its
    // row spans per unit of v.
    double total = 0.0;
    std::vector<double> rowSum(size_t(h), 0.0);
    for (int y = 0; y < h; ++y) {
        const double s = std::sin((double(y) + 0.5) / double(h) * kPi);
        for (int x = 0; x < w; ++x) {
            double& c = weight[size_t(y) * size_t(w) + size_t(x)];
            c = count[size_t(y) * size_t(w) + size_t(x)] > 0.0 ? c / count[size_t(y) * size_t(w) + size_t(x)] * s : 0.0;
            rowSum[size_t(y)] += c;
        }
        total += rowSum[size_t(y)];
    }
    if (!(total > 0.0) || !std::isfinite(total)) return d;
    d.width = w;
    d.height = h;
    d.marginal.assign(size_t(h) + 1, 0.0f);
    d.conditional.assign(size_t(h) * size_t(w + 1), 0.0f);
    d.cellPdf.assign(size_t(w) * size_t(h), 0.0f);
    double running = 0.0;
    for (int y = 0; y < h; ++y) {
        running += rowSum[size_t(y)];
        d.marginal[size_t(y) + 1] = float(running / total);
        float* cdf = &d.conditional[size_t(y) * size_t(w + 1)];
        double rowRunning = 0.0;
        for (int x = 0; x < w; ++x) {
            const double c = weight[size_t(y) * size_t(w) + size_t(x)];
            rowRunning += c;
            cdf[x + 1] = rowSum[size_t(y)] > 0.0 ? float(rowRunning / rowSum[size_t(y)]) : float(x + 1) / float(w);
            d.cellPdf[size_t(y) * size_t(w) + size_t(x)] = float(c / total * double(w) * double(h));
        }
        cdf[w] = 1.0f;
    }
    d.marginal[size_t(h)] = 1.0f;
    return d;
}

EnvironmentSample sampleEnvironment(const EnvironmentDistribution& d, glm::vec2 u) {
    EnvironmentSample s;
    if (d.empty()) return s;
    const int row = findCell(d.marginal.data(), d.height, u.y);
    const float r0 = d.marginal[size_t(row)], r1 = d.marginal[size_t(row) + 1];
    const float* cdf = &d.conditional[size_t(row) * size_t(d.width + 1)];
    const int col = findCell(cdf, d.width, u.x);
    const float c0 = cdf[col], c1 = cdf[col + 1];
    const float fy = r1 > r0 ? std::clamp((u.y - r0) / (r1 - r0), 0.0f, 1.0f) : 0.5f;
    const float fx = c1 > c0 ? std::clamp((u.x - c0) / (c1 - c0), 0.0f, 1.0f) : 0.5f;
    const glm::vec2 uv((float(col) + fx) / float(d.width), (float(row) + fy) / float(d.height));
    s.direction = equirectDirectionOf(uv);
    const double sinTheta = std::sin(double(uv.y) * kPi);
    s.pdf = sinTheta > 0.0 ? float(double(d.cellPdf[size_t(row) * size_t(d.width) + size_t(col)]) / (2.0 * kPi * kPi * sinTheta))
                           : 0.0f;
    return s;
}

float environmentPdf(const EnvironmentDistribution& d, glm::vec3 direction) {
    if (d.empty()) return 0.0f;
    const glm::vec2 uv = equirectUvOf(direction);
    const int col = std::clamp(int(uv.x * float(d.width)), 0, d.width - 1);
    const int row = std::clamp(int(uv.y * float(d.height)), 0, d.height - 1);
    const double sinTheta = std::sin(double(uv.y) * kPi);
    if (!(sinTheta > 0.0)) return 0.0f;
    return float(double(d.cellPdf[size_t(row) * size_t(d.width) + size_t(col)]) / (2.0 * kPi * kPi * sinTheta));
}

}  // namespace lp
