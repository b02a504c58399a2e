#include "engine/gl/state_check.hpp"

#include <cctype>
#include <cstdlib>

#include "engine/core/log.hpp"

namespace lp::gl {

namespace {
void addInt(WatchedState& s, const char* name, GLenum pname, int count = 1) {
    GLint v[4] = {0, 0, 0, 0};
    glGetIntegerv(pname, v);
    for (int i = 0; i < count; ++i)
        s.items.emplace_back(count == 1 ? std::string(name) : std::string(name) + "[" + std::to_string(i) + "]", v[i]);
}
void addFloat(WatchedState& s, const char* name, GLenum pname) {
    GLfloat v = 0;
    glGetFloatv(pname, &v);
    s.items.emplace_back(name, (long long)(v * 1000.0f));  // enough to see a changed bias
}
}  // namespace

WatchedState captureWatchedState() {
    WatchedState s;
    static const std::pair<GLenum, const char*> caps[] = {
        {GL_BLEND, "GL_BLEND"}, {GL_DEPTH_TEST, "GL_DEPTH_TEST"}, {GL_CULL_FACE, "GL_CULL_FACE"},
        {GL_SCISSOR_TEST, "GL_SCISSOR_TEST"}, {GL_STENCIL_TEST, "GL_STENCIL_TEST"},
        {GL_POLYGON_OFFSET_FILL, "GL_POLYGON_OFFSET_FILL"}, {GL_DEPTH_CLAMP, "GL_DEPTH_CLAMP"},
        {GL_TEXTURE_CUBE_MAP_SEAMLESS, "GL_TEXTURE_CUBE_MAP_SEAMLESS"}, {GL_RASTERIZER_DISCARD, "GL_RASTERIZER_DISCARD"},
        {GL_FRAMEBUFFER_SRGB, "GL_FRAMEBUFFER_SRGB"}};
    for (const auto& [cap, name] : caps) s.items.emplace_back(name, glIsEnabled(cap));
    // Only where the extension exists (asking for it elsewhere is a GL error); the shadow pass turns
    // it on for its hardware conservative casters.
    if (GLAD_GL_NV_conservative_raster)
        s.items.emplace_back("GL_CONSERVATIVE_RASTERIZATION_NV", glIsEnabled(GL_CONSERVATIVE_RASTERIZATION_NV));
    addInt(s, "GL_BLEND_SRC_RGB", GL_BLEND_SRC_RGB);
    addInt(s, "GL_BLEND_DST_RGB", GL_BLEND_DST_RGB);
    addInt(s, "GL_BLEND_SRC_ALPHA", GL_BLEND_SRC_ALPHA);
    addInt(s, "GL_BLEND_DST_ALPHA", GL_BLEND_DST_ALPHA);
    addInt(s, "GL_BLEND_EQUATION_RGB", GL_BLEND_EQUATION_RGB);
    addInt(s, "GL_BLEND_EQUATION_ALPHA", GL_BLEND_EQUATION_ALPHA);
    addInt(s, "GL_DEPTH_FUNC", GL_DEPTH_FUNC);
    addInt(s, "GL_DEPTH_WRITEMASK", GL_DEPTH_WRITEMASK);
    addInt(s, "GL_CULL_FACE_MODE", GL_CULL_FACE_MODE);
    addInt(s, "GL_POLYGON_MODE", GL_POLYGON_MODE);
    addFloat(s, "GL_POLYGON_OFFSET_FACTOR", GL_POLYGON_OFFSET_FACTOR);
    addFloat(s, "GL_POLYGON_OFFSET_UNITS", GL_POLYGON_OFFSET_UNITS);
    addInt(s, "GL_CLIP_ORIGIN", GL_CLIP_ORIGIN);
    addInt(s, "GL_CLIP_DEPTH_MODE", GL_CLIP_DEPTH_MODE);
    addInt(s, "GL_COLOR_WRITEMASK", GL_COLOR_WRITEMASK, 4);
    addInt(s, "GL_CURRENT_PROGRAM", GL_CURRENT_PROGRAM);
    addInt(s, "GL_VERTEX_ARRAY_BINDING", GL_VERTEX_ARRAY_BINDING);
    addInt(s, "GL_DRAW_FRAMEBUFFER_BINDING", GL_DRAW_FRAMEBUFFER_BINDING);
    addInt(s, "GL_READ_FRAMEBUFFER_BINDING", GL_READ_FRAMEBUFFER_BINDING);
    addInt(s, "GL_VIEWPORT", GL_VIEWPORT, 4);
    addInt(s, "GL_SCISSOR_BOX", GL_SCISSOR_BOX, 4);
    GLint active = GL_TEXTURE0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    s.items.emplace_back("GL_ACTIVE_TEXTURE", active);
    for (GLuint unit = 0; unit < 16; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        GLint t2d = 0, cube = 0, sampler = 0;
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &t2d);
        glGetIntegerv(GL_TEXTURE_BINDING_CUBE_MAP, &cube);
        glGetIntegerv(GL_SAMPLER_BINDING, &sampler);
        const std::string u = "texture unit " + std::to_string(unit);
        s.items.emplace_back(u + " 2D", t2d);
        s.items.emplace_back(u + " cube", cube);
        s.items.emplace_back(u + " sampler", sampler);
    }
    glActiveTexture(GLenum(active));
    for (GLuint unit = 0; unit < 8; ++unit) {
        GLint name = 0;
        glGetIntegeri_v(GL_IMAGE_BINDING_NAME, unit, &name);
        s.items.emplace_back("image unit " + std::to_string(unit), name);
    }
    return s;
}

std::string describeStateChange(const WatchedState& before, const WatchedState& after) {
    std::string out;
    for (size_t i = 0; i < before.items.size() && i < after.items.size(); ++i) {
        if (before.items[i].second == after.items[i].second) continue;
        out += (out.empty() ? "" : ", ") + after.items[i].first + " " + std::to_string(after.items[i].second) +
               " (was " + std::to_string(before.items[i].second) + ")";
    }
    return out;
}

std::optional<bool> parseStateChecksFlag(std::string_view value) {
    std::string v;
    for (char c : value) v += char(std::toupper((unsigned char)c));
    if (v == "1" || v == "ON") return true;
    if (v.empty() || v == "0" || v == "OFF") return false;
    return std::nullopt;
}

bool stateChecksFromEnvironment() {
    static const bool on = [] {
        const char* env = std::getenv("LIGHTPASS_GL_STATE_CHECKS");
        if (!env) return false;
        const std::optional<bool> flag = parseStateChecksFlag(env);
        if (!flag)
            logWarn(std::string("LIGHTPASS_GL_STATE_CHECKS=") + env + ": expected 1 or 0; the per-pass GL state check stays off");
        return flag.value_or(false);
    }();
    return on;
}

}  // namespace lp::gl
