#pragma once
// The depth-only raster the spot and point shadow maps draw their casters in: `depth` on `fbo` (no
// colour), depth test LESS with writes, no culling (thin walls and open meshes cast from both sides),
// no blending, the slope offset, depth clamp (casters before the near plane still cast). Every piece
// of state it sets is restored when it goes out of scope, the framebuffer binding and viewport last.
#include "engine/gl/gl.hpp"
#include "engine/gl/state.hpp"

namespace lp {

// `fbo` with `depth` as its only attachment.
inline GLuint attachShadowDepth(GLuint fbo, GLuint depth) {
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    glNamedFramebufferReadBuffer(fbo, GL_NONE);
    return fbo;
}

struct ShadowDepthRaster {
    ShadowDepthRaster(GLuint fbo, GLuint depth, int width, int height, float slopeBias)
        : bind(attachShadowDepth(fbo, depth), width, height) {
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glPolygonOffset(slopeBias, 0.0f);
    }
    gl::ScopedFramebuffer bind;
    gl::ScopedEnable depthTest{GL_DEPTH_TEST, true};
    gl::ScopedEnable cull{GL_CULL_FACE, false};
    gl::ScopedEnable blend{GL_BLEND, false};
    gl::ScopedEnable offset{GL_POLYGON_OFFSET_FILL, true};
    gl::ScopedEnable clamp{GL_DEPTH_CLAMP, true};
    gl::ScopedRasterState saved;  // depth function and mask, polygon offset
};

}  // namespace lp
