#pragma once
// The GL state the frame graph watches: a pass must leave it as it found it (the brief's "owns no
// global GL state it does not restore"). With the LIGHTPASS_GL_STATE_CHECKS build option the graph
// captures it before the frame and compares after every pass, throwing with the pass's name.
#include <string>
#include <vector>

#include "engine/gl/gl.hpp"

namespace lp::gl {

struct WatchedState {
    // name -> value, in a fixed order; compared item by item.
    std::vector<std::pair<std::string, long long>> items;
};

// Capabilities, blend / depth / cull / polygon / clip state, colour mask, bound program, vertex
// array, framebuffers, viewport and scissor box, texture units 0..15 (2D and cube, samplers) and
// image units 0..7. Leaves the active texture unit as it was.
WatchedState captureWatchedState();
// "GL_BLEND 1 (was 0), texture unit 3 2D 17 (was 0)"; empty when nothing changed.
std::string describeStateChange(const WatchedState& before, const WatchedState& after);

}  // namespace lp::gl
