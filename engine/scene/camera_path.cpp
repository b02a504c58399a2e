#include "engine/scene/camera_path.hpp"

#include <algorithm>
#include <cmath>

namespace lp {

namespace {

struct Sample {
    glm::dvec3 position, target;
    double fov;
};

Sample sampleOf(const CameraKey& k) { return {glm::dvec3(k.position), glm::dvec3(k.target), double(k.fovYDegrees)}; }
Sample operator-(const Sample& a, const Sample& b) { return {a.position - b.position, a.target - b.target, a.fov - b.fov}; }
Sample operator*(const Sample& a, double s) { return {a.position * s, a.target * s, a.fov * s}; }
Sample operator+(const Sample& a, const Sample& b) { return {a.position + b.position, a.target + b.target, a.fov + b.fov}; }

// Catmull-Rom tangent (per second) at key i; one-sided at the ends of an open path, across the wrap
// of a looped one (key 0 and the last key then share the tangent of the point they both stand for).
Sample tangent(const CameraPath& path, size_t i) {
    const auto& k = path.keys;
    const size_t last = k.size() - 1;
    if (path.loop && (i == 0 || i == last)) {
        const double dt = (k[1].time - k[0].time) + (k[last].time - k[last - 1].time);
        return (sampleOf(k[1]) - sampleOf(k[last - 1])) * (1.0 / dt);
    }
    const size_t a = i == 0 ? 0 : i - 1, b = i == last ? last : i + 1;
    return (sampleOf(k[b]) - sampleOf(k[a])) * (1.0 / (k[b].time - k[a].time));
}

}  // namespace

CameraKey cameraPathAt(const CameraPath& path, double time) {
    const auto& k = path.keys;
    if (k.empty()) return {};
    if (k.size() == 1) return k[0];
    const double first = k.front().time, last = k.back().time;
    if (path.loop) {
        const double period = last - first;
        time = first + (time - first) - period * std::floor((time - first) / period);
        if (!(time < last)) time = first;  // rounding at the wrap
    }
    if (!(time > first)) return k.front();
    if (!(time < last)) return k.back();
    // The segment [i, i + 1] holding time; exactly a key's values at its time.
    const size_t i = size_t(std::upper_bound(k.begin(), k.end(), time,
                                             [](double t, const CameraKey& key) { return t < key.time; }) -
                            k.begin()) - 1;
    if (time == k[i].time) return k[i];
    const double h = k[i + 1].time - k[i].time, s = (time - k[i].time) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    const Sample p = sampleOf(k[i]) * h00 + tangent(path, i) * (h10 * h) + sampleOf(k[i + 1]) * h01 +
                     tangent(path, i + 1) * (h11 * h);
    CameraKey out;
    out.time = time;
    out.position = glm::vec3(p.position);
    out.target = glm::vec3(p.target);
    // Between two keys in (0, 180) the cubic may overshoot a little: keep the fov a valid angle.
    out.fovYDegrees = float(std::clamp(p.fov, 1.0, 179.0));
    return out;
}

}  // namespace lp
