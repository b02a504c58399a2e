#include "app/pass_rows.hpp"

#include <algorithm>
#include <functional>

#include "engine/core/error.hpp"
#include "engine/render/local_lights.hpp"
#include "frame/frame_builder.hpp"

namespace lp::app {
namespace {

std::string withoutPrefix(const std::string& text, const std::string& prefix) {
    return text.compare(0, prefix.size(), prefix) == 0 ? text.substr(prefix.size()) : text;
}

}  // namespace

const char* passRowStateName(PassRowState state) {
    switch (state) {
        case PassRowState::Runs: return "runs";
        case PassRowState::Culled: return "culled";
        case PassRowState::Skipped: return "skipped";
        case PassRowState::Off: return "off";
        case PassRowState::Absent: return "not in this frame";
    }
    return "?";
}

void updatePassRows(std::vector<PassRow>& rows, const std::vector<fg::PassDecision>& decisions,
                    const std::set<std::string>& disabledPasses) {
    for (PassRow& row : rows) {
        row.state = PassRowState::Absent;
        row.reason = "not a candidate in this view or with these settings";
    }
    std::set<std::string> seenThisFrame;
    size_t insertAt = 0;  // just after the row of the pass considered before
    for (const fg::PassDecision& d : decisions) {
        if (d.name.find(' ') != std::string::npos) continue;  // a note on a pass
        auto it = std::find_if(rows.begin(), rows.end(), [&](const PassRow& r) { return r.name == d.name; });
        if (it == rows.end()) {
            PassRow added;
            added.name = d.name;
            it = rows.insert(rows.begin() + std::ptrdiff_t(std::min(insertAt, rows.size())), added);
        }
        insertAt = size_t(it - rows.begin()) + 1;
        PassRow& row = *it;
        // A name added twice in one frame (upscale of the HDR image and of a debug view) is one
        // switch: it runs if either copy runs.
        const bool again = !seenThisFrame.insert(d.name).second;
        if (again && (row.state == PassRowState::Runs || row.state == PassRowState::Off)) continue;
        if (disabledPasses.count(d.name)) {
            row.state = PassRowState::Off;
            row.reason = d.reason;
        } else if (d.runs) {
            row.state = PassRowState::Runs;
            row.reason.clear();
        } else if (d.reason.compare(0, 9, "skipped: ") == 0) {
            row.state = PassRowState::Skipped;
            row.reason = withoutPrefix(d.reason, "skipped: ");
        } else {
            row.state = PassRowState::Culled;
            row.reason = withoutPrefix(d.reason, "culled: ");
        }
    }
}

std::vector<PassRow> candidatePassRows(const Scene& scene, const RenderSettings& settings) {
    std::vector<RenderSettings> variants;
    auto with = [&](const std::function<void(RenderSettings&)>& change) {
        RenderSettings v = settings;
        v.disabledPasses.clear();
        change(v);
        variants.push_back(v);
    };
    with([](RenderSettings&) {});
    std::vector<DebugView> views = allViews();
    for (DebugView v : localLightViews()) views.push_back(v);
    for (DebugView view : views) with([&](RenderSettings& s) { s.view = view; });
    with([](RenderSettings& s) { s.post.bloom = true; });
    with([](RenderSettings& s) { s.post.bloom = true; s.post.bloomOnly = true; });  // '8'
    with([](RenderSettings& s) { s.post.toon = true; });                             // '7'
    with([](RenderSettings& s) { s.motionBlur.enabled = true; });
    for (AntiAliasing aa : {AntiAliasing::Off, AntiAliasing::Fxaa, AntiAliasing::Taa, AntiAliasing::Ssaa})
        with([&](RenderSettings& s) { s.aa.method = aa; });
    with([](RenderSettings& s) { s.renderScale = 0.5f; });
    with([](RenderSettings& s) { s.renderPath = RenderPath::ForwardPlus; });
    for (LocalLightMethod method : allLocalLightMethods())
        with([&](RenderSettings& s) { s.localLights.enabled = true; s.localLights.method = method; });
    with([](RenderSettings& s) { s.environment.ibl = true; s.shadows.enabled = true; s.ao.enabled = true; });
    with([](RenderSettings& s) { s.shadows.enabled = false; });
    with([](RenderSettings& s) { s.allPasses = true; });

    std::vector<PassRow> rows;
    for (const RenderSettings& v : variants) {
        try {
            FrameData frame = makeFrameData(scene, v, 0.0f);
            fg::FrameGraph graph;
            PassStates passes;  // never executed: naming the candidates needs no GPU
            buildFrameGraph(graph, passes, frame);
            graph.compile();
            updatePassRows(rows, graph.explain(), {});
        } catch (const Error&) {
            // a combination the renderer refuses brings no pass the panel could reach
        }
    }
    for (PassRow& row : rows) {
        row.state = PassRowState::Absent;
        row.reason = "not a candidate in this view or with these settings";
    }
    return rows;
}

}  // namespace lp::app
