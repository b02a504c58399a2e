#pragma once
// Render-and-read-back for the GL tests: one frame's HDR buffer, and image comparisons whose
// failure names the texel that differs (not two dumps of float vectors).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <gtest/gtest.h>

#include "engine/io/image_io.hpp"
#include "engine/render/settings.hpp"

namespace lp {
struct Camera;
struct FrameData;
struct Scene;
class Renderer;
}  // namespace lp

namespace lp::test {

// One untimed frame at `time` with the HDR buffer kept (settings.keepHdr), read back (rows top
// first): by a fresh Renderer of `scene`, or by `renderer` (its caches and history kept).
ImageF renderHdr(const Scene& scene, RenderSettings settings, float time = 0.0f);
ImageF renderHdr(Renderer& renderer, RenderSettings settings, float time = 0.0f);

// The G-buffer pass alone, asked for depth and velocity, for `frame` (its gpu and shaders made here).
struct VelocityImage {
    int width = 0, height = 0;
    std::vector<float> depth;          // window depth, rows bottom first
    std::vector<glm::vec2> velocity;   // gbuffer.velocity
    glm::vec2 at(int x, int y) const { return velocity[size_t(y) * size_t(width) + size_t(x)]; }
};
VelocityImage renderGBufferVelocity(const Scene& scene, FrameData frame);

// Where the centre ray of pixel (x, y) of a width x height image from `camera` meets the plane
// y = planeY (row 0 = top, as readHdr gives it); none where the ray does not reach it: the analytic
// expectation's surface point of a pixel.
std::optional<glm::dvec3> planePoint(const Camera& camera, int width, int height, int x, int y, double planeY = 0.0);
// Whether the segment a -> b passes through the axis-aligned box [lo, hi] (slab test): a CPU
// occlusion test for shadows and for what the camera sees.
bool segmentHitsBox(glm::dvec3 a, glm::dvec3 b, glm::dvec3 lo, glm::dvec3 hi);

// Every value of `a` within `tolerance` of `b` (absolute; 0: equal, NaN never passes). On failure:
// how many values differ, the first differing texel (x, y from the top, channel) with both values,
// and the largest error and where. `what` names the comparison in the message.
testing::AssertionResult imagesNear(const ImageF& a, const ImageF& b, float tolerance, const std::string& what = "");
// The same for raw values laid out `width` texels of `channels` values per row.
testing::AssertionResult valuesNear(const std::vector<float>& a, const std::vector<float>& b, int width, int channels,
                                    float tolerance, const std::string& what = "");

}  // namespace lp::test
