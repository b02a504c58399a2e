#pragma once
// A camera path: keyframes of position, target and vertical fov over time (scene-file field
// "cameraPath", or --camera-path FILE holding the same object; docs/motion.md).
//
// Interpolation: a cubic Hermite spline through the keys with Catmull-Rom tangents for uneven key
// times, m_i = (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1}) (units per second), on position, target and
// fov alike. It passes through every key exactly and is C1 in time (position and velocity continuous).
// The end keys take one-sided tangents. Outside the key range the camera holds the first / last key;
// with "loop" the time wraps over [t_first, t_last) and the end tangents look across the wrap (a
// closed loop repeats its first key's position, target and fov as its last key).
#include <vector>

#include <glm/glm.hpp>

namespace lp {

struct CameraKey {
    double time = 0.0;  // seconds on the scene's clock
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
    float fovYDegrees = 45.0f;
};

struct CameraPath {
    std::vector<CameraKey> keys;  // at least two, times strictly increasing (the loaders check)
    bool loop = false;
};

// The path at `time`: its key's values exactly at a key's time.
CameraKey cameraPathAt(const CameraPath& path, double time);

}  // namespace lp
