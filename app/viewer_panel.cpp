// The viewer's ImGui panel: passes with GPU times, and every render setting a user would tweak.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "app/viewer_state.hpp"
#include "engine/post/post_config.hpp"

namespace lp::app {
namespace fs = std::filesystem;

const char* const kViewerHelp =
    "1 depth   2 eye-space normals   3 diffuse colour   4 eye-space position\n"
    "5 lighting only   6 shininess   7 toon on/off   8 bloom buffer alone\n"
    "0 standard view (toon and bloom-only back to the start)\n"
    "r reset camera   x toggle scissor (local lights, scissor method)\n"
    "W/S forward/back   A/D left/right   Q/Z up/down   left-drag look\n"
    "+/- exposure   Tab hide/show panel   h this help   F12 screenshot   Esc quit";

namespace {

std::vector<fs::path> filesWithExtensions(const fs::path& dir, std::initializer_list<const char*> extensions) {
    std::vector<fs::path> found;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string ext = it->path().extension().string();
        for (const char* e : extensions)
            if (ext == e && it->is_regular_file(ec)) found.push_back(it->path().lexically_normal());
    }
    std::sort(found.begin(), found.end());
    return found;
}

// "scene file" / "off" / "on" for a setting that is unset until the user picks a side.
bool overrideCombo(const char* label, std::optional<bool>& value, bool sceneValue) {
    int current = value ? (*value ? 2 : 1) : 0;
    char sceneItem[32];
    std::snprintf(sceneItem, sizeof sceneItem, "scene (%s)", sceneValue ? "on" : "off");
    const char* items[] = {sceneItem, "off", "on"};
    if (!ImGui::Combo(label, &current, items, 3)) return false;
    value = current == 0 ? std::nullopt : std::optional<bool>(current == 2);
    return true;
}

template <typename Enum, size_t N>
void enumCombo(const char* label, Enum& value, const Enum (&options)[N], const char* (*name)(Enum)) {
    if (ImGui::BeginCombo(label, name(value))) {
        for (Enum option : options)
            if (ImGui::Selectable(name(option), option == value)) value = option;
        ImGui::EndCombo();
    }
}

const char* filterLabel(ShadowSettings::Filter f) { return ShadowSettings::filterName(f); }
const char* bloomMethodLabel(PostSettings::BloomMethod m) {
    return m == PostSettings::BloomMethod::Separable ? "separable" : "mip-chain";
}

// Why a pass is culled or skipped, wrapped under its name (greyed, indented).
void reasonText(const std::string& reason) {
    ImGui::Indent();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("%s", reason.c_str());
    ImGui::PopStyleColor();
    ImGui::Unindent();
}

void drawPasses(ViewerState& st, Renderer& renderer) {
    if (!ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg)) return;
    ImGui::TableSetupColumn("pass (untick to switch off)");
    ImGui::TableSetupColumn("GPU ms", ImGuiTableColumnFlags_WidthFixed, 64);
    ImGui::TableHeadersRow();
    for (const auto& p : renderer.graph().report()) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        bool on = !st.settings.disabledPasses.count(p.name);
        ImGui::PushID(p.name.c_str());
        const bool greyed = p.culled && !p.disabled;  // culled by the graph, not by the user
        if (greyed) ImGui::BeginDisabled();
        if (ImGui::Checkbox(p.name.c_str(), &on)) {
            if (on) st.settings.disabledPasses.erase(p.name);
            else st.settings.disabledPasses.insert(p.name);
        }
        if (greyed) ImGui::EndDisabled();
        if (p.culled && !p.reason.empty()) reasonText(p.reason);
        ImGui::PopID();
        ImGui::TableSetColumnIndex(1);
        if (p.disabled) ImGui::TextDisabled("off");
        else if (p.culled) ImGui::TextDisabled("culled");
        else ImGui::Text("%.3f", renderer.timers().median(p.name));
    }
    for (const auto& [name, reason] : renderer.graph().skippedPasses()) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextDisabled("%s", name.c_str());
        reasonText(reason);
        ImGui::TableSetColumnIndex(1);
        ImGui::TextDisabled("skipped");
    }
    ImGui::EndTable();
}

void drawLighting(ViewerState& st, const Scene& scene) {
    RenderSettings& s = st.settings;
    const Brdf brdfs[] = {Brdf::BlinnPhong, Brdf::Ggx};
    enumCombo("BRDF", s.brdf, brdfs, brdfName);
    overrideCombo("IBL", s.environment.ibl, scene.environment.ibl);
    ImGui::Checkbox("directional lights", &s.globalLighting);

    ImGui::Checkbox("local lights", &s.localLights.enabled);
    const LocalLightMethod methods[] = {LocalLightMethod::Fullscreen, LocalLightMethod::Scissor,
                                        LocalLightMethod::Volumes, LocalLightMethod::Tiled};
    enumCombo("method", s.localLights.method, methods, localLightMethodName);
    int count = s.localLights.lightCount < 0 ? int(scene.pointLights.size()) : s.localLights.lightCount;
    if (ImGui::SliderInt("light count", &count, 0, 4096, "%d", ImGuiSliderFlags_Logarithmic))
        s.localLights.lightCount = count;
    ImGui::SameLine();
    if (ImGui::SmallButton("scene's")) s.localLights.lightCount = -1;
    ImGui::Checkbox("scissor (x)", &s.localLights.scissor);
    if (s.localLights.method != LocalLightMethod::Scissor) {
        ImGui::SameLine();
        ImGui::TextDisabled("(scissor method only)");
    }

    if (ImGui::TreeNode("shadows")) {
        ShadowSettings& sh = s.shadows;
        ImGui::Checkbox("enabled", &sh.enabled);
        int sizeIndex = std::clamp(int(std::log2(float(sh.size))) - 9, 0, 3);  // 512..4096
        const char* sizes[] = {"512", "1024", "2048", "4096"};
        if (ImGui::Combo("map size", &sizeIndex, sizes, 4)) sh.size = 512 << sizeIndex;
        ImGui::SliderInt("cascades", &sh.cascades, 1, 4);
        ImGui::SliderFloat("split lambda", &sh.splitLambda, 0.0f, 1.0f, "%.2f");
        const ShadowSettings::Filter filters[] = {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3,
                                                  ShadowSettings::Filter::Pcf5x5, ShadowSettings::Filter::Poisson};
        enumCombo("filter", sh.filter, filters, filterLabel);
        ImGui::SliderFloat("depth bias", &sh.depthBias, 0.0f, 4.0f, "%.2f texels");
        ImGui::SliderFloat("slope bias", &sh.slopeBias, 0.0f, 4.0f, "%.2f");
        ImGui::SliderFloat("normal bias", &sh.normalBias, 0.0f, 4.0f, "%.2f texels");
        ImGui::TreePop();
    }
}

void drawPost(ViewerState& st, const Scene& scene) {
    PostSettings& p = st.settings.post;
    const BloomEffect& b = scene.effects.bloom;
    overrideCombo("bloom", p.bloom, b.enabled);
    const PostSettings::BloomMethod bloomMethods[] = {PostSettings::BloomMethod::Separable,
                                                      PostSettings::BloomMethod::MipChain};
    enumCombo("bloom method", p.bloomMethod, bloomMethods, bloomMethodLabel);
    int kernel = p.bloomKernel.value_or(b.kernelSize);
    if (ImGui::SliderInt("kernel (px)", &kernel, 1, 101)) p.bloomKernel = kernel | 1;  // odd: centred taps
    float threshold = p.bloomThreshold.value_or(b.threshold);
    if (ImGui::SliderFloat("threshold", &threshold, 0.0f, 10.0f, "%.2f")) p.bloomThreshold = threshold;
    float strength = p.bloomStrength.value_or(b.strength);
    if (ImGui::SliderFloat("strength", &strength, 0.0f, 1.0f, "%.3f")) p.bloomStrength = strength;
    if (ImGui::Checkbox("bloom buffer alone (8)", &p.bloomOnly) && p.bloomOnly) p.bloom = true;

    const ToonEffect& t = scene.effects.toon;
    overrideCombo("toon (7)", p.toon, t.enabled);
    int levels = p.toonLevels.value_or(t.levels);
    if (ImGui::SliderInt("toon levels", &levels, 1, 16)) p.toonLevels = levels;
    float edge = p.toonEdge.value_or(t.edgeThreshold);
    if (ImGui::SliderFloat("depth edge", &edge, 0.01f, 2.0f, "%.2f")) p.toonEdge = edge;
    ImGui::SliderFloat("normal edge", &p.toonNormalEdge, 0.01f, 1.0f, "%.2f");
}

void filePicker(const char* label, const std::vector<fs::path>& files, const fs::path& current,
                std::optional<fs::path>& request, const char* noneItem) {
    std::string shown = !current.empty() ? current.filename().string() : noneItem ? noneItem : "(generated)";
    if (!ImGui::BeginCombo(label, shown.c_str())) return;
    if (noneItem && ImGui::Selectable(noneItem, current.empty())) request = fs::path();
    for (const auto& f : files) {
        std::string item = f.parent_path().filename().string() + "/" + f.filename().string();
        std::error_code ec;
        if (ImGui::Selectable(item.c_str(), fs::equivalent(f, current, ec))) request = f;
    }
    ImGui::EndCombo();
}

}  // namespace

PickerFiles findPickerFiles(const fs::path& repositoryRoot) {
    PickerFiles files;
    for (const fs::path& dir : {repositoryRoot / "scenes", repositoryRoot / "../shared/assets"})
        for (auto& f : filesWithExtensions(dir, {".json", ".obj"})) files.scenes.push_back(f);
    for (const fs::path& dir : {repositoryRoot / "hdr", repositoryRoot / "../shared/assets"})
        for (auto& f : filesWithExtensions(dir, {".exr", ".hdr"})) files.environments.push_back(f);
    return files;
}

void drawViewerPanel(ViewerState& st, Renderer& renderer, const Scene& scene, const gl::GpuContext& ctx,
                     const PickerFiles& files) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    // Fits its content (it shrinks when a section collapses), fixed width, never taller than the window.
    ImGui::SetNextWindowSizeConstraints(ImVec2(380, 60), ImVec2(380, std::max(60.0f, ImGui::GetIO().DisplaySize.y - 16)));
    ImGui::Begin("lightpass   (Tab hides, h lists the keys)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::TextUnformatted(ctx.info().renderer.c_str());

    if (!st.shaderError.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("shader reload failed, still running the last good programs:\n%s", st.shaderError.c_str());
        ImGui::PopStyleColor();
    } else if (!st.shaderStatus.empty()) {
        ImGui::TextDisabled("%s", st.shaderStatus.c_str());
    }

    std::vector<float> ms(st.frameMs.begin(), st.frameMs.end());
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "frame %.1f ms  (GPU %.2f ms)", ms.empty() ? 0.0f : ms.back(),
                  renderer.timers().median("frame"));
    // Scale to the slowest recent frame so a one-off hitch (an environment bake) reads as a spike.
    const float top = ms.empty() ? 1.0f : *std::max_element(ms.begin(), ms.end()) * 1.1f;
    ImGui::PlotLines("##frame", ms.data(), int(ms.size()), 0, overlay, 0.0f, top, ImVec2(ImGui::GetContentRegionAvail().x, 48));

    if (ImGui::CollapsingHeader("passes (GPU ms, rolling median)", ImGuiTreeNodeFlags_DefaultOpen)) {
        drawPasses(st, renderer);
        ImGui::TextDisabled("transient textures: %.1f MiB in %zu", renderer.pool().totalBytes() / 1048576.0,
                            renderer.pool().textureCount());
    }

    if (ImGui::CollapsingHeader("view", ImGuiTreeNodeFlags_DefaultOpen)) {
        std::vector<DebugView> views = allViews();
        for (DebugView v : localLightViews()) views.push_back(v);
        if (ImGui::BeginCombo("debug view", viewName(st.settings.view))) {
            for (DebugView v : views)
                if (ImGui::Selectable(viewName(v), v == st.settings.view)) st.settings.view = v;
            ImGui::EndCombo();
        }
        const ToneMapOperator ops[] = {ToneMapOperator::Lightpass, ToneMapOperator::Aces, ToneMapOperator::PbrNeutral,
                                       ToneMapOperator::Agx};
        enumCombo("tone map", st.settings.environment.toneMap, ops, toneMapName);
        ImGui::SliderFloat("exposure (EV)", &st.settings.exposureEV, -8.0f, 8.0f, "%+.1f");
        // G-buffer and lighting at a fraction of the window, upsampled before the tone map.
        ImGui::SliderFloat("render scale", &st.settings.renderScale, kMinRenderScale, 1.0f, "%.2f",
                           ImGuiSliderFlags_AlwaysClamp);
    }
    if (ImGui::CollapsingHeader("lighting")) drawLighting(st, scene);
    if (ImGui::CollapsingHeader("bloom and toon")) drawPost(st, scene);

    if (ImGui::CollapsingHeader("scene", ImGuiTreeNodeFlags_DefaultOpen)) {
        filePicker("scene file", files.scenes, st.sceneFile, st.sceneRequest, nullptr);
        filePicker("environment", files.environments, scene.environment.map, st.environmentRequest, "plain colour");
        if (!st.sceneError.empty()) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
            ImGui::TextWrapped("%s", st.sceneError.c_str());
            ImGui::PopStyleColor();
        }
    }
    if (ImGui::Button("screenshot (F12)")) st.screenshotRequested = true;
    ImGui::SameLine();
    ImGui::Checkbox("with panel", &st.screenshotWithPanel);
    if (!st.lastScreenshot.empty()) ImGui::TextDisabled("%s", st.lastScreenshot.c_str());
    ImGui::End();
}

}  // namespace lp::app
