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

// The raster state beyond capabilities, framebuffer and viewport, saved when made and put back
// when it ends: blend function and equation, depth function and mask, cull face, polygon mode and
// offset, scissor box, colour mask, clip control. One saver for every pass that draws.
class ScopedRasterState {
public:
    ScopedRasterState() {
        glGetIntegerv(GL_BLEND_SRC_RGB, &blend_[0]);
        glGetIntegerv(GL_BLEND_DST_RGB, &blend_[1]);
        glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_[2]);
        glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_[3]);
        glGetIntegerv(GL_BLEND_EQUATION_RGB, &equation_[0]);
        glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &equation_[1]);
        glGetIntegerv(GL_DEPTH_FUNC, &depthFunc_);
        glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask_);
        glGetIntegerv(GL_CULL_FACE_MODE, &cullFace_);
        glGetIntegerv(GL_POLYGON_MODE, polygonMode_);
        glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &offset_[0]);
        glGetFloatv(GL_POLYGON_OFFSET_UNITS, &offset_[1]);
        glGetIntegerv(GL_SCISSOR_BOX, scissor_);
        glGetBooleanv(GL_COLOR_WRITEMASK, colorMask_);
        glGetIntegerv(GL_CLIP_ORIGIN, &clip_[0]);
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_[1]);
    }
    ~ScopedRasterState() {
        glBlendFuncSeparate(GLenum(blend_[0]), GLenum(blend_[1]), GLenum(blend_[2]), GLenum(blend_[3]));
        glBlendEquationSeparate(GLenum(equation_[0]), GLenum(equation_[1]));
        glDepthFunc(GLenum(depthFunc_));
        glDepthMask(depthMask_);
        glCullFace(GLenum(cullFace_));
        glPolygonMode(GL_FRONT_AND_BACK, GLenum(polygonMode_[0]));
        glPolygonOffset(offset_[0], offset_[1]);
        glScissor(scissor_[0], scissor_[1], scissor_[2], scissor_[3]);
        glColorMask(colorMask_[0], colorMask_[1], colorMask_[2], colorMask_[3]);
        glClipControl(GLenum(clip_[0]), GLenum(clip_[1]));
    }
    ScopedRasterState(const ScopedRasterState&) = delete;
    ScopedRasterState& operator=(const ScopedRasterState&) = delete;

private:
    GLint blend_[4] = {GL_ONE, GL_ZERO, GL_ONE, GL_ZERO}, equation_[2] = {GL_FUNC_ADD, GL_FUNC_ADD};
    GLint depthFunc_ = GL_LESS, cullFace_ = GL_BACK, polygonMode_[2] = {GL_FILL, GL_FILL};
    GLboolean depthMask_ = GL_TRUE, colorMask_[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLfloat offset_[2] = {0.0f, 0.0f};
    GLint scissor_[4] = {0, 0, 0, 0}, clip_[2] = {GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE};
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
