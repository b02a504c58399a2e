#pragma once
// The GL state the frame graph watches: a pass must leave it as it found it (the brief's "owns no
// global GL state it does not restore"). Where the check is on (LIGHTPASS_GL_STATE_CHECKS=1 in the
// environment, as CTest sets for the tests) the graph captures it before the frame and compares after
// every pass, throwing with the pass's name. Always built in: turning it on rebuilds nothing.
#include <optional>
#include <string>
#include <string_view>
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

// LIGHTPASS_GL_STATE_CHECKS's value: "1" or "ON" (any case) turns the check on; "0", "OFF" or empty
// leaves it off; anything else is nullopt.
std::optional<bool> parseStateChecksFlag(std::string_view value);
// The environment's choice, read once per process: off when unset; an unknown value is one warning
// naming it, and off.
bool stateChecksFromEnvironment();

}  // namespace lp::gl
