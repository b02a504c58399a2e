#include "app/viewer_clock.hpp"

#include <algorithm>
#include <cstdio>

namespace lp::app {

void ViewerClock::advance(double wallSeconds) {
    if (playing && wallSeconds > 0.0) time += wallSeconds * double(speed);
}

void ViewerClock::scaleSpeed(float factor) { speed = std::clamp(speed * factor, kMinSpeed, kMaxSpeed); }

std::string ViewerClock::togglePlaying() {
    playing = !playing;
    char line[96];
    std::snprintf(line, sizeof line, "clock %s at %.2f s (speed x%.2f)", playing ? "playing" : "paused", time, double(speed));
    return line;
}

std::string ViewerClock::changeSpeed(float factor) {
    scaleSpeed(factor);
    char line[96];
    std::snprintf(line, sizeof line, "clock speed x%.2f%s", double(speed), playing ? "" : " (paused: Space plays)");
    return line;
}

double clockRange(const Scene& scene) {
    double range = 0.0;
    for (const ModelInstance& m : scene.models)
        if (m.animation)
            for (int c : m.playingClips) range = std::max(range, double(m.animation->clips[size_t(c)].duration));
    if (range <= 0.0 && scene.cameraPath && !scene.cameraPath->keys.empty()) range = scene.cameraPath->keys.back().time;
    return range > 0.0 ? range : 10.0;
}

}  // namespace lp::app
