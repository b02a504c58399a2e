#pragma once
// The viewer panel's pass list as data: one row per candidate pass seen since the scene loaded, in a
// stable order, with this frame's state. A row never moves or disappears when its pass is switched
// off, culled or skipped, so a second click lands on the same pass.
#include <set>
#include <string>
#include <vector>

#include "engine/graph/frame_graph.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

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

// Every pass the viewer's keys and panel can bring into this scene's frame, as rows in the order the
// frame builder considers them (all Absent until updatePassRows): the frame of `settings` under each
// view, then with each switch the keys and panel offer (bloom, bloom alone, toon, motion blur, every
// anti-aliasing method, a render scale below 1, forward+, every local-light method, IBL, shadows and
// AO on, and --all-passes). Graphs built on the CPU only, never executed. So the rows are fixed from
// the start: pressing '8' greys or un-greys bloom's row, it never inserts one.
std::vector<PassRow> candidatePassRows(const Scene& scene, const RenderSettings& settings);

// "runs", "culled", "skipped", "off", "not in this frame".
const char* passRowStateName(PassRowState state);

// Sets every row's state from this frame's decisions (FrameGraph::explain()) and the user's
// switched-off passes. Rows keep their places; a pass seen for the first time goes right after the
// pass considered before it; a known pass missing from this frame stays, as Absent. A decision
// whose name has a space ("shadow_map_0 cascades") is a note on a pass, not a pass: no row.
void updatePassRows(std::vector<PassRow>& rows, const std::vector<fg::PassDecision>& decisions,
                    const std::set<std::string>& disabledPasses);

}  // namespace lp::app
