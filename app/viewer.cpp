#include "app/viewer.hpp"

#include <cmath>
#include <cstdio>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/context.hpp"
#include "engine/render/renderer.hpp"
#include "engine/scene/scene_loader.hpp"

namespace lp::app {
namespace {

struct ViewerState {
    RenderSettings settings;
    Camera home;
    bool scissor = true;
    bool dragging = false;
    double lastX = 0, lastY = 0;
};

void keyCallback(GLFWwindow* window, int key, int, int action, int) {
    if (action != GLFW_PRESS) return;
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
            logInfo(std::string("scissor ") + (st->scissor ? "on" : "off"));
            break;
        case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: st->settings.exposureEV += 0.5f; break;
        case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: st->settings.exposureEV -= 0.5f; break;
        case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(window, GLFW_TRUE); break;
        default: break;
    }
}

// Fly camera: W/S forward/back, A/D strafe, Q/Z up/down; drag with the left button to look.
void moveCamera(GLFWwindow* window, ViewerState& st, Camera& cam, float dt) {
    glm::vec3 forward = glm::normalize(cam.target - cam.position);
    glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
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

    double x, y;
    glfwGetCursorPos(window, &x, &y);
    bool down = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
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
    st.settings.view = o.view;
    st.settings.exposureEV = o.exposure;
    st.home = scene.camera;
    GLFWwindow* window = ctx->window();
    glfwSetWindowUserPointer(window, &st);
    glfwSetKeyCallback(window, keyCallback);
    gl::Framebuffer blit = gl::makeFramebuffer("present");
    double last = glfwGetTime(), titleAt = 0.0;
    while (!glfwWindowShouldClose(window)) {
        glfwPollEvents();
        double now = glfwGetTime();
        float dt = float(now - last);
        last = now;
        moveCamera(window, st, scene.camera, dt);
        glm::ivec2 fb = ctx->framebufferSize();
        if (fb.x <= 0 || fb.y <= 0) continue;  // minimised
        st.settings.width = fb.x;
        st.settings.height = fb.y;
        renderer.render(st.settings, float(now), true);
        glNamedFramebufferTexture(blit.id(), GL_COLOR_ATTACHMENT0, renderer.displayTexture(), 0);
        glBlitNamedFramebuffer(blit.id(), 0, 0, 0, fb.x, fb.y, 0, 0, fb.x, fb.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        ctx->swapBuffers();
        renderer.timers().trim(120);
        if (now - titleAt > 0.5) {
            titleAt = now;
            char title[256];
            std::snprintf(title, sizeof title, "lightpass - %s - view %s - frame %.2f ms GPU", scene.file.filename().c_str(),
                          viewName(st.settings.view), renderer.timers().median("frame"));
            glfwSetWindowTitle(window, title);
        }
    }
    return 0;
}

}  // namespace lp::app
