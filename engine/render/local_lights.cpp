#include "engine/render/local_lights.hpp"

#include "engine/render/frame_data.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

namespace lp {

namespace {
// Deterministic hash to [0, 1): light i of a demo set does not depend on how many are asked for.
float hash01(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return float(x >> 8) * (1.0f / 16777216.0f);
}
}  // namespace

BoundingSphere localLightBounds(const PointLight& light) {
    if (!light.spot) return {light.position, light.range};
    const double a = glm::radians(double(light.spot->outerDegrees));
    const double r = light.range;
    const glm::dvec3 axis(light.spot->direction);
    double along, radius;
    if (a <= M_PI / 4.0) {
        along = radius = r / (2.0 * std::cos(a));
    } else {
        along = r * std::cos(a);
        radius = r * std::sin(a);
    }
    return {glm::vec3(glm::dvec3(light.position) + along * axis), float(radius)};
}

namespace {
// view * (p, w) for w = 1 (a point) and w = 0 (a direction), summed as glm's mat4 * vec4 sums,
// (m0 x + m1 y) + (m2 z + m3 w), so the results are the same bits; written out because the
// library's operator is not inlined here and cost ~25 ns a light (16384 lights: 0.8 ms a frame).
glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) {
    return (glm::vec3(m[0]) * p.x + glm::vec3(m[1]) * p.y) + (glm::vec3(m[2]) * p.z + glm::vec3(m[3]));
}
glm::vec3 transformDirection(const glm::mat4& m, glm::vec3 d) {
    return (glm::vec3(m[0]) * d.x + glm::vec3(m[1]) * d.y) + glm::vec3(m[2]) * d.z;
}
}  // namespace

GpuLocalLight gpuLocalLight(const PointLight& l, const glm::mat4& view, int shadowLayer, int pointShadowCube) {
    GpuLocalLight g;
    g.positionRange = glm::vec4(transformPoint(view, l.position), l.range);
    float cosInner = -1.5f, cosOuter = -2.0f;  // a point light: lpSpotFalloff is exactly 1 everywhere
    glm::vec3 axis(0.0f, 0.0f, -1.0f);
    if (l.spot) {
        cosInner = float(std::cos(glm::radians(double(l.spot->innerDegrees))));
        cosOuter = float(std::cos(glm::radians(double(l.spot->outerDegrees))));
        axis = glm::normalize(transformDirection(view, l.spot->direction));
    }
    g.intensity = glm::vec4(l.color * l.intensity, cosInner);
    g.directionCos = glm::vec4(axis, cosOuter);
    if (l.spot) {
        const BoundingSphere b = localLightBounds(l);
        g.bound = glm::vec4(transformPoint(view, b.center), b.radius);
    } else {
        g.bound = g.positionRange;  // a point light's bounds: its range sphere (localLightBounds)
    }
    g.shadow = glm::vec4(float(shadowLayer), float(pointShadowCube), 0.0f, 0.0f);
    return g;
}

std::vector<PointLight> generateDemoLights(glm::vec3 lo, glm::vec3 hi, int count) {
    std::vector<PointLight> out;
    if (count <= 0) return out;
    const glm::vec3 size = glm::max(hi - lo, glm::vec3(1e-3f));
    // Range so that about 8 lights overlap a point in a box filled with `count` spheres.
    const float volume = size.x * size.y * size.z;
    const float range = std::cbrt(8.0f * volume / (4.18879f * float(count)));
    out.reserve(size_t(count));
    for (int i = 0; i < count; ++i) {
        const uint32_t s = uint32_t(i) * 8u;
        PointLight l;
        l.position = lo + size * glm::vec3(hash01(s + 1), hash01(s + 2), hash01(s + 3));
        const float hue = hash01(s + 4) * 6.0f;
        glm::vec3 c = glm::clamp(glm::vec3(std::abs(hue - 3.0f) - 1.0f, 2.0f - std::abs(hue - 2.0f),
                                           2.0f - std::abs(hue - 4.0f)),
                                 0.0f, 1.0f);
        l.color = glm::mix(glm::vec3(1.0f), c, 0.7f);
        l.range = range * (0.6f + 0.8f * hash01(s + 5));
        // Irradiance 0.25 at a quarter of the range (before the window), whatever the scale.
        l.intensity = 0.25f * (0.25f * l.range) * (0.25f * l.range);
        l.orbitCenter = glm::vec3(0.5f * (lo.x + hi.x), l.position.y, 0.5f * (lo.z + hi.z));
        l.orbitSpeed = 0.2f + 0.3f * hash01(s + 6);
        out.push_back(l);
    }
    return out;
}

glm::vec3 orbitPosition(const PointLight& light, float time) {
    if (light.orbitSpeed == 0.0f) return light.position;
    // The rotation about +Y written out (x and z as glm::rotate's matrix gives them, the height kept
    // exactly) rather than a 4x4 matrix built and applied per light and frame.
    const float angle = light.orbitSpeed * time;
    const float c = std::cos(angle), s = std::sin(angle);
    const glm::vec3 v = light.position - light.orbitCenter;
    return light.orbitCenter + glm::vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}

int localLightCount(const Scene& scene, const LocalLightSettings& settings) {
    if (!settings.enabled) return 0;
    if (settings.lightCount < 0) return int(scene.pointLights.size());
    return settings.lightCount;
}

std::shared_ptr<const std::vector<PointLight>> frameLocalLights(const FrameData& frame) {
    if (frame.localLights) return frame.localLights;
    return std::make_shared<const std::vector<PointLight>>(
        localLightsForFrame(*frame.scene, frame.settings->localLights, frame.time));
}

std::vector<PointLight> localLightsForFrame(const Scene& scene, const LocalLightSettings& settings, float time) {
    const int count = localLightCount(scene, settings);
    std::vector<PointLight> lights(scene.pointLights.begin(),
                                   scene.pointLights.begin() + std::min<long>(count, long(scene.pointLights.size())));
    if (int(lights.size()) < count) {
        glm::vec3 lo, hi;
        scene.bounds(lo, hi);
        if (!(glm::all(glm::lessThan(lo, hi)))) {  // no models: a 10 m box around the camera's target
            lo = scene.camera.target - glm::vec3(5.0f);
            hi = scene.camera.target + glm::vec3(5.0f);
        }
        std::vector<PointLight> demo = generateDemoLights(lo, hi, count - int(lights.size()));
        lights.insert(lights.end(), demo.begin(), demo.end());
    }
    for (auto& l : lights) {
        if (l.spot && l.orbitSpeed != 0.0f) {  // the spot turns with its orbit
            const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), l.orbitSpeed * time, glm::vec3(0.0f, 1.0f, 0.0f));
            l.spot->direction = glm::normalize(glm::vec3(turn * glm::vec4(l.spot->direction, 0.0f)));
        }
        l.position = orbitPosition(l, time);
        l.orbitSpeed = 0.0f;
        l.range *= settings.rangeScale;  // --light-range-scale: shading and every method's bounds agree
        // Any finite range is allowed in a scene; past 1e7 m the window is 1 wherever anything is drawn
        // (the far plane is at most 1e7 m), and bounds math stays far from float overflow.
        l.range = std::min(l.range, 1e7f);
    }
    return lights;
}

ScissorRect sphereScissorRect(glm::vec3 centerEye, float radius, const glm::mat4& projection, float nearPlane, int width,
                              int height) {
    ScissorRect full{0, 0, width, height, true};
    const glm::dvec3 c(centerEye);
    const double r = radius;
    if (c.z - r >= -double(nearPlane)) return {};  // wholly behind the near plane: invisible
    if (c.z + r >= -double(nearPlane)) return full;  // crosses the near plane (or holds the eye)
    // Per screen axis, the two planes through the eye (containing the other screen axis) tangent to
    // the sphere touch it at points whose projections are the rectangle's edges; a 2D problem in
    // (c.axis, c.z). |c| > r here because c.z + r < -near < 0.
    double ndcLo[2], ndcHi[2];
    for (int axis = 0; axis < 2; ++axis) {
        const double a = c[axis], z = c.z;
        const double len2 = a * a + z * z;
        const double len = std::sqrt(len2);
        const double t = std::sqrt(len2 - r * r);  // distance from the eye to the tangent points
        const double cosA = t / len, sinA = r / len;
        const double ua = a / len, uz = z / len;
        const double scale = projection[axis][axis], shear = projection[2][axis];
        double ndc[2];
        for (int s = 0; s < 2; ++s) {
            const double sign = s == 0 ? 1.0 : -1.0;
            const double pa = t * (ua * cosA - sign * uz * sinA);
            const double pz = t * (sign * ua * sinA + uz * cosA);
            ndc[s] = (scale * pa + shear * pz) / -pz;  // pz < 0: the tangent points lie on the sphere
        }
        ndcLo[axis] = std::min(ndc[0], ndc[1]);
        ndcHi[axis] = std::max(ndc[0], ndc[1]);
    }
    const double size[2] = {double(width), double(height)};
    int lo[2], hi[2];
    for (int axis = 0; axis < 2; ++axis) {
        // Outward rounding with a small margin against float rounding in the pixel positions.
        const double eps = 1e-4;
        double p0 = std::floor((ndcLo[axis] * 0.5 + 0.5) * size[axis] - eps);
        double p1 = std::ceil((ndcHi[axis] * 0.5 + 0.5) * size[axis] + eps);
        lo[axis] = int(std::clamp(p0, 0.0, size[axis]));
        hi[axis] = int(std::clamp(p1, 0.0, size[axis]));
    }
    ScissorRect rect{lo[0], lo[1], hi[0] - lo[0], hi[1] - lo[1], false};
    if (rect.empty()) return {};
    return rect;
}

std::vector<glm::vec3> circumscribingIcosphere(int subdivisions) {
    const float p = (1.0f + std::sqrt(5.0f)) * 0.5f;
    std::vector<glm::vec3> v = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                                {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    for (auto& x : v) x = glm::normalize(x);
    std::vector<std::array<uint32_t, 3>> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                  {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                  {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                  {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto mid = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            midpoints[key] = uint32_t(v.size() - 1);
            return uint32_t(v.size() - 1);
        };
        std::vector<std::array<uint32_t, 3>> next;
        for (const auto& f : faces) {
            uint32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces = std::move(next);
    }
    // The vertices lie on the unit sphere, so the faces cut inside it: scale by 1 / (smallest
    // distance from the origin to a face plane), plus 0.1% against rounding in the vertex shader.
    double inradius = 1.0;
    for (const auto& f : faces) {
        glm::dvec3 a(v[f[0]]), b(v[f[1]]), c(v[f[2]]);
        glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        inradius = std::min(inradius, std::abs(glm::dot(n, a)));
    }
    const float scale = float(1.001 / inradius);
    std::vector<glm::vec3> tris;
    tris.reserve(faces.size() * 3);
    for (const auto& f : faces) {
        glm::vec3 a = v[f[0]], b = v[f[1]], c = v[f[2]];
        if (glm::dot(glm::cross(b - a, c - a), a) < 0.0f) std::swap(b, c);  // counter-clockwise seen from outside
        for (glm::vec3 x : {a, b, c}) tris.push_back(x * scale);
    }
    return tris;
}

}  // namespace lp
