#pragma once
// Clustered shading's froxel grid (Olsson, Billeter, Assarsson 2012), CPU side: the grid's shape,
// exponential depth slices, each froxel's eye-space box, and the light-vs-froxel test that
// shaders/light_clusters.comp runs, here in double as the reference the tests compare it with.
//
// The grid: screen tiles of tileSize pixels x `slices` depth slices between the camera's near and
// far planes, slice k covering eye distances [near (far/near)^(k/S), near (far/near)^((k+1)/S)].
// A light is listed in a froxel when its bounding sphere touches the tile's frustum between the near
// and far planes (the build's first, per-tile, test), touches the froxel's eye-space box and, for a
// spot, its cone touches the sphere around that box (Wronski, "Cull that cone", 2017). Each
// froxel lists at most kMaxLightsPerCluster lights, the lowest indices first; lights past the cap are
// dropped there (counted, warned about, and shown magenta in the lights-per-cluster view).
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/local_lights.hpp"

namespace lp {

constexpr int kMaxLightsPerCluster = 256;
// light_clusters.comp gives each slice of a tile one invocation of a 64-wide work group.
constexpr int kMaxClusterSlices = 64;
// The largest light-index list the grid may allocate (clusters x cap x 4 bytes).
constexpr double kMaxClusterListBytes = 1024.0 * 1024.0 * 1024.0;

struct ClusterGrid {
    int tilesX = 1, tilesY = 1, slices = 1;
    int tileSize = 32;     // pixels
    int width = 1, height = 1;  // the image the tiles cover
    float nearPlane = 0.1f, farPlane = 100.0f;
    int count() const { return tilesX * tilesY * slices; }
    // Cluster index of tile (x, y) in slice k: x fastest, then y, then the slice.
    int index(int x, int y, int k) const { return (k * tilesY + y) * tilesX + x; }
};

// The grid for a width x height image; throws lp::Error when its light lists would pass
// kMaxClusterListBytes (naming the flags to change).
ClusterGrid makeClusterGrid(int width, int height, int tileSize, int slices, float nearPlane, float farPlane);

// Eye distance where slice k begins (k = slices gives the far plane).
double clusterSliceStart(const ClusterGrid& grid, int k);
// The slice holding eye distance d (clamped to the grid).
int clusterSliceOf(const ClusterGrid& grid, double d);

struct EyeBox {
    glm::dvec3 lo, hi;
};
// Eye-space box around froxel (x, y, k): its 8 corners on the rays through the tile's corners at
// the slice's two depths. `projection` is the camera's (possibly off-centre) perspective.
EyeBox froxelBox(const ClusterGrid& grid, const glm::mat4& projection, int x, int y, int k);

// Does `light`'s bounding sphere touch tile (x, y)'s frustum between the grid's near and far planes
// (its four side planes through the eye)? `margin` as below.
bool lightTouchesTileColumn(const GpuLocalLight& light, const ClusterGrid& grid, const glm::mat4& projection, int x,
                            int y, double margin);

// Does `light` (eye space, as the shaders read it) reach into `box`? Conservative: true for every
// light that does; `margin` grows the light's bounds by that fraction (the shader uses 1e-3).
bool lightTouchesFroxel(const GpuLocalLight& light, const EyeBox& box, double margin);

// Per cluster, the indices of the lights that pass lightTouchesTileColumn and lightTouchesFroxel
// (uncapped), in index order.
std::vector<std::vector<int>> referenceClusterLists(const ClusterGrid& grid, const glm::mat4& projection,
                                                    const std::vector<GpuLocalLight>& lights, double margin);

}  // namespace lp
