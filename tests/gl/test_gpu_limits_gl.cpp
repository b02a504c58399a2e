// GPU limits asked before allocating (engine/gl/limits): on the real driver, the proxy probe agrees
// with GL_MAX_TEXTURE_SIZE and raises no GL error; the queried limits are sane.
#include <gtest/gtest.h>

#include "engine/gl/gl.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/limits.hpp"
#include "gl_fixture.hpp"

using namespace lp;

TEST(GpuLimits, ProbeAcceptsSmallTexturesAndRefusesOverTheLimitWithoutGlErrors) {
    const gl::RenderTargetLimits limits = gl::queryRenderTargetLimits(test::gContext->isSoftware());
    ASSERT_GE(limits.maxTextureSize, 1024);
    EXPECT_GE(limits.maxViewport[0], 1024);
    for (GLenum format : {GLenum(GL_RGBA8), GLenum(GL_RGBA16F), GLenum(GL_RGBA32F), GLenum(GL_R16UI),
                          GLenum(GL_DEPTH_COMPONENT32F), GLenum(GL_DEPTH24_STENCIL8)}) {
        EXPECT_TRUE(gl::canAllocateTexture(format, 64, 64)) << gl::formatName(format);
        EXPECT_FALSE(gl::canAllocateTexture(format, limits.maxTextureSize + 1, 1)) << gl::formatName(format);
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}
