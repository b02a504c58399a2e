#include "tests/gl/render_fixture.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "engine/graph/frame_graph.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/gl/shader.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/scene.hpp"
#include "frame/renderer.hpp"
#include "passes/gbuffer_pass.hpp"

namespace lp::test {

VelocityImage renderGBufferVelocity(const Scene& scene, FrameData frame) {
    SceneGpu gpu(scene);
    gl::ShaderLibrary shaders;
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    GBufferPass state;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    GBufferChannels channels;
    channels.velocity = true;
    const GBuffer g = addGBufferPass(graph, state, frame, channels);
    graph.markOutput(g.depth);
    graph.markOutput(g.velocity);
    graph.compile();
    graph.execute(pool);
    VelocityImage out;
    out.width = frame.width;
    out.height = frame.height;
    const size_t n = size_t(frame.width) * size_t(frame.height);
    out.depth.resize(n);
    out.velocity.resize(n);
    glGetTextureImage(graph.outputTexture(g.depth), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)),
                      out.depth.data());
    glGetTextureImage(graph.outputTexture(g.velocity), 0, GL_RG, GL_FLOAT, GLsizei(n * sizeof(glm::vec2)),
                      out.velocity.data());
    return out;
}

std::optional<glm::dvec3> planePoint(const Camera& camera, int width, int height, int x, int y, double planeY) {
    const glm::dmat4 inv =
        glm::inverse(glm::dmat4(camera.projection(float(width) / float(height))) * glm::dmat4(camera.view()));
    const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / height * 2.0;
    const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 o = glm::dvec3(a) / a.w, dir = glm::dvec3(b) / b.w - o;
    if ((planeY - o.y) * dir.y <= 0.0) return std::nullopt;
    return o + dir * ((planeY - o.y) / dir.y);
}

ImageF renderHdr(Renderer& renderer, RenderSettings settings, float time) {
    settings.keepHdr = true;
    renderer.render(settings, time, false);
    return renderer.readHdr();
}

ImageF renderHdr(const Scene& scene, RenderSettings settings, float time) {
    Renderer renderer(scene);
    return renderHdr(renderer, std::move(settings), time);
}

bool segmentHitsBox(glm::dvec3 a, glm::dvec3 b, glm::dvec3 lo, glm::dvec3 hi) {
    const glm::dvec3 d = b - a;
    double t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(d[i]) < 1e-12) {
            if (a[i] < lo[i] || a[i] > hi[i]) return false;
            continue;
        }
        double u = (lo[i] - a[i]) / d[i], v = (hi[i] - a[i]) / d[i];
        if (u > v) std::swap(u, v);
        t0 = std::max(t0, u);
        t1 = std::min(t1, v);
        if (t0 > t1) return false;
    }
    return true;
}

testing::AssertionResult valuesNear(const std::vector<float>& a, const std::vector<float>& b, int width, int channels,
                                    float tolerance, const std::string& what) {
    const std::string label = what.empty() ? "" : what + ": ";
    if (a.size() != b.size())
        return testing::AssertionFailure() << label << "sizes differ (" << a.size() << " and " << b.size() << " values)";
    size_t differing = 0, first = 0, worst = 0;
    double largest = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double error = std::abs(double(a[i]) - double(b[i]));
        if (error <= tolerance) continue;  // NaN compares false: it differs
        if (differing++ == 0) first = i;
        if (!(error <= largest)) largest = error, worst = i;
    }
    if (differing == 0) return testing::AssertionSuccess();
    const size_t perRow = size_t(width) * size_t(channels);
    auto where = [&](size_t i) {
        std::ostringstream s;
        s << "texel (" << (i % perRow) / size_t(channels) << ", " << i / perRow << ") channel " << i % size_t(channels);
        return s.str();
    };
    std::ostringstream m;  // 6 significant digits, not gtest's 17
    m << label << differing << " of " << a.size() << " values differ by more than " << tolerance << "; first at "
      << where(first) << ": " << a[first] << " vs " << b[first] << "; largest error " << largest << " at " << where(worst)
      << " (" << a[worst] << " vs " << b[worst] << ")";
    return testing::AssertionFailure() << m.str();
}

testing::AssertionResult imagesNear(const ImageF& a, const ImageF& b, float tolerance, const std::string& what) {
    if (a.width != b.width || a.height != b.height)
        return testing::AssertionFailure() << (what.empty() ? "" : what + ": ") << "sizes differ (" << a.width << "x"
                                           << a.height << " and " << b.width << "x" << b.height << ")";
    return valuesNear(a.rgba, b.rgba, a.width, 4, tolerance, what);
}

}  // namespace lp::test
