#include "engine/render/light_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.hpp"

namespace lp {

ClusterGrid makeClusterGrid(int width, int height, int tileSize, int slices, float nearPlane, float farPlane) {
    ClusterGrid g;
    g.tileSize = std::max(tileSize, 1);
    g.width = std::max(width, 1);
    g.height = std::max(height, 1);
    g.tilesX = (g.width + g.tileSize - 1) / g.tileSize;
    g.tilesY = (g.height + g.tileSize - 1) / g.tileSize;
    if (slices > kMaxClusterSlices)
        throw Error("clustered: " + std::to_string(slices) + " depth slices: at most " + std::to_string(kMaxClusterSlices));
    g.slices = std::max(slices, 1);
    g.nearPlane = nearPlane;
    g.farPlane = std::max(farPlane, nearPlane * 1.001f);
    const double bytes = double(g.count()) * kMaxLightsPerCluster * 4.0;
    if (bytes > kMaxClusterListBytes)
        throw Error("clustered: " + std::to_string(g.count()) + " clusters x " + std::to_string(kMaxLightsPerCluster) +
                    " lights need " + std::to_string(int(bytes / 1048576.0)) + " MiB, over the " +
                    std::to_string(int(kMaxClusterListBytes / 1048576.0)) +
                    " MiB limit: raise --cluster-size or lower --cluster-slices");
    return g;
}

double clusterSliceStart(const ClusterGrid& g, int k) {
    return double(g.nearPlane) * std::pow(double(g.farPlane) / double(g.nearPlane), double(k) / double(g.slices));
}

int clusterSliceOf(const ClusterGrid& g, double d) {
    const double s = std::log(std::max(d, 1e-30) / double(g.nearPlane)) /
                     std::log(double(g.farPlane) / double(g.nearPlane)) * double(g.slices);
    return int(std::clamp(std::floor(s), 0.0, double(g.slices - 1)));
}

namespace {
// Tile (x, y)'s NDC rectangle (the last tile stops at the image's edge).
void tileNdc(const ClusterGrid& g, int x, int y, double& x0, double& x1, double& y0, double& y1) {
    x0 = double(x * g.tileSize) / g.width * 2.0 - 1.0;
    x1 = double(std::min((x + 1) * g.tileSize, g.width)) / g.width * 2.0 - 1.0;
    y0 = double(y * g.tileSize) / g.height * 2.0 - 1.0;
    y1 = double(std::min((y + 1) * g.tileSize, g.height)) / g.height * 2.0 - 1.0;
}
}  // namespace

EyeBox tileBox(const ClusterGrid& g, const glm::mat4& projection, int x, int y, double d0, double d1) {
    const double p00 = projection[0][0], p20 = projection[2][0], p11 = projection[1][1], p21 = projection[2][1];
    double x0, x1, y0, y1;
    tileNdc(g, x, y, x0, x1, y0, y1);
    EyeBox b{glm::dvec3(1e300), glm::dvec3(-1e300)};
    for (double d : {d0, d1})
        for (double nx : {x0, x1})
            for (double ny : {y0, y1}) {
                // x_ndc = (p00 x + p20 z) / -z at z = -d.
                const glm::dvec3 c((nx + p20) * d / p00, (ny + p21) * d / p11, -d);
                b.lo = glm::min(b.lo, c);
                b.hi = glm::max(b.hi, c);
            }
    return b;
}

EyeBox froxelBox(const ClusterGrid& g, const glm::mat4& projection, int x, int y, int k) {
    return tileBox(g, projection, x, y, clusterSliceStart(g, k), clusterSliceStart(g, k + 1));
}

bool lightTouchesTileDepthRange(const GpuLocalLight& l, const ClusterGrid& g, const glm::mat4& projection, int x,
                                int y, double d0, double d1, double margin) {
    const glm::dvec3 c(l.bound);
    const double r = double(l.bound.w) * (1.0 + margin) + 1e-6;
    const double dist = -c.z;
    if (dist + r < d0 || dist - r > d1) return false;
    double x0, x1, y0, y1;
    tileNdc(g, x, y, x0, x1, y0, y1);
    const double p00 = projection[0][0], p20 = projection[2][0], p11 = projection[1][1], p21 = projection[2][1];
    // x_ndc >= x0  <=>  p00 x + (p20 + x0) z >= 0 (with z < 0); likewise for the other sides.
    const glm::dvec3 planes[4] = {{p00, 0.0, p20 + x0}, {-p00, 0.0, -(p20 + x1)}, {0.0, p11, p21 + y0}, {0.0, -p11, -(p21 + y1)}};
    for (const glm::dvec3& n : planes)
        if (glm::dot(n, c) < -r * glm::length(n)) return false;
    return true;
}

bool lightTouchesTileColumn(const GpuLocalLight& l, const ClusterGrid& g, const glm::mat4& projection, int x, int y,
                            double margin) {
    return lightTouchesTileDepthRange(l, g, projection, x, y, double(g.nearPlane), double(g.farPlane), margin);
}

bool lightTouchesFroxel(const GpuLocalLight& l, const EyeBox& box, double margin) {
    const glm::dvec3 c(l.bound);
    const double r = double(l.bound.w) * (1.0 + margin) + 1e-6;
    const glm::dvec3 nearest = glm::clamp(c, box.lo, box.hi);
    const glm::dvec3 off = c - nearest;
    if (glm::dot(off, off) > r * r) return false;
    const double cosOuter = l.directionCos.w;
    if (cosOuter < -1.0) return true;  // a point light: the sphere is its exact bound
    // The spot's cone against the sphere around the box.
    const glm::dvec3 centre = 0.5 * (box.lo + box.hi);
    const double radius = 0.5 * glm::length(box.hi - box.lo) * (1.0 + margin) + 1e-6;
    const glm::dvec3 v = centre - glm::dvec3(l.positionRange);
    const double along = glm::dot(v, glm::dvec3(l.directionCos));
    const double sinOuter = std::sqrt(std::max(1.0 - cosOuter * cosOuter, 0.0));
    const double toSurface = cosOuter * std::sqrt(std::max(glm::dot(v, v) - along * along, 0.0)) - along * sinOuter;
    const double range = double(l.positionRange.w) * (1.0 + margin);
    return !(toSurface > radius || along > radius + range || along < -radius);
}

std::vector<std::vector<int>> referenceClusterLists(const ClusterGrid& g, const glm::mat4& projection,
                                                    const std::vector<GpuLocalLight>& lights, double margin) {
    std::vector<std::vector<int>> lists(size_t(g.count()));
    for (int k = 0; k < g.slices; ++k)
        for (int y = 0; y < g.tilesY; ++y)
            for (int x = 0; x < g.tilesX; ++x) {
                const EyeBox box = froxelBox(g, projection, x, y, k);
                auto& list = lists[size_t(g.index(x, y, k))];
                for (size_t i = 0; i < lights.size(); ++i)
                    if (lightTouchesTileColumn(lights[i], g, projection, x, y, margin) &&
                        lightTouchesFroxel(lights[i], box, margin))
                        list.push_back(int(i));
            }
    return lists;
}

std::vector<FroxelDepth> occupiedFroxelDepths(const ClusterGrid& g, const std::vector<double>& eyeDistance) {
    std::vector<FroxelDepth> depths(size_t(g.count()));
    for (int py = 0; py < g.height; ++py)
        for (int px = 0; px < g.width; ++px) {
            const double e = eyeDistance[size_t(py) * size_t(g.width) + size_t(px)];
            if (std::isnan(e)) continue;
            const double d = std::max(e, 0.0);
            FroxelDepth& f = depths[size_t(g.index(px / g.tileSize, py / g.tileSize, clusterSliceOf(g, d)))];
            f.nearest = std::min(f.nearest, d);
            f.farthest = std::max(f.farthest, d);
        }
    return depths;
}

std::vector<std::vector<int>> referenceTightClusterLists(const ClusterGrid& g, const glm::mat4& projection,
                                                         const std::vector<GpuLocalLight>& lights,
                                                         const std::vector<FroxelDepth>& depths, double margin) {
    std::vector<std::vector<int>> lists(size_t(g.count()));
    for (int k = 0; k < g.slices; ++k)
        for (int y = 0; y < g.tilesY; ++y)
            for (int x = 0; x < g.tilesX; ++x) {
                const FroxelDepth& f = depths[size_t(g.index(x, y, k))];
                if (!f.occupied()) continue;
                const EyeBox box = tileBox(g, projection, x, y, f.nearest, f.farthest);
                auto& list = lists[size_t(g.index(x, y, k))];
                for (size_t i = 0; i < lights.size(); ++i)
                    if (lightTouchesTileDepthRange(lights[i], g, projection, x, y, f.nearest, f.farthest, margin) &&
                        lightTouchesFroxel(lights[i], box, margin))
                        list.push_back(int(i));
            }
    return lists;
}

}  // namespace lp
