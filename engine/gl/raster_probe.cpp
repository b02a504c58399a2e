#include "engine/gl/raster_probe.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/gl/state.hpp"

namespace lp::gl {

namespace {
constexpr int kSize = 32;

// The plane through three window-space points, evaluated at (x, y).
double planeAt(const double (&wx)[3], const double (&wy)[3], const double (&wz)[3], double x, double y) {
    const double e1x = wx[1] - wx[0], e1y = wy[1] - wy[0], e2x = wx[2] - wx[0], e2y = wy[2] - wy[0];
    const double det = e1x * e2y - e2x * e1y;
    const double dzdx = ((wz[1] - wz[0]) * e2y - (wz[2] - wz[0]) * e1y) / det;
    const double dzdy = ((wz[2] - wz[0]) * e1x - (wz[1] - wz[0]) * e2x) / det;
    return wz[0] + dzdx * (x - wx[0]) + dzdy * (y - wy[0]);
}
}  // namespace

RasterInterpolation probeRasterInterpolation(const ShaderLibrary& shaders) {
    RasterInterpolation r;
    GLint bits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
    r.subpixelBits = std::clamp(int(bits), 4, 16);

    // Window positions a third and a fifth of a sub-pixel step off the grid, depth rising steeply
    // across the tile, so the two models' planes differ by far more than depth rounding.
    const double step = std::ldexp(1.0, -r.subpixelBits);
    const double wx[3] = {2.0 + 0.3 * step + 0.137, 29.0 + 0.2 * step + 0.611, 8.0 + 0.45 * step + 0.271};
    const double wy[3] = {3.0 + 0.35 * step + 0.419, 7.0 + 0.15 * step + 0.083, 30.0 + 0.4 * step + 0.557};
    const double wz[3] = {0.05, 0.93, 0.41};
    float ndc[9];
    for (int i = 0; i < 3; ++i) {
        ndc[3 * i] = float(wx[i] / kSize * 2.0 - 1.0);
        ndc[3 * i + 1] = float(wy[i] / kSize * 2.0 - 1.0);
        ndc[3 * i + 2] = float(wz[i] * 2.0 - 1.0);
    }
    // What the hardware sees: the float NDC back in window space (double), then snapped.
    double fx[3], fy[3], fz[3], sx[3], sy[3];
    for (int i = 0; i < 3; ++i) {
        fx[i] = (double(ndc[3 * i]) * 0.5 + 0.5) * kSize;
        fy[i] = (double(ndc[3 * i + 1]) * 0.5 + 0.5) * kSize;
        fz[i] = double(ndc[3 * i + 2]) * 0.5 + 0.5;
        sx[i] = std::round(fx[i] / step) * step;
        sy[i] = std::round(fy[i] / step) * step;
    }

    Program program = shaders.graphics("raster_probe.vert", "raster_probe.frag");
    Texture depth = makeTexture2D(GL_DEPTH_COMPONENT32F, kSize, kSize, 1, "raster_probe.depth");
    Framebuffer fbo = makeFramebuffer("raster_probe");
    glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth.id(), 0);
    glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    VertexArray vao = makeVertexArray("raster_probe");
    std::vector<float> z(size_t(kSize) * kSize, 1.0f);
    {
        ScopedRasterState raster;
        ScopedFramebuffer target(fbo.id(), kSize, kSize);
        ScopedEnable depthTest(GL_DEPTH_TEST, true), cull(GL_CULL_FACE, false), scissor(GL_SCISSOR_TEST, false),
            clamp(GL_DEPTH_CLAMP, false), offset(GL_POLYGON_OFFSET_FILL, false), multisample(GL_MULTISAMPLE, false);
        GLint program0 = 0, vao0 = 0;
        GLfloat depthRange[2] = {0.0f, 1.0f};
        glGetIntegerv(GL_CURRENT_PROGRAM, &program0);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao0);
        glGetFloatv(GL_DEPTH_RANGE, depthRange);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDepthRange(0.0, 1.0);
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_TRUE);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        const float one = 1.0f;
        glClearNamedFramebufferfv(fbo.id(), GL_DEPTH, 0, &one);
        glUseProgram(program.id());
        glProgramUniform3fv(program.id(), glGetUniformLocation(program.id(), "uNdc"), 3, ndc);
        glBindVertexArray(vao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(GLuint(vao0));
        glUseProgram(GLuint(program0));
        glDepthRange(depthRange[0], depthRange[1]);
    }
    GLint packAlignment = 4;
    glGetIntegerv(GL_PACK_ALIGNMENT, &packAlignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(z.size() * sizeof(float)), z.data());
    glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float d = z[size_t(y) * kSize + size_t(x)];
            if (d >= 1.0f) continue;  // not covered
            const double cx = x + 0.5, cy = y + 0.5;
            r.unsnappedError += std::abs(double(d) - planeAt(fx, fy, fz, cx, cy));
            r.snappedError += std::abs(double(d) - planeAt(sx, sy, fz, cx, cy));
        }
    r.fromSnappedVertices = r.snappedError < r.unsnappedError;
    return r;
}

}  // namespace lp::gl
