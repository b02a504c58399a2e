// The viewer panel's pass rows (app/pass_rows.hpp) and where the viewer keeps its layout
// (app/config_dir.hpp): no GL, no window.
#include <gtest/gtest.h>

#include <map>

#include "app/config_dir.hpp"
#include "app/pass_rows.hpp"

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
