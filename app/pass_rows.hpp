#pragma once
// The viewer panel's pass list as data: one row per candidate pass seen since the scene loaded, in a
// stable order, with this frame's state. A row never moves or disappears when its pass is switched
// off, culled or skipped, so a second click lands on the same pass.
#include <set>
#include <string>
#include <vector>

#include "engine/graph/frame_graph.hpp"

namespace lp::app {

enum class PassRowState {
    Runs,
    Culled,   // added, but nothing live reads what it writes
    Skipped,  // the frame builder left it out (no shadow-casting light, bloom off, ...)
    Off,      // switched off by the user (its checkbox, --disable-pass)
    Absent,   // not a candidate of this frame at all (e.g. debug_view outside the channel views)
};

struct PassRow {
    std::string name;
    PassRowState state = PassRowState::Absent;
    std::string reason;  // why it does not run; empty when it runs
    // Centre of the row's checkbox where the panel last drew it (window pixels), for --panel-rows-out.
    float checkboxX = 0.0f, checkboxY = 0.0f;
};

// "runs", "culled", "skipped", "off", "not in this frame".
const char* passRowStateName(PassRowState state);

// Sets every row's state from this frame's decisions (FrameGraph::explain()) and the user's
// switched-off passes. Rows keep their places; a pass seen for the first time goes right after the
// pass considered before it; a known pass missing from this frame stays, as Absent.
void updatePassRows(std::vector<PassRow>& rows, const std::vector<fg::PassDecision>& decisions,
                    const std::set<std::string>& disabledPasses);

}  // namespace lp::app
