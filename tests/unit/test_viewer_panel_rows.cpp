// The viewer panel's pass rows (app/pass_rows.hpp), the viewport beside it (app/viewer_layout.hpp)
// and where the viewer keeps its layout (app/config_dir.hpp): no GL, no window.
#include <gtest/gtest.h>

#include <map>

#include "app/config_dir.hpp"
#include "app/pass_rows.hpp"
#include "app/viewer_layout.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/frame_builder.hpp"

namespace lp::app {
namespace {

std::vector<std::string> names(const std::vector<PassRow>& rows) {
    std::vector<std::string> out;
    for (const auto& r : rows) out.push_back(r.name);
    return out;
}

const PassRow& row(const std::vector<PassRow>& rows, const std::string& name) {
    for (const auto& r : rows)
        if (r.name == name) return r;
    throw std::runtime_error("no row " + name);
}

TEST(PanelPassRows, SwitchingAPassOffKeepsEveryRowInPlace) {
    std::vector<PassRow> rows;
    const std::vector<fg::PassDecision> before = {{"ibl_bake", false, "skipped: scene has no environment map"},
                                                  {"gbuffer", true, ""},
                                                  {"sky", true, ""},
                                                  {"tonemap", true, ""}};
    updatePassRows(rows, before, {});
    EXPECT_EQ(names(rows), (std::vector<std::string>{"ibl_bake", "gbuffer", "sky", "tonemap"}));
    EXPECT_EQ(row(rows, "ibl_bake").state, PassRowState::Skipped);
    EXPECT_EQ(row(rows, "ibl_bake").reason, "scene has no environment map");
    EXPECT_EQ(row(rows, "sky").state, PassRowState::Runs);

    const std::vector<fg::PassDecision> skyOff = {{"ibl_bake", false, "skipped: scene has no environment map"},
                                                  {"gbuffer", true, ""},
                                                  {"sky", false, "disabled by the user (its input passes through)"},
                                                  {"tonemap", true, ""}};
    updatePassRows(rows, skyOff, {"sky"});
    EXPECT_EQ(names(rows), (std::vector<std::string>{"ibl_bake", "gbuffer", "sky", "tonemap"}));
    EXPECT_EQ(row(rows, "sky").state, PassRowState::Off);
    EXPECT_EQ(row(rows, "sky").reason, "disabled by the user (its input passes through)");
}

TEST(PanelPassRows, NewPassesGoAfterTheirPredecessorAndMissingOnesStay) {
    std::vector<PassRow> rows;
    updatePassRows(rows, {{"gbuffer", true, ""}, {"global_lights", true, ""}, {"tonemap", true, ""}}, {});
    // A channel view: lighting culled, tone mapping culled, debug_view appears; global_lights is
    // no longer a candidate in this made-up frame.
    updatePassRows(rows,
                   {{"gbuffer", true, ""}, {"tonemap", false, "culled: nothing live reads its writes (ldr)"},
                    {"debug_view", true, ""}},
                   {});
    EXPECT_EQ(names(rows), (std::vector<std::string>{"gbuffer", "global_lights", "tonemap", "debug_view"}));
    EXPECT_EQ(row(rows, "global_lights").state, PassRowState::Absent);
    EXPECT_EQ(row(rows, "tonemap").state, PassRowState::Culled);
    EXPECT_EQ(row(rows, "tonemap").reason, "nothing live reads its writes (ldr)");
    // Back to the final view with bloom added between global_lights and tonemap.
    updatePassRows(rows, {{"gbuffer", true, ""}, {"global_lights", true, ""}, {"bloom", true, ""}, {"tonemap", true, ""}}, {});
    EXPECT_EQ(names(rows), (std::vector<std::string>{"gbuffer", "global_lights", "bloom", "tonemap", "debug_view"}));
    EXPECT_EQ(row(rows, "debug_view").state, PassRowState::Absent);
    EXPECT_STREQ(passRowStateName(PassRowState::Absent), "not in this frame");
}

TEST(PanelPassRows, APassAddedTwiceIsOneRowThatRunsIfEitherRuns) {
    std::vector<PassRow> rows;
    updatePassRows(rows, {{"upscale", false, "culled: nothing live reads its writes (hdr)"}, {"debug_view", true, ""}, {"upscale", true, ""}}, {});
    EXPECT_EQ(names(rows), (std::vector<std::string>{"upscale", "debug_view"}));
    EXPECT_EQ(row(rows, "upscale").state, PassRowState::Runs);
}

// The frame's decisions for `settings`, as the viewer's renderer makes them (built on the CPU).
std::vector<fg::PassDecision> frameDecisions(const Scene& scene, const RenderSettings& settings) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph graph;
    PassStates passes;
    buildFrameGraph(graph, passes, frame);
    graph.compile();
    return graph.explain();
}

TEST(PanelPassRows, EveryRowIsThereFromTheStartAndBloomInsertsNone) {
    const Scene scene = loadScene(std::string(LIGHTPASS_SOURCE_DIR) + "/scenes/cornell.json");
    RenderSettings settings;
    std::vector<PassRow> rows = candidatePassRows(scene, settings);
    for (const PassRow& r : rows) EXPECT_EQ(r.state, PassRowState::Absent) << r.name;
    for (const char* name : {"gbuffer", "global_lights", "bloom", "toon", "debug_view", "taa", "fxaa", "upscale",
                             "motion_blur", "forward_opaque", "tonemap"})
        EXPECT_NO_THROW(row(rows, name)) << name;
    for (const PassRow& r : rows) EXPECT_EQ(r.name.find(' '), std::string::npos) << r.name;  // notes are no rows
    const std::vector<std::string> start = names(rows);

    // The viewer's first frame, then '8' (the bloom buffer alone), then a channel view: the same rows,
    // in the same order; only their states change.
    updatePassRows(rows, frameDecisions(scene, settings), {});
    EXPECT_EQ(names(rows), start);
    const PassRowState bloomBefore = row(rows, "bloom").state;
    EXPECT_NE(bloomBefore, PassRowState::Runs);  // cornell has no bloom of its own
    settings.post.bloom = true;
    settings.post.bloomOnly = true;
    updatePassRows(rows, frameDecisions(scene, settings), {});
    EXPECT_EQ(names(rows), start);
    EXPECT_EQ(row(rows, "bloom").state, PassRowState::Runs);
    settings.view = DebugView::Normals;
    updatePassRows(rows, frameDecisions(scene, settings), {});
    EXPECT_EQ(names(rows), start);
    EXPECT_EQ(row(rows, "debug_view").state, PassRowState::Runs);
}

TEST(ViewerViewport, BesideThePanelOrTheWholeWindow) {
    // 1280x720 window, 1:1 framebuffer: the 340-px panel's width is the image's left edge.
    ViewerViewport v = viewerViewport(1280, 720, 1280.0f, true, 340.0f);
    EXPECT_EQ(v.x, 340);
    EXPECT_EQ(v.width, 940);
    EXPECT_EQ(v.height, 720);
    // Panel hidden: the whole window.
    v = viewerViewport(1280, 720, 1280.0f, false, 340.0f);
    EXPECT_EQ(v.x, 0);
    EXPECT_EQ(v.width, 1280);
    // A framebuffer twice the window's size (a high-DPI display): the panel's width in pixels doubles.
    v = viewerViewport(2560, 1440, 1280.0f, true, 340.0f);
    EXPECT_EQ(v.x, 680);
    EXPECT_EQ(v.width, 1880);
    // A panel as wide as the window still leaves the image a pixel.
    v = viewerViewport(300, 200, 300.0f, true, 400.0f);
    EXPECT_EQ(v.width, 1);
    EXPECT_EQ(v.x, 299);
}

TEST(ViewerViewport, DragsStartOnTheImageNotOnThePanel) {
    const ViewerViewport v = viewerViewport(1280, 720, 1280.0f, true, 340.0f);
    EXPECT_FALSE(insideViewport(v, 1280, 720, 1280.0f, 720.0f, 100.0, 300.0));  // on the panel
    EXPECT_FALSE(insideViewport(v, 1280, 720, 1280.0f, 720.0f, 339.5, 300.0));
    EXPECT_TRUE(insideViewport(v, 1280, 720, 1280.0f, 720.0f, 340.0, 300.0));
    EXPECT_TRUE(insideViewport(v, 1280, 720, 1280.0f, 720.0f, 1279.0, 0.0));
    EXPECT_FALSE(insideViewport(v, 1280, 720, 1280.0f, 720.0f, 1280.0, 300.0));  // off the window
    // High DPI: window coordinates scale to framebuffer pixels.
    const ViewerViewport hi = viewerViewport(2560, 1440, 1280.0f, true, 340.0f);
    EXPECT_FALSE(insideViewport(hi, 2560, 1440, 1280.0f, 720.0f, 339.0, 300.0));
    EXPECT_TRUE(insideViewport(hi, 2560, 1440, 1280.0f, 720.0f, 341.0, 300.0));
}

TEST(ViewerConfigDir, OverrideThenXdgThenHome) {
    auto from = [](std::map<std::string, std::string> env) {
        return userConfigDir([env](const char* name) -> const char* {
            auto it = env.find(name);
            return it == env.end() ? nullptr : it->second.c_str();
        });
    };
    EXPECT_EQ(from({{"LIGHTPASS_CONFIG_DIR", "/tmp/t"}, {"XDG_CONFIG_HOME", "/x"}, {"HOME", "/h"}}), "/tmp/t");
    EXPECT_EQ(from({{"XDG_CONFIG_HOME", "/x"}, {"HOME", "/h"}}), "/x/lightpass");
    EXPECT_EQ(from({{"XDG_CONFIG_HOME", "relative"}, {"HOME", "/h"}}), "/h/.config/lightpass");  // XDG: absolute only
    EXPECT_EQ(from({{"LIGHTPASS_CONFIG_DIR", ""}, {"HOME", "/h"}}), "/h/.config/lightpass");
    EXPECT_EQ(from({}), std::filesystem::path());
}

}  // namespace
}  // namespace lp::app
