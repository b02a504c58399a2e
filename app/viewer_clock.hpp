#pragma once
// The viewer's scene clock: the time its frames are rendered at (animated glTF models, orbiting
// lights and the camera path all follow it), played, paused, scrubbed and sped up by the keys and
// the panel's "animation" section (docs/viewer.md).
#include <string>

#include "engine/scene/scene.hpp"

namespace lp::app {

struct ViewerClock {
    double time = 0.0;   // seconds of scene time
    bool playing = true;
    float speed = 1.0f;  // scene seconds per wall-clock second, kMinSpeed..kMaxSpeed
    static constexpr float kMinSpeed = 0.05f, kMaxSpeed = 8.0f;
    // Moves on by `wallSeconds` x speed while playing; paused it stays.
    void advance(double wallSeconds);
    // The speed halved or doubled (keys), kept within [kMinSpeed, kMaxSpeed].
    void scaleSpeed(float factor);
    // Space and the panel's button: playing <-> paused; the line the viewer prints
    // ("clock paused at 3.20 s (speed x1.00)").
    std::string togglePlaying();
    // '[' and ']': scaleSpeed, and the line the viewer prints ("clock speed x2.00").
    std::string changeSpeed(float factor);
};

// What the panel's time slider spans: the longest clip the scene's models play, else the camera
// path's last key time, else 10 s.
double clockRange(const Scene& scene);

}  // namespace lp::app
