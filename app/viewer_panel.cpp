// The viewer's ImGui panel: passes with GPU times, and every render setting a user would tweak
// (the knob widgets come from frame/knobs.cpp's table, through knobWidget()).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "app/viewer_state.hpp"
#include "frame/knobs.hpp"

namespace lp::app {
namespace fs = std::filesystem;

const char* const kViewerHelp =
    "1 depth   2 eye-space normals   3 diffuse colour   4 eye-space position\n"
    "5 lighting only   6 shininess   7 toon on/off   8 bloom buffer alone   9 velocity\n"
    "0 standard view (toon and bloom-only back to the start)\n"
    "m next material input (base-color, metallic, roughness, occlusion, emissive)\n"
    "t next lit term (term-diffuse, term-specular, clearcoat)   k clearcoat layer alone\n"
    "r reset camera   p follow the camera path   x toggle scissor (local lights, scissor method)\n"
    "c compare with the path tracer: raster, path tracer and a heat map of the error\n"
    "Space play/pause the scene clock   [ / ] clock speed halved/doubled\n"
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

// One knob's widget, as frame/knobs.cpp's table describes it: the panel's only knob widgets, so the
// panel offers the CLI's range and choices. Optional knobs show the scene's value until changed;
// "scene's" unsets them again.
void knobWidget(const KnobEntry& knob, RenderSettings& s, const Scene& scene) {
    const KnobPanel& panel = knob.panel;
    const char* knobLabel = panel.label.empty() ? knob.name.c_str() : panel.label.c_str();
    const KnobValueOrUnset value = knob.field.get(s);
    const double shown = value ? *value : knob.field.sceneValue ? knob.field.sceneValue(scene) : 0.0;
    const KnobRange& range = knob.range;
    ImGui::PushID(knob.name.c_str());
    switch (panel.widget) {
        case PanelWidget::None: break;
        case PanelWidget::Checkbox: {
            bool on = shown != 0.0;
            if (ImGui::Checkbox(knobLabel, &on)) knob.field.set(s, on ? 1.0 : 0.0);
            break;
        }
        case PanelWidget::Combo: {
            if (knob.type == KnobType::Bool) {  // optional: the scene's value, off or on
                int current = value ? (*value != 0.0 ? 2 : 1) : 0;
                const std::string sceneItem = std::string("scene (") + (shown != 0.0 ? "on" : "off") + ")";
                const char* items[] = {sceneItem.c_str(), "off", "on"};
                if (ImGui::Combo(knobLabel, &current, items, 3))
                    knob.field.set(s, current == 0 ? KnobValueOrUnset() : KnobValueOrUnset(current == 2 ? 1.0 : 0.0));
                break;
            }
            if (ImGui::BeginCombo(knobLabel, formatKnobValue(knob, shown).c_str())) {
                for (size_t i = 0; i < knob.choices.size(); ++i)
                    if (ImGui::Selectable(knob.choices[i].c_str(), double(i) == shown)) knob.field.set(s, double(i));
                ImGui::EndCombo();
            }
            break;
        }
        case PanelWidget::PowersOfTwo: {
            if (ImGui::BeginCombo(knobLabel, formatKnobValue(knob, shown).c_str())) {
                for (double p = std::exp2(std::ceil(std::log2(std::max(1.0, range.min)))); p <= range.max; p *= 2)
                    if (ImGui::Selectable(formatKnobValue(knob, p).c_str(), p == shown)) knob.field.set(s, p);
                ImGui::EndCombo();
            }
            break;
        }
        case PanelWidget::Slider:
        case PanelWidget::LogSlider: {
            if (knob.field.optional)  // room for the "scene's" button after the label
                ImGui::SetNextItemWidth(ImGui::CalcItemWidth() - ImGui::CalcTextSize("scene's").x -
                                        ImGui::GetStyle().FramePadding.x * 2 - ImGui::GetStyle().ItemSpacing.x);
            const ImGuiSliderFlags flags =
                ImGuiSliderFlags_AlwaysClamp | (panel.widget == PanelWidget::LogSlider ? ImGuiSliderFlags_Logarithmic : 0);
            bool changed = false;
            if (knob.type == KnobType::Int) {  // the table's int ranges are bounded (tests/unit/test_knob_table.cpp)
                int v = int(shown);
                changed = ImGui::SliderInt(knobLabel, &v, int(range.min), int(range.max),
                                           panel.format.empty() ? "%d" : panel.format.c_str(), flags);
                if (changed) knob.field.set(s, double(v));
            } else {
                float v = float(shown);
                const char* format = panel.format.empty() ? "%.2f" : panel.format.c_str();
                const float lo = range.minExclusive ? std::nextafter(float(range.min), FLT_MAX) : float(range.min);
                changed = range.bounded()
                              ? ImGui::SliderFloat(knobLabel, &v, lo, float(range.max), format, flags)
                              // open-ended: a drag box (a slider needs both ends)
                              : ImGui::DragFloat(knobLabel, &v, 0.01f, std::max(lo, -FLT_MAX),
                                                 std::min(float(range.max), FLT_MAX), format, flags);
                if (changed) knob.field.set(s, double(v));
            }
            if (knob.field.optional) {
                ImGui::SameLine();
                if (ImGui::SmallButton("scene's")) knob.field.set(s, std::nullopt);
            }
            break;
        }
    }
    ImGui::PopID();
}

// Room right of the widgets for the longest label of a knob drawn with its label there (checkboxes
// put theirs inside the width), so a narrow panel clips none.
float widgetLabelRoom() {
    float widest = ImGui::CalcTextSize("environment").x;  // the pickers' labels
    for (const KnobEntry& knob : knobTable())
        if (knob.panel.section != PanelSection::None && knob.panel.widget != PanelWidget::None &&
            knob.panel.widget != PanelWidget::Checkbox)
            widest = std::max(widest, ImGui::CalcTextSize(knob.panel.label.empty() ? knob.name.c_str() : knob.panel.label.c_str()).x);
    return widest + ImGui::GetStyle().ItemInnerSpacing.x;
}

// Every knob the table puts in this panel section, in table order.
void knobWidgets(PanelSection section, RenderSettings& s, const Scene& scene) {
    for (const KnobEntry& knob : knobTable())
        if (knob.panel.section == section && knob.panel.widget != PanelWidget::None) knobWidget(knob, s, scene);
}

// One line per pass, every row always there with a checkbox of the same size: switching a pass off
// changes its state text, never the rows' places (a second click lands on the same pass). The reason
// a pass does not run is clipped to the state column and shown whole on hover.
void drawPasses(ViewerState& st, Renderer& renderer) {
    if (!ImGui::BeginTable("passes", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) return;
    ImGui::TableSetupColumn("pass (untick: off)", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn("state", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("GPU ms", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("000.000").x);
    ImGui::TableHeadersRow();
    for (PassRow& p : st.passRows) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::PushID(p.name.c_str());
        bool on = !st.settings.disabledPasses.count(p.name);
        // Greyed when the graph or the builder left it out: ticking it would change nothing.
        const bool greyed = on && p.state != PassRowState::Runs;
        if (greyed) ImGui::BeginDisabled();
        if (ImGui::Checkbox(p.name.c_str(), &on)) {
            if (on) st.settings.disabledPasses.erase(p.name);
            else st.settings.disabledPasses.insert(p.name);
        }
        if (greyed) ImGui::EndDisabled();
        const ImVec2 box = ImGui::GetItemRectMin();
        p.checkboxX = box.x + ImGui::GetFrameHeight() * 0.5f;
        p.checkboxY = box.y + ImGui::GetFrameHeight() * 0.5f;
        ImGui::PopID();
        ImGui::TableSetColumnIndex(1);
        if (p.state == PassRowState::Runs) ImGui::TextUnformatted(passRowStateName(p.state));
        else if (p.state == PassRowState::Skipped) ImGui::TextDisabled("skipped: %s", p.reason.c_str());
        else ImGui::TextDisabled("%s", passRowStateName(p.state));
        if (!p.reason.empty() && ImGui::IsItemHovered())
            ImGui::SetTooltip("%s: %s", passRowStateName(p.state), p.reason.c_str());
        ImGui::TableSetColumnIndex(2);
        if (p.state == PassRowState::Runs) ImGui::Text("%.3f", renderer.timers().median(p.name));
    }
    ImGui::EndTable();
}

void drawLighting(ViewerState& st, const Scene& scene) {
    knobWidgets(PanelSection::Lighting, st.settings, scene);
    if (ImGui::TreeNodeEx("shadows", ImGuiTreeNodeFlags_DefaultOpen)) {  // every section starts open (docs/viewer.md)
        knobWidgets(PanelSection::Shadows, st.settings, scene);
        ImGui::TreePop();
    }
}

void filePicker(const char* pickerLabel, const std::vector<fs::path>& files, const fs::path& current,
                std::optional<fs::path>& request, const char* noneItem) {
    std::string shown = !current.empty() ? current.filename().string() : noneItem ? noneItem : "(generated)";
    if (!ImGui::BeginCombo(pickerLabel, shown.c_str())) return;
    if (noneItem && ImGui::Selectable(noneItem, current.empty())) request = fs::path();
    for (const auto& f : files) {
        std::string item = f.parent_path().filename().string() + "/" + f.filename().string();
        std::error_code ec;
        if (ImGui::Selectable(item.c_str(), fs::equivalent(f, current, ec))) request = f;
    }
    ImGui::EndCombo();
}

// KHR_materials_variants: every variant the scene's glTF models name, once each; "file's own" for none.
void materialVariantPicker(const Scene& scene, std::optional<std::string>& request) {
    std::vector<std::string> variants;
    std::string current;
    for (const ModelInstance& m : scene.models) {
        for (const std::string& v : m.mesh.materialVariants)
            if (std::find(variants.begin(), variants.end(), v) == variants.end()) variants.push_back(v);
        if (!m.materialVariant.empty()) current = m.materialVariant;
    }
    if (variants.empty()) return;
    const char* own = "file's own";
    if (!ImGui::BeginCombo("material variant", current.empty() ? own : current.c_str())) return;
    if (ImGui::Selectable(own, current.empty())) request = std::string();
    for (const std::string& v : variants)
        if (ImGui::Selectable(v.c_str(), v == current)) request = v;
    ImGui::EndCombo();
}

}  // namespace

PickerFiles findPickerFiles(const fs::path& repositoryRoot) {
    PickerFiles files;
    for (const fs::path& dir : {repositoryRoot / "scenes", repositoryRoot / "models", repositoryRoot / "../shared/assets"})
        for (auto& f : filesWithExtensions(dir, {".json", ".obj", ".gltf", ".glb"})) files.scenes.push_back(f);
    for (const fs::path& dir : {repositoryRoot / "hdr", repositoryRoot / "../shared/assets"})
        for (auto& f : filesWithExtensions(dir, {".exr", ".hdr"})) files.environments.push_back(f);
    return files;
}

void drawViewerPanel(ViewerState& st, Renderer& renderer, const Scene& scene, const gl::GpuContext& ctx,
                     const PickerFiles& files) {
    // A sidebar docked at the window's left edge, full height: the image is rendered beside it
    // (app/viewer_layout.hpp), never under it. Its right edge drags to widen it (up to all but 64 px
    // of the window); ImGui's ini file (app/viewer.cpp) remembers the width.
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelDefaultWidth, display.y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(220, display.y), ImVec2(std::max(220.0f, display.x - 64), display.y));
    // "###": the ini file keys the layout by this id, not by the title text.
    ImGui::Begin("lightpass   (Tab hides, h lists the keys)###lightpass panel", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse);
    st.panelX = ImGui::GetWindowPos().x;
    st.panelY = ImGui::GetWindowPos().y;
    st.panelWidth = ImGui::GetWindowWidth();
    st.panelHeight = ImGui::GetWindowHeight();
    // Widgets take the width less room for their labels, so labels stay inside a narrow panel.
    ImGui::PushItemWidth(-widgetLabelRoom());
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
        const LocalLightStats& lights = renderer.localLightStats();
        if (st.settings.localLights.method == LocalLightMethod::Clustered && lights.froxelKernelMs >= 0.0)
            ImGui::TextDisabled("clustered kernel: %s%s (froxels %.3f ms, tiles %.3f ms)",
                                lights.slicesShaded ? "froxels" : "tiles", lights.kernelRacing ? ", timing both" : "",
                                lights.froxelKernelMs, lights.tileKernelMs);
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
        knobWidgets(PanelSection::View, st.settings, scene);
        if (st.cameraPath) {  // the scene's camera path on the viewer's clock; moving by hand stops it
            bool follow = st.followPath;
            if (ImGui::Checkbox("follow camera path (p)", &follow)) st.togglePath = true;
        }
        // Truth beside the frame (app/viewer_compare.hpp): greyed, with the reason, where it cannot run.
        const std::string why = truthComparisonUnavailable(st.settings);
        ImGui::BeginDisabled(!why.empty() && !st.compareWithTruth);
        if (ImGui::Checkbox("compare with the path tracer (c)", &st.compareWithTruth)) st.comparison.describedStats.clear();
        ImGui::EndDisabled();
        if (!why.empty() && !st.compareWithTruth) ImGui::TextDisabled("  %s", why.c_str());
    }
    if (ImGui::CollapsingHeader("animation", ImGuiTreeNodeFlags_DefaultOpen)) {
        // The scene clock (animated models, orbiting lights, the camera path): play/pause, scrub, speed.
        ViewerClock& clock = st.clock;
        if (ImGui::Button(clock.playing ? "pause (Space)" : "play (Space)")) {  // says what it did, as Space does
            std::printf("%s\n", clock.togglePlaying().c_str());
            std::fflush(stdout);
        }
        ImGui::SameLine();
        ImGui::Text("%.2f s", clock.time);
        const double range = clockRange(scene);
        float t = float(clock.time - std::floor(clock.time / range) * range);  // where in the loop
        if (ImGui::SliderFloat("time (s)", &t, 0.0f, float(range), "%.2f")) {
            clock.time = double(t);
            st.clockJumped = true;
        }
        ImGui::SliderFloat("speed ([ ])", &clock.speed, ViewerClock::kMinSpeed, ViewerClock::kMaxSpeed, "x%.2f",
                           ImGuiSliderFlags_Logarithmic);
    }
    if (ImGui::CollapsingHeader("lighting", ImGuiTreeNodeFlags_DefaultOpen)) drawLighting(st, scene);
    if (ImGui::CollapsingHeader("bloom, toon and motion blur", ImGuiTreeNodeFlags_DefaultOpen))
        knobWidgets(PanelSection::Post, st.settings, scene);

    if (ImGui::CollapsingHeader("scene", ImGuiTreeNodeFlags_DefaultOpen)) {
        filePicker("scene file", files.scenes, st.sceneFile, st.sceneRequest, nullptr);
        filePicker("environment", files.environments, scene.environment.map, st.environmentRequest, "plain colour");
        materialVariantPicker(scene, st.materialVariantRequest);
        // Seed 003's flat lighting, per material: shown as its colour, no light adds to it.
        if (ImGui::TreeNodeEx("flat-lit materials", ImGuiTreeNodeFlags_DefaultOpen)) {
            const std::vector<GpuMaterial>& materials = renderer.sceneGpu().materials;
            for (size_t i = 0; i < materials.size(); ++i) {
                const GpuMaterial& m = materials[i];
                bool flat = m.flat;
                ImGui::PushID(int(i));
                if (ImGui::Checkbox(m.name.c_str(), &flat)) renderer.setMaterialFlat(i, flat);
                ImGui::PopID();
            }
            ImGui::TreePop();
        }
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
    ImGui::PopItemWidth();
    ImGui::End();
}

}  // namespace lp::app
