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
// dropped there (counted, warned about, and shown magenta in the lights-per-cluster view). The
// deferred clustered method lists tight froxels instead (referenceTightClusterLists below).
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/local_lights.hpp"

namespace lp {

constexpr int kMaxLightsPerCluster = 256;
// light_clusters.comp and light_clusters_tight.comp give each slice of a tile one invocation of
// their work group (at least 64 invocations).
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
// Eye-space box around the part of tile (x, y) between eye distances d0 and d1: its 8 corners on the
// rays through the tile's corners at both distances. `projection` is the camera's (possibly
// off-centre) perspective.
EyeBox tileBox(const ClusterGrid& grid, const glm::mat4& projection, int x, int y, double d0, double d1);
// The box around froxel (x, y, k): tileBox between the slice's two depths.
EyeBox froxelBox(const ClusterGrid& grid, const glm::mat4& projection, int x, int y, int k);

// Does `light`'s bounding sphere touch tile (x, y)'s frustum (its four side planes through the eye)
// between eye distances d0 and d1? `margin` as below. The tiled method's test, and
// shaders/common/local_light.glsl's sphereTouchesTileFrustum.
bool lightTouchesTileDepthRange(const GpuLocalLight& light, const ClusterGrid& grid, const glm::mat4& projection,
                                int x, int y, double d0, double d1, double margin);
// The same between the grid's near and far planes.
bool lightTouchesTileColumn(const GpuLocalLight& light, const ClusterGrid& grid, const glm::mat4& projection, int x,
                            int y, double margin);

// Does `light` (eye space, as the shaders read it) reach into `box`? Conservative: true for every
// light that does; `margin` grows the light's bounds by that fraction (the shader uses 1e-3).
bool lightTouchesFroxel(const GpuLocalLight& light, const EyeBox& box, double margin);

// Per cluster, the indices of the lights that pass lightTouchesTileColumn and lightTouchesFroxel
// (uncapped), in index order.
std::vector<std::vector<int>> referenceClusterLists(const ClusterGrid& grid, const glm::mat4& projection,
                                                    const std::vector<GpuLocalLight>& lights, double margin);

// Tight froxels (the deferred clustered method, shaders/local_light_clustered.comp; its lists:
// light_clusters_tight.comp): a froxel is
// tightened to the eye distances of the pixels it holds. Per cluster, the nearest and farthest
// eye distance of those pixels; none: nearest > farthest.
struct FroxelDepth {
    double nearest = 1e300, farthest = -1e300;
    bool occupied() const { return nearest <= farthest; }
};
// From each pixel's eye distance, eyeDistance[y * width + x] (row 0 at the bottom, as GL's images),
// NaN where the pixel holds no surface to light; negative distances count as 0, as the shader's.
std::vector<FroxelDepth> occupiedFroxelDepths(const ClusterGrid& grid, const std::vector<double>& eyeDistance);

// Per cluster, the lights a tight froxel lists (uncapped, in index order): for an occupied froxel
// the lights that pass lightTouchesTileDepthRange between its nearest and farthest pixel (hence
// also the whole tile's depth range, the build's first test) and lightTouchesFroxel against the box
// around that part of the tile; for an unoccupied one none. A light that only crosses the empty
// depth of a froxel is dropped; every light reaching one of its pixels is kept.
std::vector<std::vector<int>> referenceTightClusterLists(const ClusterGrid& grid, const glm::mat4& projection,
                                                         const std::vector<GpuLocalLight>& lights,
                                                         const std::vector<FroxelDepth>& depths, double margin);

}  // namespace lp
