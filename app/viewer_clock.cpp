#include "app/viewer_clock.hpp"

#include <algorithm>

namespace lp::app {

void ViewerClock::advance(double wallSeconds) {
    if (playing && wallSeconds > 0.0) time += wallSeconds * double(speed);
}

void ViewerClock::scaleSpeed(float factor) { speed = std::clamp(speed * factor, kMinSpeed, kMaxSpeed); }

double clockRange(const Scene& scene) {
    double range = 0.0;
    for (const ModelInstance& m : scene.models)
        if (m.animation)
            for (int c : m.playingClips) range = std::max(range, double(m.animation->clips[size_t(c)].duration));
    if (range <= 0.0 && scene.cameraPath && !scene.cameraPath->keys.empty()) range = scene.cameraPath->keys.back().time;
    return range > 0.0 ? range : 10.0;
}

}  // namespace lp::app
