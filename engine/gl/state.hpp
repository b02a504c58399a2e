#pragma once
// Scoped GL state: a pass that changes a capability, the viewport or the framebuffer binding puts
// it back when it ends, so no pass depends on what ran before it.
#include "engine/gl/gl.hpp"

namespace lp::gl {

class ScopedEnable {
public:
    ScopedEnable(GLenum cap, bool enable) : cap_(cap), was_(glIsEnabled(cap)) { enable ? glEnable(cap) : glDisable(cap); }
    ~ScopedEnable() { was_ ? glEnable(cap_) : glDisable(cap_); }
    ScopedEnable(const ScopedEnable&) = delete;
    ScopedEnable& operator=(const ScopedEnable&) = delete;

private:
    GLenum cap_;
    GLboolean was_;
};

class ScopedFramebuffer {
public:
    ScopedFramebuffer(GLuint fbo, int width, int height) {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, width, height);
    }
    ~ScopedFramebuffer() {
        glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_));
        glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    }
    ScopedFramebuffer(const ScopedFramebuffer&) = delete;
    ScopedFramebuffer& operator=(const ScopedFramebuffer&) = delete;

private:
    GLint previous_ = 0;
    GLint viewport_[4] = {0, 0, 0, 0};
};

// Dispatch covering a width x height image with 8x8 work groups.
inline void dispatch2D(int width, int height, int group = 8) {
    glDispatchCompute(GLuint((width + group - 1) / group), GLuint((height + group - 1) / group), 1);
}

// The common shape of an image-to-image compute pass: `source` sampled on `sourceUnit`, `target`
// written as image 0 in `format`, one invocation per target texel, and the bindings put back to 0.
// No barrier: the frame graph issues the ones the next users of `target` need.
inline void dispatchTextureToImage(GLuint program, GLuint sourceUnit, GLuint source, GLuint target, GLenum format,
                                   int width, int height) {
    glBindTextureUnit(sourceUnit, source);
    glBindImageTexture(0, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    glUseProgram(program);
    dispatch2D(width, height);
    glUseProgram(0);
    glBindTextureUnit(sourceUnit, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
}

}  // namespace lp::gl
