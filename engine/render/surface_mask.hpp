#pragma once
// Which pixels of a camera's frame see a surface: a ray through each pixel's centre against every
// model's triangles (at their transforms; an animated glTF posed at `time`) through a BVH on the CPU. An error figure over
// these pixels alone leaves out the background, whose sky both a raster frame and the path tracer
// read from the same map.
#include <cstdint>
#include <vector>

#include "engine/scene/scene.hpp"

namespace lp {

// width x height bytes, rows top first: 1 where the pixel centre's ray meets a triangle within
// (near, far) of `camera`, else 0.
std::vector<uint8_t> surfaceMask(const Scene& scene, const Camera& camera, int width, int height, double time = 0.0);

}  // namespace lp
