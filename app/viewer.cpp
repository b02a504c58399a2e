#include "app/viewer.hpp"

#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/context.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {
namespace {

struct ViewerState {
    RenderSettings settings;
    Camera home;
    bool scissor = true;
    bool showPanel = true;
    bool showHelp = false;
    bool screenshotRequested = false;
    bool screenshotWithPanel = false;  // --screenshot-ui: F12 captures the window, panel included
    bool dragging = false;
    double lastX = 0, lastY = 0;
    std::filesystem::path screenshotDir = ".";
    int screenshotCount = 0;
    std::deque<float> frameMs;  // frame-time graph
};

const char* kHelp =
    "1 depth   2 normals   3 diffuse   4 eye-space position   5 lighting only\n"
    "6 shininess   7 specular   8 texcoords   0 final view\n"
    "r reset camera   x toggle scissor (local lights)\n"
    "W/S forward/back   A/D left/right   Q/Z up/down   left-drag look\n"
    "+/- exposure   Tab hide/show panel   h this help   F12 screenshot   Esc quit";

void keyCallback(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;  // typing in a field
    auto* st = static_cast<ViewerState*>(glfwGetWindowUserPointer(window));
    auto& v = st->settings.view;
    switch (key) {
        case GLFW_KEY_1: v = DebugView::Depth; break;
        case GLFW_KEY_2: v = DebugView::Normals; break;
        case GLFW_KEY_3: v = DebugView::Diffuse; break;
        case GLFW_KEY_4: v = DebugView::Position; break;
        case GLFW_KEY_5: v = DebugView::Lighting; break;
        case GLFW_KEY_6: v = DebugView::Shininess; break;
        case GLFW_KEY_7: v = DebugView::Specular; break;
        case GLFW_KEY_8: v = DebugView::Texcoords; break;
        case GLFW_KEY_0: v = DebugView::Final; break;
        case GLFW_KEY_X:
            st->scissor = !st->scissor;
            std::printf("scissor %s\n", st->scissor ? "on" : "off");
            std::fflush(stdout);
            break;
        case GLFW_KEY_H: st->showHelp = !st->showHelp; break;
        case GLFW_KEY_TAB: st->showPanel = !st->showPanel; break;
        case GLFW_KEY_F12: st->screenshotRequested = true; break;
        case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: st->settings.exposureEV += 0.5f; break;
        case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: st->settings.exposureEV -= 0.5f; break;
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
        default: break;
    }
    if (key >= GLFW_KEY_0 && key <= GLFW_KEY_8) {
        std::printf("view %s\n", viewName(v));
        std::fflush(stdout);
    }
}

// Fly camera: W/S forward/back, A/D strafe, Q/Z up/down; drag with the left button to look.
void moveCamera(GLFWwindow* window, ViewerState& st, Camera& cam, float dt) {
    const ImGuiIO& io = ImGui::GetIO();
    glm::vec3 forward = glm::normalize(cam.target - cam.position);
    glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
    if (!io.WantCaptureKeyboard) {
        float speed = glm::length(cam.target - cam.position) * 0.8f * dt;
        glm::vec3 move(0.0f);
        if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move += forward;
        if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move -= forward;
        if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move += right;
        if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move -= right;
        if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) move += cam.up;
        if (glfwGetKey(window, GLFW_KEY_Z) == GLFW_PRESS) move -= cam.up;
        cam.position += move * speed;
        cam.target += move * speed;
        if (glfwGetKey(window, GLFW_KEY_R) == GLFW_PRESS) cam = st.home;
    }
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !io.WantCaptureMouse;
    if (down && st.dragging) {
        float yaw = float(x - st.lastX) * -0.005f, pitch = float(y - st.lastY) * -0.005f;
        glm::vec3 dir = cam.target - cam.position;
        glm::mat4 r = glm::rotate(glm::mat4(1.0f), yaw, cam.up);
        r = glm::rotate(r, pitch, right);
        glm::vec3 nd = glm::vec3(r * glm::vec4(dir, 0.0f));
        if (std::abs(glm::dot(glm::normalize(nd), glm::normalize(cam.up))) < 0.99f) cam.target = cam.position + nd;
    }
    st.dragging = down;
    st.lastX = x;
    st.lastY = y;
}

void takeScreenshot(ViewerState& st, Renderer& renderer) {
    std::filesystem::path base = st.screenshotDir / ("lightpass-" + std::to_string(st.screenshotCount++));
    writePng(base.string() + ".png", renderer.readDisplay());
    std::string msg = "screenshot " + base.string() + ".png";
    if (renderer.hdrTexture()) {
        writeExr(base.string() + ".exr", renderer.readHdr());
        msg += " + .exr";
    }
    std::printf("%s\n", msg.c_str());
    std::fflush(stdout);
}

void drawPanel(ViewerState& st, Renderer& renderer, const gl::GpuContext& ctx) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("lightpass (Tab hides, h help)");
    ImGui::TextUnformatted(ctx.info().renderer.c_str());

    // Frame-time graph and per-pass GPU times (rolling median of the last frames).
    std::vector<float> ms(st.frameMs.begin(), st.frameMs.end());
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "frame %.2f ms GPU", renderer.timers().median("frame"));
    ImGui::PlotLines("##frame", ms.data(), int(ms.size()), 0, overlay, 0.0f, FLT_MAX, ImVec2(-1, 48));
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms", ImGuiTableColumnFlags_WidthFixed, 70);
        ImGui::TableHeadersRow();
        for (const auto& p : renderer.graph().report()) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            // One checkbox per pass: unticking switches it off (FrameGraph::disablePass).
            bool on = !st.settings.disabledPasses.count(p.name);
            ImGui::PushID(p.name.c_str());
            if (p.culled && !p.disabled) ImGui::BeginDisabled();
            if (ImGui::Checkbox(p.name.c_str(), &on)) {
                if (on) st.settings.disabledPasses.erase(p.name);
                else st.settings.disabledPasses.insert(p.name);
            }
            if (p.culled && !p.disabled) ImGui::EndDisabled();
            if (!p.reason.empty() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
                ImGui::SetTooltip("%s", p.reason.c_str());
            ImGui::PopID();
            ImGui::TableSetColumnIndex(1);
            if (p.disabled && p.culled) ImGui::TextDisabled("off");
            else if (p.culled) ImGui::TextDisabled("culled");
            else ImGui::Text("%.3f", renderer.timers().median(p.name));
        }
        for (const auto& [name, reason] : renderer.graph().skippedPasses()) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextDisabled("   %s", name.c_str());
            if (ImGui::IsItemHovered()) ImGui::SetTooltip("skipped: %s", reason.c_str());
            ImGui::TableSetColumnIndex(1);
            ImGui::TextDisabled("skipped");
        }
        ImGui::EndTable();
    }
    ImGui::Text("transient textures: %.1f MiB in %zu", renderer.pool().totalBytes() / 1048576.0, renderer.pool().textureCount());

    // View and lighting controls.
    int view = int(st.settings.view);
    std::string names;
    for (DebugView v : allViews()) names += std::string(viewName(v)) + '\0';
    if (ImGui::Combo("view", &view, names.c_str())) st.settings.view = DebugView(view);
    ImGui::SliderFloat("exposure (EV)", &st.settings.exposureEV, -8.0f, 8.0f, "%.1f");
    ImGui::Checkbox("global lights", &st.settings.globalLighting);
    ImGui::Checkbox("scissor (x)", &st.scissor);
    if (ImGui::Button("screenshot (F12)")) st.screenshotRequested = true;
    ImGui::End();
}

}  // namespace

int runViewer(const Options& o) {
    Scene scene = o.model.empty() ? loadScene(o.scene) : sceneForModel(o.model);
    gl::ContextOptions co;
    co.width = o.width;
    co.height = o.height;
    co.vsync = o.vsync;
    co.title = "lightpass";
    auto ctx = gl::createWindowContext(co);
    logInfo("viewer on " + ctx->info().renderer);
    Renderer renderer(scene);
    ViewerState st;
    st.settings = o.base;
    st.scissor = o.base.localLights.scissor;  // --no-scissor starts with it off
    st.settings.view = o.view;
    st.settings.exposureEV = o.exposure;
    st.settings.keepHdr = true;
    st.home = scene.camera;
    if (!o.screenshotDir.empty()) st.screenshotDir = o.screenshotDir;
    st.showPanel = !o.hidePanel;
    st.screenshotWithPanel = o.screenshotUi;
    GLFWwindow* window = ctx->window();
    glfwSetWindowUserPointer(window, &st);
    glfwSetKeyCallback(window, keyCallback);  // before ImGui, which chains to it

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini files left in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");
    struct ImGuiShutdown {
        ~ImGuiShutdown() {
            ImGui_ImplOpenGL3_Shutdown();
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
        }
    } imguiShutdown;

    gl::Framebuffer blit = gl::makeFramebuffer("present");
    double last = glfwGetTime();
    long frame = 0;
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        double now = glfwGetTime();
        float dt = float(now - last);
        last = now;
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        moveCamera(window, st, scene.camera, dt);
        glm::ivec2 fb = ctx->framebufferSize();
        if (fb.x <= 0 || fb.y <= 0) {  // minimised
            ImGui::EndFrame();
            continue;
        }
        st.settings.width = fb.x;
        st.settings.height = fb.y;
        st.settings.localLights.scissor = st.scissor;  // 'x' / the panel's checkbox
        renderer.render(st.settings, float(now), true);
        if (st.screenshotRequested && !st.screenshotWithPanel) {  // the frame alone, no panel
            st.screenshotRequested = false;
            takeScreenshot(st, renderer);
        }
        glNamedFramebufferTexture(blit.id(), GL_COLOR_ATTACHMENT0, renderer.displayTexture(), 0);
        glBlitNamedFramebuffer(blit.id(), 0, 0, 0, fb.x, fb.y, 0, 0, fb.x, fb.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        renderer.timers().trim(120);
        st.frameMs.push_back(float(renderer.timers().samples("frame").empty() ? 0.0 : renderer.timers().samples("frame").back()));
        if (st.frameMs.size() > 240) st.frameMs.pop_front();
        if (st.showPanel) drawPanel(st, renderer, *ctx);
        if (st.showHelp) {
            ImGui::SetNextWindowPos(ImVec2(fb.x * 0.5f, fb.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
            ImGui::Begin("keys", &st.showHelp, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
            ImGui::TextUnformatted(kHelp);
            ImGui::End();
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (st.screenshotRequested && st.screenshotWithPanel) {
            st.screenshotRequested = false;
            Image8 window{fb.x, fb.y, std::vector<uint8_t>(size_t(fb.x) * fb.y * 4)};
            glPixelStorei(GL_PACK_ALIGNMENT, 1);
            glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, window.rgba.data());
            std::vector<uint8_t> flipped(window.rgba.size());
            const size_t row = size_t(fb.x) * 4;
            for (int y = 0; y < fb.y; ++y)
                std::copy_n(&window.rgba[size_t(fb.y - 1 - y) * row], row, &flipped[size_t(y) * row]);
            window.rgba.swap(flipped);
            std::string path = (st.screenshotDir / ("lightpass-" + std::to_string(st.screenshotCount++) + ".png")).string();
            writePng(path, window);
            std::printf("screenshot %s (window with panel)\n", path.c_str());
            std::fflush(stdout);
        }
        ctx->swapBuffers();
        if (++frame == 3) {
            std::printf("viewer ready\n");
            std::fflush(stdout);
        }
    }
    return 0;
}

}  // namespace lp::app
