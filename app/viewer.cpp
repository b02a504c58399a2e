#include "app/viewer.hpp"
#include "app/viewer_state.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "app/config_dir.hpp"
#include "app/environment_pick.hpp"
#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/context.hpp"
#include "engine/io/image_io.hpp"
#include "frame/renderer.hpp"
#include "passes/hdr_view_pass.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {
namespace {

// Seed 001's keys. Each prints what it did, which the viewer tests read.
void keyCallback(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
    if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;  // typing in a field
    auto* st = static_cast<ViewerState*>(glfwGetWindowUserPointer(window));
    RenderSettings& s = st->settings;
    auto say = [](const std::string& line) {
        std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    };
    auto setView = [&](DebugView v) {
        s.view = v;
        say(std::string("view ") + viewName(v));
    };
    switch (key) {
        case GLFW_KEY_1: setView(DebugView::Depth); break;
        case GLFW_KEY_2: setView(DebugView::Normals); break;
        case GLFW_KEY_3: setView(DebugView::Diffuse); break;
        case GLFW_KEY_4: setView(DebugView::Position); break;
        case GLFW_KEY_5: setView(DebugView::Lighting); break;
        case GLFW_KEY_6: setView(DebugView::Shininess); break;
        case GLFW_KEY_9: setView(DebugView::Velocity); break;
        case GLFW_KEY_M: setView(nextViewInCycle(materialInputViews(), s.view)); break;  // the material's inputs
        case GLFW_KEY_T: setView(nextViewInCycle(termViews(), s.view)); break;           // the lit frame's terms
        case GLFW_KEY_K: setView(DebugView::TermClearcoat); break;                      // the clearcoat layer alone
        case GLFW_KEY_7:  // toon on/off over the standard view (which the bloom buffer alone is not)
            s.view = DebugView::Final;
            if (s.post.bloomOnly) {
                s.post.bloomOnly = false;
                s.post.bloom = st->startBloom;
            }
            s.post.toon = !st->toonShown;
            say(std::string("toon ") + (*s.post.toon ? "on" : "off"));
            break;
        case GLFW_KEY_8:  // the bloom buffer alone (bloom switched on for it)
            s.view = DebugView::Final;
            s.post.bloomOnly = !s.post.bloomOnly;
            s.post.bloom = s.post.bloomOnly ? std::optional<bool>(true) : st->startBloom;
            say(std::string("bloom only ") + (s.post.bloomOnly ? "on" : "off") +
                (s.post.bloomOnly && st->toonShown ? " (toon is not shown meanwhile: 7 or 0 goes back)" : ""));
            break;
        case GLFW_KEY_0:
            s.post.bloomOnly = false;
            s.post.bloom = st->startBloom;
            s.post.toon = st->startToon;
            setView(DebugView::Final);
            break;
        case GLFW_KEY_R:
            st->resetCamera = true;
            say("camera reset");
            break;
        case GLFW_KEY_P:
            // Without a path there is nothing to follow: say so rather than seem to do nothing.
            if (st->cameraPath) st->togglePath = true;
            else say("no camera path (a scene's \"cameraPath\" or --camera-path gives one)");
            break;
        case GLFW_KEY_X: {
            s.localLights.scissor = !s.localLights.scissor;
            // Only the deferred path's scissor method reads the switch: say so under the others.
            std::string why;
            if (s.renderPath == RenderPath::ForwardPlus)
                why = " (used by the deferred path's scissor method; forward+ shades local lights in forward_opaque)";
            else if (!s.localLights.enabled)
                why = " (local lights are off; used by the scissor method)";
            else if (s.localLights.method != LocalLightMethod::Scissor)
                why = std::string(" (used by the scissor method; now ") + localLightMethodName(s.localLights.method) +
                      "; the panel's lighting section picks the method)";
            say(std::string("scissor ") + (s.localLights.scissor ? "on" : "off") + why);
            break;
        }
        case GLFW_KEY_C: {
            // Truth beside the frame: the path tracer of the same view, and the raster's error against it.
            const std::string why = truthComparisonUnavailable(s);
            if (!st->compareWithTruth && !why.empty()) {
                say("compare with the path tracer: " + why);
                break;
            }
            st->compareWithTruth = !st->compareWithTruth;
            st->comparison.describedStats.clear();
            say(st->compareWithTruth ? "compare with the path tracer on (raster | path tracer / heat map of the error)"
                                     : "compare with the path tracer off");
            break;
        }
        case GLFW_KEY_SPACE: say(st->clock.togglePlaying()); break;
        case GLFW_KEY_LEFT_BRACKET: case GLFW_KEY_RIGHT_BRACKET:
            say(st->clock.changeSpeed(key == GLFW_KEY_RIGHT_BRACKET ? 2.0f : 0.5f));
            break;
        case GLFW_KEY_H: st->showHelp = !st->showHelp; break;
        case GLFW_KEY_TAB:
            st->showPanel = !st->showPanel;
            say(st->showPanel ? "panel shown (the image beside it)" : "panel hidden (the image fills the window)");
            break;
        case GLFW_KEY_F12: st->screenshotRequested = true; break;
        case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: {
            s.exposureEV += (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) ? 0.5f : -0.5f;
            // The G-buffer views write raw values: exposure shows again in the lit views.
            const bool exposed = s.view == DebugView::Final || s.view == DebugView::Lighting || isLocalLightView(s.view) ||
                                 isHdrView(s.view);
            char line[160];
            std::snprintf(line, sizeof line, "exposure %+.1f EV%s", s.exposureEV,
                          exposed ? "" : " (not in this view: the G-buffer views show raw values; 0 or 5 shows it)");
            say(line);
            break;
        }
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
        default: break;
    }
}

// Fly camera: W/S forward/back, A/D strafe, Q/Z up/down; drag with the left button to look.
// Returns whether the user moved or turned it.
bool moveCamera(GLFWwindow* window, ViewerState& st, Camera& cam, float dt) {
    bool moved = false;
    if (st.resetCamera) cam = st.home;
    st.resetCamera = false;
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
        moved = move != glm::vec3(0.0f);
    }
    double x, y;
    glfwGetCursorPos(window, &x, &y);
    // A drag starts on the image (not on the panel beside it) and goes on wherever the cursor goes.
    int windowWidth = 0, windowHeight = 0, fbWidth = 0, fbHeight = 0;
    glfwGetWindowSize(window, &windowWidth, &windowHeight);
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    const bool onImage = insideViewport(st.viewport, fbWidth, fbHeight, float(windowWidth), float(windowHeight), x, y);
    bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !io.WantCaptureMouse &&
                (st.dragging || onImage);
    if (down && st.dragging) {
        float yaw = float(x - st.lastX) * -0.005f, pitch = float(y - st.lastY) * -0.005f;
        glm::vec3 dir = cam.target - cam.position;
        glm::mat4 r = glm::rotate(glm::mat4(1.0f), yaw, cam.up);
        r = glm::rotate(r, pitch, right);
        glm::vec3 nd = glm::vec3(r * glm::vec4(dir, 0.0f));
        if (std::abs(glm::dot(glm::normalize(nd), glm::normalize(cam.up))) < 0.99f) cam.target = cam.position + nd;
        moved = moved || x != st.lastX || y != st.lastY;
    }
    st.dragging = down;
    st.lastX = x;
    st.lastY = y;
    return moved;
}

void say(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

void takeScreenshot(ViewerState& st, Renderer& renderer) {
    std::filesystem::path base = st.screenshotDir / ("lightpass-" + std::to_string(st.screenshotCount++));
    writePng(base.string() + ".png", renderer.readDisplay());
    std::string msg = "screenshot " + base.string() + ".png";
    if (renderer.hdrTexture()) {
        writeExr(base.string() + ".exr", renderer.readHdr());
        msg += " + .exr";
    }
    st.lastScreenshot = msg;
    say(msg);
}

void takeWindowScreenshot(ViewerState& st, glm::ivec2 fb) {
    Image8 window{fb.x, fb.y, std::vector<uint8_t>(size_t(fb.x) * fb.y * 4)};
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, fb.x, fb.y, GL_RGBA, GL_UNSIGNED_BYTE, window.rgba.data());
    std::vector<uint8_t> flipped(window.rgba.size());
    const size_t row = size_t(fb.x) * 4;
    for (int y = 0; y < fb.y; ++y) std::copy_n(&window.rgba[size_t(fb.y - 1 - y) * row], row, &flipped[size_t(y) * row]);
    window.rgba.swap(flipped);
    std::string path = (st.screenshotDir / ("lightpass-" + std::to_string(st.screenshotCount++) + ".png")).string();
    writePng(path, window);
    st.lastScreenshot = "screenshot " + path + " (window with panel)";
    say(st.lastScreenshot);
}

// Twice a second: rebuild the programs that read a changed shader file; only when all compile are
// the renderer's programs dropped (rebuilt next frame), so a broken edit keeps the last good ones.
void reloadChangedShaders(ViewerState& st, Renderer& renderer, double now) {
    if (now < st.nextShaderPoll) return;
    st.nextShaderPoll = now + 0.5;
    std::vector<std::string> changed = gl::pollChangedShaderFiles(st.shaderWatcher);
    if (changed.empty()) return;
    gl::ShaderReloadResult result = gl::rebuildProgramsReading(renderer.shaders(), changed);
    if (result.affected.empty() && st.shaderError.empty()) return;
    std::string files;
    for (const auto& f : changed) files += (files.empty() ? "" : ", ") + f;
    if (!result.ok()) {
        st.shaderError = result.error;
        say("shader error: " + result.error);
        return;
    }
    renderer.resetPasses();
    st.shaderError.clear();
    st.shaderStatus = "shaders reloaded: " + std::to_string(result.affected.size()) + " programs (" + files + ")";
    say(st.shaderStatus);
}

// ImGui's ini file (the panel's position, size, collapsed state) in the per-user config folder,
// created if missing; empty (no ini) when there is no such folder or it cannot be made.
std::string panelLayoutFile() {
    const std::filesystem::path dir = userConfigDir([](const char* name) { return std::getenv(name); });
    if (dir.empty()) {
        logWarn("no $LIGHTPASS_CONFIG_DIR, $XDG_CONFIG_HOME or $HOME: the panel layout is not saved");
        return "";
    }
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
        logWarn("cannot create " + dir.string() + " (" + ec.message() + "): the panel layout is not saved");
        return "";
    }
    logInfo("panel layout: " + (dir / "imgui.ini").string());
    return (dir / "imgui.ini").string();
}

// What --panel-rows-out writes: the panel's place, then one tab-separated line per pass row.
std::string panelRowsText(const ViewerState& st) {
    std::ostringstream out;
    if (st.showPanel)
        out << "panel\t" << st.panelX << "," << st.panelY << "\t" << st.panelWidth << "x" << st.panelHeight << "\n";
    else
        out << "panel\thidden\n";
    // Framebuffer pixels, from the top left as the panel's.
    out << "viewport\t" << st.viewport.x << ",0\t" << st.viewport.width << "x" << st.viewport.height << "\n";
    for (const PassRow& row : st.passRows) {
        out << "pass\t" << row.name << "\t" << row.checkboxX << "," << row.checkboxY << "\t" << passRowStateName(row.state);
        if (!row.reason.empty()) out << ": " << row.reason;
        out << "\n";
    }
    return out.str();
}

// Written whole under a temporary name and renamed, so a test never reads half a file.
void writePanelRows(const std::string& path, const std::string& text) {
    const std::string partial = path + ".partial";
    {
        std::ofstream out(partial, std::ios::binary);
        out << text;
        if (!out) throw Error(path + ": cannot write the panel rows");
    }
    std::filesystem::rename(partial, path);
}

}  // namespace

int runViewer(const Options& o) {
    auto scene = std::make_unique<Scene>(sceneFromOptions(o));
    gl::ContextOptions co;
    co.width = o.width;
    co.height = o.height;
    co.vsync = o.vsync;
    co.title = "lightpass";
    auto ctx = gl::createWindowContext(co);
    logInfo("viewer on " + ctx->info().renderer);
    gl::ShaderLibrary shaders;
    auto renderer = std::make_unique<Renderer>(*scene, shaders);
    ViewerState st;
    st.settings = o.base;
    st.settings.view = o.view;
    st.settings.exposureEV = o.exposure;
    st.settings.keepHdr = true;
    st.startToon = o.base.post.toon;
    st.startBloom = o.base.post.bloom;
    st.home = scene->camera;
    st.cameraPath = scene->cameraPath;
    st.followPath = st.cameraPath.has_value();
    st.sceneFile = o.model.empty() ? std::filesystem::path(o.scene) : std::filesystem::path(o.model);
    if (!o.screenshotDir.empty()) st.screenshotDir = o.screenshotDir;
    st.showPanel = !o.hidePanel;
    st.screenshotWithPanel = o.screenshotUi;
    st.passRows = candidatePassRows(*scene, st.settings);  // every row from the start: none appears later
    st.shaderWatcher = gl::watchShaderFiles(shaders.root());
    const PickerFiles pickerFiles = findPickerFiles(shaders.root().parent_path());
    GLFWwindow* window = ctx->window();
    glfwSetWindowUserPointer(window, &st);
    glfwSetKeyCallback(window, keyCallback);  // before ImGui, which chains to it

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    const std::string layoutFile = panelLayoutFile();  // ImGui keeps the pointer: outlives the context
    ImGui::GetIO().IniFilename = layoutFile.empty() ? nullptr : layoutFile.c_str();
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 1.0f;  // the panel sits beside the image, nothing under it
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
    std::string reportedGraph;
    std::string writtenPanelRows;
    RenderSettings lastGoodSettings = st.settings;
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        double now = glfwGetTime();
        float dt = float(now - last);
        last = now;
        if (frame >= 3) st.frameMs.push_back(dt * 1000.0f);  // the first frames include start-up bakes
        if (st.frameMs.size() > 240) st.frameMs.pop_front();

        // Pickers: load between frames; a bad file keeps the old scene and shows its one-line error.
        if (st.sceneRequest) {
            try {
                const auto& file = *st.sceneRequest;
                auto next = std::make_unique<Scene>(isModelPath(file) ? sceneForModel(file) : loadScene(file));
                renderer.reset();  // it points at the old scene
                scene = std::move(next);
                renderer = std::make_unique<Renderer>(*scene, shaders);
                st.home = scene->camera;
                st.cameraPath = scene->cameraPath;
                st.followPath = st.cameraPath.has_value();
                st.passRows = candidatePassRows(*scene, st.settings);  // the new scene's, in its order
                st.sceneError.clear();
                st.sceneFile = file;
                say("scene " + file.string());
            } catch (const Error& e) {
                st.sceneError = e.what();
                say(std::string("scene error: ") + e.what());
            }
            st.sceneRequest.reset();
        }
        // A material variant: the models' sub-meshes draw other materials, so the GPU scene is made again.
        if (st.materialVariantRequest) {
            try {
                chooseMaterialVariant(*scene, *st.materialVariantRequest);
                renderer.reset();
                renderer = std::make_unique<Renderer>(*scene, shaders);
                say("material variant " + (st.materialVariantRequest->empty() ? std::string("(the files' own)") : *st.materialVariantRequest));
            } catch (const Error& e) {
                st.sceneError = e.what();
            }
            st.materialVariantRequest.reset();
        }
        std::optional<EnvironmentBefore> previousEnvironment;  // a pick this frame, to undo if its map fails
        if (st.environmentRequest) {
            previousEnvironment = pickEnvironment(*scene, st.settings, *st.environmentRequest);
            st.environmentRequest.reset();
        }
        reloadChangedShaders(st, *renderer, now);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        if (st.togglePath) {
            st.togglePath = false;
            if (st.cameraPath) {
                st.followPath = !st.followPath;
                renderer->cutMotion();  // the camera jumps onto (or stays off) the path
                say(std::string("camera path ") + (st.followPath ? "on" : "off"));
            }
        }
        if (st.resetCamera) renderer->cutMotion();  // a jump: no motion vectors across it
        // The scene clock: wall time times the speed while playing; a scrub on the panel is a jump.
        st.clock.advance(dt);
        if (st.clockJumped) renderer->cutMotion();
        st.clockJumped = false;
        const double sceneTime = st.clock.time;
        // Following, the camera is the path's at the viewer's clock (the time orbits use); the
        // user's moves start from there and stop following.
        scene->cameraPath = st.followPath ? st.cameraPath : std::nullopt;
        if (st.followPath) scene->camera = scene->cameraAt(sceneTime);
        if (moveCamera(window, st, scene->camera, dt) && st.followPath) {
            st.followPath = false;
            scene->cameraPath.reset();
            say("camera path off (p follows it again)");
        }
        glm::ivec2 fb = ctx->framebufferSize();
        if (fb.x <= 0 || fb.y <= 0) {  // minimised
            ImGui::EndFrame();
            continue;
        }
        int windowWidth = 0, windowHeight = 0;
        glfwGetWindowSize(window, &windowWidth, &windowHeight);
        // The image beside the panel (the panel's width as last drawn), or the whole window without
        // it: rendered at the viewport's size, so the camera's aspect is the viewport's.
        st.viewport = viewerViewport(fb.x, fb.y, float(windowWidth), st.showPanel, st.panelWidth);
        // Comparing with the path tracer: both render at a quarter of the viewport (the 2 x 2 grid),
        // the raster frame keeping its HDR buffer for the heat map. A setting the tracer cannot show
        // (a G-buffer view, the tracer itself) ends the comparison, saying why.
        if (st.compareWithTruth && !truthComparisonUnavailable(st.settings).empty()) {
            st.compareWithTruth = false;
            say("compare with the path tracer off: " + truthComparisonUnavailable(st.settings));
        }
        const ViewerViewport renderSize = st.compareWithTruth ? comparisonTile(st.viewport) : st.viewport;
        st.settings.width = renderSize.width;
        st.settings.height = renderSize.height;
        st.settings.keepHdr = st.compareWithTruth;
        st.toonShown = st.settings.post.toon.value_or(scene->effects.toon.enabled);
        try {
            renderer->render(st.settings, float(sceneTime), true);
            if (previousEnvironment) {
                st.passRows = candidatePassRows(*scene, st.settings);  // a map brings ibl and sky
                st.sceneError.clear();
                say("environment " + (scene->environment.map.empty() ? std::string("plain colour") : scene->environment.map.string()));
            }
            lastGoodSettings = st.settings;
        } catch (const Error& e) {
            // A map that does not load, or a setting the renderer refuses: show the one-line error,
            // go back to what last rendered (the first frame has nothing to go back to).
            if (frame == 0) throw;
            st.settings = lastGoodSettings;
            if (previousEnvironment) restoreEnvironment(*scene, st.settings, *previousEnvironment);
            st.sceneError = e.what();
            say(std::string(previousEnvironment ? "environment error: " : "render error: ") + e.what());
            renderer->render(st.settings, float(sceneTime), true);
        }
        {  // the passes that ran, whenever they change (checkboxes, '7', '8', settings)
            std::string live;
            for (const auto& p : renderer->graph().report())
                if (!p.culled && p.name != "ibl_bake") live += " " + p.name;
            if (live != reportedGraph) say("graph:" + live);
            reportedGraph = live;
        }
        updatePassRows(st.passRows, renderer->graph().explain(), st.settings.disabledPasses);
        if (st.screenshotRequested && !st.screenshotWithPanel) {  // the frame alone, no panel
            st.screenshotRequested = false;
            takeScreenshot(st, *renderer);
        }
        const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f};  // the window cleared, the frame blitted into the viewport
        glClearNamedFramebufferfv(0, GL_COLOR, 0, black);
        const ViewerViewport& vp = st.viewport;
        if (st.compareWithTruth) {
            try {
                const std::string line = drawTruthComparison(st.comparison, *renderer, *scene, st.settings, float(sceneTime), now, vp, blit.id());
                if (!line.empty()) say(line);
            } catch (const Error& e) {  // e.g. a scene the tracer refuses: the frame alone again
                st.compareWithTruth = false;
                say(std::string("compare with the path tracer off: ") + e.what());
            }
        }
        if (!st.compareWithTruth) {
            glNamedFramebufferTexture(blit.id(), GL_COLOR_ATTACHMENT0, renderer->displayTexture(), 0);
            glBlitNamedFramebuffer(blit.id(), 0, 0, 0, vp.width, vp.height, vp.x, vp.y, vp.x + vp.width, vp.y + vp.height,
                                   GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        renderer->timers().trim(120);
        if (st.showPanel) drawViewerPanel(st, *renderer, *scene, *ctx, pickerFiles);
        if (st.showHelp) {
            const float toWindow = windowWidth > 0 ? float(windowWidth) / float(fb.x) : 1.0f;  // over the image
            ImGui::SetNextWindowPos(ImVec2((st.viewport.x + st.viewport.width * 0.5f) * toWindow, windowHeight * 0.5f),
                                    ImGuiCond_Always, ImVec2(0.5f, 0.5f));
            ImGui::Begin("keys (h closes)", &st.showHelp, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
            ImGui::TextUnformatted(kViewerHelp);
            ImGui::End();
        }
        if (st.compareWithTruth) {  // the legend and numbers in the grid's empty quarter (bottom right)
            const float toWindow = windowWidth > 0 ? float(windowWidth) / float(fb.x) : 1.0f;
            ImGui::SetNextWindowPos(ImVec2((vp.x + vp.width * 0.75f) * toWindow, windowHeight * 0.75f), ImGuiCond_Always,
                                    ImVec2(0.5f, 0.5f));
            ImGui::Begin("compare with the path tracer", nullptr,
                         ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
            ImGui::TextUnformatted(truthComparisonLegend(st.comparison.stats).c_str());
            ImGui::End();
        }
        if (!o.panelRowsOut.empty() && frame >= 3) {  // from "viewer ready" on: the panel has settled
            const std::string rows = panelRowsText(st);
            if (rows != writtenPanelRows) writePanelRows(o.panelRowsOut, rows);
            writtenPanelRows = rows;
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (st.screenshotRequested && st.screenshotWithPanel) {
            st.screenshotRequested = false;
            takeWindowScreenshot(st, fb);
        }
        ctx->swapBuffers();
        if (++frame == 3) say("viewer ready");
    }
    return 0;
}

}  // namespace lp::app
