#include "engine/render/floors.hpp"

#include <vector>

#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/state.hpp"

namespace lp {

Bandwidth measureComputeBandwidth(const gl::ShaderLibrary& shaders, int width, int height, int repeats) {
    gl::Program prog = shaders.compute("bandwidth_copy.comp");
    gl::Texture a = gl::makeTexture2D(GL_RGBA32F, width, height, 1, "bandwidth.src");
    gl::Texture b = gl::makeTexture2D(GL_RGBA32F, width, height, 1, "bandwidth.dst");
    const float zero[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(a.id(), 0, GL_RGBA, GL_FLOAT, zero);
    glUseProgram(prog.id());
    gl::Query q0 = gl::makeQuery(GL_TIMESTAMP), q1 = gl::makeQuery(GL_TIMESTAMP);
    std::vector<double> ms;
    for (int i = 0; i < repeats + 5; ++i) {
        glBindImageTexture(0, (i % 2) ? b.id() : a.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
        glBindImageTexture(1, (i % 2) ? a.id() : b.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glQueryCounter(q0.id(), GL_TIMESTAMP);
        gl::dispatch2D(width, height);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glQueryCounter(q1.id(), GL_TIMESTAMP);
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(q0.id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(q1.id(), GL_QUERY_RESULT, &t1);
        if (i >= 5) ms.push_back(double(t1 - t0) * 1e-6);
    }
    glUseProgram(0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    Bandwidth bw;
    bw.bytes = size_t(width) * size_t(height) * 16 * 2;
    bw.copyMs = gl::median(ms);
    bw.bytesPerSecond = bw.copyMs > 0.0 ? double(bw.bytes) / (bw.copyMs * 1e-3) : 0.0;
    return bw;
}

Bandwidth measureFragmentBandwidth(const gl::ShaderLibrary& shaders, int width, int height, int repeats) {
    gl::Program prog = shaders.graphics("fullscreen.vert", "fill_rate.frag");
    gl::Texture target = gl::makeTexture2D(GL_RGBA32F, width, height, 1, "fillrate.target");
    gl::Framebuffer fbo = gl::makeFramebuffer("fillrate");
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
    gl::VertexArray vao = gl::makeVertexArray("fillrate");
    gl::ScopedFramebuffer bind(fbo.id(), width, height);
    gl::ScopedEnable depth(GL_DEPTH_TEST, false);
    gl::ScopedEnable blend(GL_BLEND, false);
    glUseProgram(prog.id());
    glBindVertexArray(vao.id());
    gl::Query q0 = gl::makeQuery(GL_TIMESTAMP), q1 = gl::makeQuery(GL_TIMESTAMP);
    std::vector<double> ms;
    for (int i = 0; i < repeats + 5; ++i) {
        glQueryCounter(q0.id(), GL_TIMESTAMP);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glQueryCounter(q1.id(), GL_TIMESTAMP);
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(q0.id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(q1.id(), GL_QUERY_RESULT, &t1);
        if (i >= 5) ms.push_back(double(t1 - t0) * 1e-6);
    }
    glBindVertexArray(0);
    glUseProgram(0);
    Bandwidth bw;
    bw.bytes = size_t(width) * size_t(height) * 16;
    bw.copyMs = gl::median(ms);
    bw.bytesPerSecond = bw.copyMs > 0.0 ? double(bw.bytes) / (bw.copyMs * 1e-3) : 0.0;
    return bw;
}

double passFloorMs(fg::PassKind kind, size_t bytes, const Bandwidth& compute, const Bandwidth& fragment) {
    const double rate = kind == fg::PassKind::Raster ? fragment.bytesPerSecond : compute.bytesPerSecond;
    return rate > 0.0 ? double(bytes) / rate * 1e3 : 0.0;
}

const char* floorBasis(fg::PassKind kind) { return kind == fg::PassKind::Raster ? "fragment fill" : "compute copy"; }

FloorBandwidths measureFloorBandwidths(const gl::ShaderLibrary& shaders, int width, int height, int repeats) {
    return {measureComputeBandwidth(shaders, width, height, repeats), measureFragmentBandwidth(shaders, width, height, repeats)};
}

std::optional<PassFloor> passFloor(const fg::FrameGraph& graph, const std::string& pass, const FloorBandwidths& bandwidths) {
    const size_t bytes = graph.passTrafficBytes(pass);
    if (bytes == 0) return std::nullopt;
    const fg::PassKind kind = graph.passKind(pass);  // what the pass declared
    return PassFloor{bytes, passFloorMs(kind, bytes, bandwidths.compute, bandwidths.fragment), floorBasis(kind)};
}

}  // namespace lp
