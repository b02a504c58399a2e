// The viewer's scene clock (app/viewer_clock.hpp): plays at its speed, holds while paused, keeps its
// speed in range, and its slider spans the longest playing clip, else the camera path.
#include <gtest/gtest.h>

#include <memory>

#include "app/viewer_clock.hpp"

using namespace lp;
using namespace lp::app;

TEST(ViewerClock, PlaysAtItsSpeedAndHoldsWhilePaused) {
    ViewerClock c;
    EXPECT_TRUE(c.playing);  // the viewer opens playing, at 1x
    c.advance(0.5);
    EXPECT_DOUBLE_EQ(c.time, 0.5);
    c.scaleSpeed(2.0f);
    c.advance(0.25);
    EXPECT_DOUBLE_EQ(c.time, 1.0);
    c.playing = false;
    c.advance(3.0);
    EXPECT_DOUBLE_EQ(c.time, 1.0);
    c.advance(-1.0);  // a clock never runs back on its own
    EXPECT_DOUBLE_EQ(c.time, 1.0);
    for (int i = 0; i < 10; ++i) c.scaleSpeed(2.0f);
    EXPECT_EQ(c.speed, ViewerClock::kMaxSpeed);
    for (int i = 0; i < 20; ++i) c.scaleSpeed(0.5f);
    EXPECT_EQ(c.speed, ViewerClock::kMinSpeed);
}

// What Space, '[' and ']' (and the panel's button) print: the state, the time and the speed.
TEST(ViewerClock, KeysSayWhatTheyDid) {
    ViewerClock c;
    c.advance(3.2);
    EXPECT_EQ(c.togglePlaying(), "clock paused at 3.20 s (speed x1.00)");
    EXPECT_FALSE(c.playing);
    EXPECT_EQ(c.changeSpeed(2.0f), "clock speed x2.00 (paused: Space plays)");
    EXPECT_EQ(c.togglePlaying(), "clock playing at 3.20 s (speed x2.00)");
    EXPECT_EQ(c.changeSpeed(0.5f), "clock speed x1.00");
}

TEST(ViewerClock, RangeIsTheLongestPlayingClipElseThePath) {
    Scene scene;
    EXPECT_EQ(clockRange(scene), 10.0);
    CameraPath path;
    path.keys.resize(2);
    path.keys[1].time = 4.0f;
    scene.cameraPath = path;
    EXPECT_EQ(clockRange(scene), 4.0);
    ModelInstance m;
    auto anim = std::make_shared<NodeAnimation>();
    anim->clips.resize(2);
    anim->clips[0].duration = 1.5f;
    anim->clips[1].duration = 7.0f;
    m.animation = anim;
    m.playingClips = {0};
    scene.models.push_back(m);
    EXPECT_EQ(clockRange(scene), 1.5);
    scene.models[0].playingClips = {0, 1};
    EXPECT_EQ(clockRange(scene), 7.0);
}
