// The visibility-buffer G-buffer (--gbuffer-mode visibility): the ray/triangle barycentrics of
// shaders/common/visibility.glsl against a double-precision reference, and the resolved G-buffer,
// every debug view and the final HDR image against the classic raster G-buffer on every bundled
// scene and on the glTF test models with textures, normal maps and MASK alpha.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/gl/handles.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/motion.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/frame_builder.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {

// ---- shaders/common/visibility.glsl ---------------------------------------------------------

// Random triangles in front of the eye and random points on them (barycentrics, some outside the
// triangle as the derivative rays are): the ray from the eye through the point, scaled arbitrarily,
// gives back the point's barycentrics.
TEST(ShaderVisibility, RayBarycentricsArePerspectiveCorrect) {
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> xy(-2.0f, 2.0f), z(-20.0f, -0.2f), w(-0.3f, 1.3f), scale(0.01f, 50.0f);
    std::vector<glm::vec4> inputs, expected;
    const int n = 256;
    for (int i = 0; i < n; ++i) {
        glm::vec3 v[3];
        for (glm::vec3& p : v) p = {xy(rng), xy(rng), z(rng)};
        const float b1 = w(rng), b2 = w(rng);
        const glm::dvec3 b(1.0 - double(b1) - double(b2), b1, b2);
        const glm::dvec3 point = b.x * glm::dvec3(v[0]) + b.y * glm::dvec3(v[1]) + b.z * glm::dvec3(v[2]);
        const glm::vec3 dir = glm::vec3(point) * scale(rng);
        // Four vec4 per case: v0, v1, v2 and the ray direction.
        inputs.emplace_back(v[0], 0.0f);
        inputs.emplace_back(v[1], 0.0f);
        inputs.emplace_back(v[2], 0.0f);
        inputs.emplace_back(dir, 0.0f);
        const glm::dvec3 normal = glm::cross(glm::dvec3(v[1] - v[0]), glm::dvec3(v[2] - v[0]));
        expected.emplace_back(glm::vec3(b), glm::dot(normal, glm::dvec3(v[0])) < 0.0 ? 1.0f : 0.0f);
    }
    // Each invocation reads its case's four inputs (the harness hands it only x, its own index).
    const std::string globals = R"(
layout(std430, binding = 7) readonly buffer Cases { vec4 cases[]; };
)";
    gl::Buffer cases = gl::makeBuffer(GLsizeiptr(inputs.size() * sizeof(glm::vec4)), inputs.data(), 0, "cases");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, cases.id());
    std::vector<glm::vec4> index(n);
    for (int i = 0; i < n; ++i) index[size_t(i)] = glm::vec4(float(i));
    const std::vector<glm::vec4> got = test::runGlsl({"common/visibility.glsl"}, R"(
        int c = int(x.x) * 4;
        vec3 v0 = cases[c].xyz, v1 = cases[c + 1].xyz, v2 = cases[c + 2].xyz;
        vec3 b = rayTriangleBarycentrics(vec3(0.0), cases[c + 3].xyz, v0, v1, v2);
        return vec4(b, eyeTriangleFrontFacing(v0, v1, v2) ? 1.0 : 0.0);
    )",
                                                     index, globals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, 0);
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        const glm::vec4 e = expected[size_t(i)], g = got[size_t(i)];
        for (int k = 0; k < 3; ++k) worst = std::max(worst, double(std::abs(g[k] - e[k])));
        EXPECT_EQ(g.w, e.w) << "facing of case " << i;
    }
    std::printf("  largest barycentric error %.3g\n", worst);
    EXPECT_LT(worst, 2e-4);
}

// interpolateAttribute keeps a value the three vertices share exact, whatever the weights' rounding:
// random triangles lying in a plane z = c (c random, like a floor's eye z), with weights that sum to
// 1 only within 4 ulps (an approximate reciprocal in windowBarycentrics' normalisation leaves them
// so on NVIDIA). z must come out exactly c; x and y (up to ~60) within 1e-4 of the double reference.
// The sum form b0 a0 + b1 a1 + b2 a2 misses c for many of these cases (checked on the CPU below),
// which a light lying in the plane turns into N.L != 0 (StabilityRender.LightAtTheCameraAndOnTheSurface).
TEST(ShaderVisibility, SharedVertexValuesInterpolateExactly) {
    std::mt19937 rng(1919);
    std::uniform_real_distribution<float> xy(-20.0f, 20.0f), plane(-30.0f, -0.1f), w(-0.3f, 1.3f);
    std::uniform_int_distribution<int> ulps(-4, 4);
    const int n = 256;
    std::vector<glm::vec4> inputs, index(n);
    std::vector<glm::dvec3> expected;
    int sumFormMisses = 0;
    for (int i = 0; i < n; ++i) {
        const float c = plane(rng);
        glm::vec3 v[3];
        for (glm::vec3& p : v) p = {xy(rng), xy(rng), c};
        const float b1 = w(rng), b2 = w(rng);
        glm::vec3 b(1.0f - b1 - b2, b1, b2);
        for (int k = 0; k < 3; ++k) b[k] = b[k] * (1.0f + float(ulps(rng)) * std::ldexp(1.0f, -24));
        inputs.emplace_back(v[0], 0.0f);
        inputs.emplace_back(v[1], 0.0f);
        inputs.emplace_back(v[2], 0.0f);
        inputs.emplace_back(b, 0.0f);
        expected.push_back(double(b.x) * glm::dvec3(v[0]) + double(b.y) * glm::dvec3(v[1]) + double(b.z) * glm::dvec3(v[2]));
        volatile float sumForm = b.x * c;  // no contraction: the float sum form
        sumForm = sumForm + b.y * c;
        sumForm = sumForm + b.z * c;
        sumFormMisses += sumForm != c ? 1 : 0;
        index[size_t(i)] = glm::vec4(float(i));
    }
    ASSERT_GT(sumFormMisses, n / 10) << "the cases do not exercise the weights' rounding";
    const std::string globals = R"(
layout(std430, binding = 7) readonly buffer Cases { vec4 cases[]; };
)";
    gl::Buffer cases = gl::makeBuffer(GLsizeiptr(inputs.size() * sizeof(glm::vec4)), inputs.data(), 0, "cases");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, cases.id());
    const std::vector<glm::vec4> got = test::runGlsl({"common/visibility.glsl"}, R"(
        int c = int(x.x) * 4;
        return vec4(interpolateAttribute(cases[c + 3].xyz, cases[c].xyz, cases[c + 1].xyz, cases[c + 2].xyz), 0.0);
    )",
                                                     index, globals);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, 0);
    for (int i = 0; i < n; ++i) {
        const glm::vec4 g = got[size_t(i)];
        EXPECT_EQ(g.z, inputs[size_t(i) * 4].z) << "case " << i << ": the plane's z is not kept";
        for (int k = 0; k < 2; ++k)
            EXPECT_NEAR(g[k], expected[size_t(i)][k], 1e-4) << "case " << i << " component " << k;
    }
}

TEST(ShaderVisibility, IdPackingKeepsZeroForEmpty) {
    const std::vector<glm::vec4> got = test::runGlsl({"common/visibility.glsl"}, R"(
        uint id = visibilityPackId(uint(x.x), uint(x.y));
        return vec4(float(id == LP_VISIBILITY_EMPTY), float(visibilityTriangle(id)), 0.0, 0.0);
    )",
                                                     {glm::vec4(0, 0, 0, 0), glm::vec4(100, 7, 0, 0), glm::vec4(0, 65535, 0, 0)});
    EXPECT_EQ(got[0], glm::vec4(0, 0, 0, 0));
    EXPECT_EQ(got[1], glm::vec4(0, 107, 0, 0));
    EXPECT_EQ(got[2], glm::vec4(0, 65535, 0, 0));
}

// ---- the resolved G-buffer against the classic one ------------------------------------------

constexpr int kWidth = 96, kHeight = 64;

struct GBufferImages {
    std::vector<float> depth;
    std::vector<glm::vec4> normal, diffuse, position, specular, tangent;
    std::vector<glm::vec2> texcoord, velocity;
    std::vector<uint32_t> ids;  // visibility mode only
};

template <class T>
std::vector<T> readTexture(GLuint tex, GLenum format, GLenum type) {
    std::vector<T> v(size_t(kWidth) * kHeight);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(tex, 0, format, type, GLsizei(v.size() * sizeof(T)), v.data());
    return v;
}

// A frame at t = 1 s after one at t = 1 - 1/30 s (the camera paths move, so velocity is not zero),
// with a sub-pixel jitter so the resolve's rays must follow the jittered projection.
FrameData testFrame(const Scene& scene, const RenderSettings& s) {
    FrameData previous = makeFrameData(scene, s, 1.0f - 1.0f / 30.0f);
    FrameData f = makeFrameData(scene, s, 1.0f);
    applyMotion(f, motionHistoryOf(previous), glm::vec2(0.3f, -0.2f));
    return f;
}

// The G-buffer of `mode` alone with every channel (the unpacked, stored layout: every value as the
// material evaluation computed it, at float precision).
GBufferImages renderGBuffer(const Scene& scene, SceneGpu& gpu, const gl::ShaderLibrary& shaders, PassStates& states,
                            GBufferMode mode, fg::TexturePool* keptPool = nullptr) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = kWidth;
    s.height = kHeight;
    s.gbuffer.mode = mode;
    FrameData frame = testFrame(scene, s);
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    fg::FrameGraph graph;
    fg::TexturePool localPool;
    fg::TexturePool& pool = keptPool ? *keptPool : localPool;
    GBufferChannels channels;
    channels.texcoord = channels.tangent = channels.velocity = true;
    GBuffer g;
    fg::ResourceId ids;
    if (mode == GBufferMode::Visibility) {
        const VisibilityBuffer v = addVisibilityPass(graph, states.visibility, frame);
        ids = v.ids;
        g = addVisibilityResolvePass(graph, states.visibilityResolve, frame, v, channels);
        graph.markOutput(ids);
    } else {
        g = addGBufferPass(graph, states.gbuffer, frame, channels);
    }
    for (fg::ResourceId r : {g.depth, g.normal, g.diffuse, g.position, g.specular, g.texcoord, g.tangent, g.velocity})
        graph.markOutput(r);
    graph.compile();
    graph.execute(pool);
    GBufferImages out;
    out.depth = readTexture<float>(graph.outputTexture(g.depth), GL_DEPTH_COMPONENT, GL_FLOAT);
    out.normal = readTexture<glm::vec4>(graph.outputTexture(g.normal), GL_RGBA, GL_FLOAT);
    out.diffuse = readTexture<glm::vec4>(graph.outputTexture(g.diffuse), GL_RGBA, GL_FLOAT);
    out.position = readTexture<glm::vec4>(graph.outputTexture(g.position), GL_RGBA, GL_FLOAT);
    out.specular = readTexture<glm::vec4>(graph.outputTexture(g.specular), GL_RGBA, GL_FLOAT);
    out.tangent = readTexture<glm::vec4>(graph.outputTexture(g.tangent), GL_RGBA, GL_FLOAT);
    out.texcoord = readTexture<glm::vec2>(graph.outputTexture(g.texcoord), GL_RG, GL_FLOAT);
    out.velocity = readTexture<glm::vec2>(graph.outputTexture(g.velocity), GL_RG, GL_FLOAT);
    if (ids.valid()) {
        out.ids = readTexture<uint32_t>(graph.outputTexture(ids), GL_RED_INTEGER, GL_UNSIGNED_INT);
        // The ids are not cleared: where the depth keeps its cleared value the pixel is empty (0).
        const float background = s.gbuffer.position == GBufferPositionMode::ReversedZ ? 0.0f : 1.0f;
        for (size_t i = 0; i < out.ids.size(); ++i)
            if (out.depth[i] == background) out.ids[i] = 0;
    }
    return out;
}

// Where a pixel's 2x2 quad (the one the raster computed its derivatives over) holds more than one
// triangle: the hardware's texture footprint there comes from helper invocations, the resolve's
// from the pixel's own neighbours' rays, so texture LOD may differ.
bool onTriangleEdge(const std::vector<uint32_t>& ids, int x, int y) {
    const int qx = x & ~1, qy = y & ~1;
    const uint32_t id = ids[size_t(y) * kWidth + size_t(x)];
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const int px = std::min(qx + dx, kWidth - 1), py = std::min(qy + dy, kHeight - 1);
            if (ids[size_t(py) * kWidth + size_t(px)] != id) return true;
        }
    return false;
}

double angleDegrees(glm::vec3 a, glm::vec3 b) {
    const double la = glm::length(glm::dvec3(a)), lb = glm::length(glm::dvec3(b));
    if (la <= 0.0 || lb <= 0.0) return la == lb ? 0.0 : 180.0;
    return glm::degrees(std::acos(std::clamp(glm::dot(glm::dvec3(a), glm::dvec3(b)) / (la * lb), -1.0, 1.0)));
}

double maxAbs(glm::vec4 a, glm::vec4 b, int channels) {
    double d = 0.0;
    for (int c = 0; c < channels; ++c) d = std::max(d, double(std::abs(a[c] - b[c])));
    return d;
}

// Per pixel, every channel within these bounds (docs/visibility-buffer.md): the G-buffer's own
// storage bounds (tests/gl/test_gbuffer_formats.cpp: 1/255 for colours, 0.04 for shininess and
// 1e-4 deg for unpacked normals) widened only for float rounding in the rebuilt interpolation.
struct Mismatch {
    int covered = 0, edge = 0, bad = 0, badOffEdge = 0;
    double normalDeg = 0, colour = 0, shininess = 0, position = 0, texcoord = 0, tangent = 0, velocityPx = 0;
    std::string firstBad;
};

// The channel differences of two pixels (classic against visibility, or a classic pixel against
// its neighbour on the same triangle).
struct ChannelDiff {
    double normalDeg = 0, colour = 0, shininess = 0, position = 0, texcoord = 0, tangent = 0;
};

ChannelDiff channelDiff(const GBufferImages& a, size_t i, const GBufferImages& b, size_t j) {
    ChannelDiff d;
    d.normalDeg = angleDegrees(a.normal[i], b.normal[j]);
    d.colour = std::max(maxAbs(a.diffuse[i], b.diffuse[j], 4), maxAbs(a.specular[i], b.specular[j], 3));
    d.shininess = std::abs(a.specular[i].w - b.specular[j].w) / std::max(1.0f, a.specular[i].w);
    d.position = glm::length(glm::dvec3(a.position[i] - b.position[j])) / std::max(1e-3, glm::length(glm::dvec3(a.position[i])));
    d.texcoord = glm::length(glm::dvec2(a.texcoord[i] - b.texcoord[j])) / std::max(1.0, glm::length(glm::dvec2(a.texcoord[i])));
    d.tangent = maxAbs(a.tangent[i], b.tangent[j], 4);
    return d;
}

// The rasteriser snaps vertices to 1 / 2^GL_SUBPIXEL_BITS of a pixel and may interpolate from the
// snapped triangle (NVIDIA does; llvmpipe interpolates from the unsnapped one), while the resolve
// rebuilds the exact one: a pixel's values may then differ by what moving the triangle by about a
// sub-pixel step changes them, taken as their change to each of the four neighbouring pixels on the
// same triangle times 2^-bits, summed. That term widens each per-channel bound.
ChannelDiff snapAllowance(const GBufferImages& c, const std::vector<uint32_t>& ids, int x, int y, double step) {
    const size_t i = size_t(y) * kWidth + size_t(x);
    ChannelDiff a;
    for (auto [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= kWidth || ny >= kHeight) continue;
        const size_t j = size_t(ny) * kWidth + size_t(nx);
        if (ids[j] != ids[i]) continue;
        const ChannelDiff d = channelDiff(c, i, c, j);
        a.normalDeg += d.normalDeg * step;
        a.colour += d.colour * step;
        a.shininess += d.shininess * step;
        a.position += d.position * step;
        a.texcoord += d.texcoord * step;
        a.tangent += d.tangent * step;
    }
    return a;
}

Mismatch compareGBuffers(const GBufferImages& c, const GBufferImages& v, double normalBoundDeg) {
    Mismatch m;
    GLint bits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &bits);
    const double step = std::ldexp(1.0, -std::max(bits, 4));  // the sub-pixel grid, in pixels
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + size_t(x);
            if (c.depth[i] != v.depth[i]) {  // the same vertex shader: the same depth, bit for bit
                ++m.bad;
                ++m.badOffEdge;
                if (m.firstBad.empty()) m.firstBad = "depth at " + std::to_string(x) + "," + std::to_string(y);
                continue;
            }
            const glm::vec2 dv = (c.velocity[i] - v.velocity[i]) * glm::vec2(kWidth, kHeight);
            const double velocityPx = glm::length(glm::dvec2(dv));
            m.velocityPx = std::max(m.velocityPx, velocityPx);
            if (c.depth[i] >= 1.0f) continue;  // background: only velocity is written
            ++m.covered;
            const bool edge = onTriangleEdge(v.ids, x, y);
            m.edge += edge;
            const ChannelDiff d = channelDiff(c, i, v, i);
            const ChannelDiff snap = snapAllowance(c, v.ids, x, y, step);
            const double normalDeg = d.normalDeg, colour = d.colour, shininess = d.shininess, position = d.position,
                         texcoord = d.texcoord, tangent = d.tangent;
            m.normalDeg = std::max(m.normalDeg, normalDeg);
            m.colour = std::max(m.colour, colour);
            m.shininess = std::max(m.shininess, shininess);
            m.position = std::max(m.position, position);
            m.texcoord = std::max(m.texcoord, texcoord);
            m.tangent = std::max(m.tangent, tangent);
            const bool bad = normalDeg > normalBoundDeg + snap.normalDeg || colour > 1.0 / 255.0 + 1e-4 + snap.colour ||
                             shininess > 0.04 + snap.shininess || position > 1e-4 + snap.position ||
                             texcoord > 1e-4 + snap.texcoord || tangent > 2.0 / 255.0 + snap.tangent || velocityPx > 0.02;
            if (!bad) continue;
            ++m.bad;
            if (!edge) {
                ++m.badOffEdge;
                if (m.firstBad.empty())
                    m.firstBad = "pixel " + std::to_string(x) + "," + std::to_string(y) + " normal " +
                                 std::to_string(normalDeg) + " deg, colour " + std::to_string(colour) + ", shininess " +
                                 std::to_string(shininess) + ", position " + std::to_string(position) + ", uv " +
                                 std::to_string(texcoord) + ", tangent " + std::to_string(tangent);
            }
        }
    return m;
}

// A 64x64 texture of hashed noise in every channel (alpha included): each mip level differs from
// the next, so a texture sampled at another LOD than the raster's shows up in every channel.
TextureRef noiseTexture(uint32_t seed) {
    Image8 img;
    img.width = img.height = 64;
    img.rgba.resize(64 * 64 * 4);
    uint32_t h = seed * 2654435761u + 1u;
    for (uint8_t& v : img.rgba) {
        h ^= h << 13;
        h ^= h >> 17;
        h ^= h << 5;
        v = uint8_t(h >> 24);
    }
    TextureRef t;
    t.encoded = std::make_shared<const std::string>(encodePng(img));
    t.key = "visibility-test-noise-" + std::to_string(seed);
    return t;
}

// A floor seen at a grazing angle (many mip levels and anisotropy across the image) and a sphere,
// with every kind of map: base colour (with alpha), bump, normal, metallic-roughness, occlusion; the
// sphere single-sided and MASK (its alpha test cuts holes through which the floor shows).
Scene everyMapScene() {
    Scene s;
    auto add = [&](const std::string& name, MeshData mesh, glm::mat4 transform, bool masked, uint32_t seed) {
        ModelInstance m;
        m.name = name;
        m.primitive = name;
        m.mesh = std::move(mesh);
        for (Material& mat : m.mesh.materials) {
            mat.diffuseMap = noiseTexture(seed);
            mat.bumpMap = noiseTexture(seed + 1);
            mat.bumpScale = 0.3f;
            mat.normalMap = noiseTexture(seed + 2);
            mat.normalScale = 0.8f;
            mat.metallicRoughnessMap = noiseTexture(seed + 3);
            mat.metallic = 1.0f;
            mat.roughness = 0.9f;
            mat.occlusionMap = noiseTexture(seed + 4);
            mat.occlusionStrength = 0.7f;
            if (masked) {
                mat.alphaMode = AlphaMode::Mask;
                mat.alphaCutoff = 0.3f;
                mat.doubleSided = false;
            }
        }
        m.transform = transform;
        s.models.push_back(std::move(m));
    };
    add("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(30.0f)), false, 10);
    add("sphere", makeSphere(0.6f, 32, 16), glm::translate(glm::mat4(1.0f), {0.0f, 0.6f, 0.0f}), true, 20);
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    sun.intensity = 2.0f;
    s.directionalLights.push_back(sun);
    s.ambient = glm::vec3(0.05f);
    s.camera.position = {0.0f, 0.5f, 3.0f};
    s.camera.target = {0.0f, 0.3f, 0.0f};
    s.camera.fovYDegrees = 60.0f;
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 60.0f;
    return s;
}

// Every bundled scene (the gallery where ../shared/assets is present), the glTF test models (a
// base-colour texture with MASK alpha, a normal map) and the every-map scene above.
std::vector<std::pair<std::string, Scene>> testScenes() {
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const char* name : {"cornell", "cornell-flythrough", "depth-discontinuity", "ibl-spheres", "lights-4k",
                             "pbr-spheres", "unlit", "gallery"}) {
        const std::string path = test::repoPath(std::string("scenes/") + name + ".json");
        if (std::string(name) == "gallery" && !std::filesystem::exists(std::string(LIGHTPASS_SHARED_ASSETS) + "/stanford-bunny")) {
            std::printf("  gallery: ../shared/assets is absent, not compared\n");
            continue;
        }
        scenes.emplace_back(name, loadScene(path));
    }
    for (const char* model : {"alpha_mask.gltf", "normal_plane.glb", "forms.glb"}) {
        const std::string path = test::repoPath(std::string("tests/data/gltf/") + model);
        scenes.emplace_back(model, sceneForModel(path));
    }
    scenes.emplace_back("every map", everyMapScene());
    return scenes;
}

// Anisotropic filtering is not continuous in its gradients (the driver picks a whole number of
// probes along the long axis), so float-rounding differences between the raster's interpolated uv
// and the resolve's rebuilt one flip the filtered value of the noise textures above: measured up to
// 0.37 in a colour on llvmpipe (where compute and fragment shaders also filter anisotropically in
// different ways) and normals 18 degrees apart on an H100. Isotropic trilinear filtering is
// continuous in them, so the comparison samples isotropically (still through every mip level,
// which the noise makes differ) on every driver.
void isotropicSampling(const SceneGpu& gpu) {
    for (const GpuMaterial& m : gpu.materials)
        for (GLuint t : {m.diffuseMap, m.bumpMap, m.normalMap, m.metallicRoughnessMap, m.occlusionMap})
            if (t && GLAD_GL_EXT_texture_filter_anisotropic) glTextureParameterf(t, GL_TEXTURE_MAX_ANISOTROPY_EXT, 1.0f);
}

bool hasNormalDetailMaps(const Scene& scene) {
    for (const ModelInstance& m : scene.models)
        for (const Material& mat : m.mesh.materials)
            if (!mat.normalMap.empty() || !mat.bumpMap.empty()) return true;
    return false;
}

TEST(VisibilityBuffer, GBufferEqualsClassicOnEveryBundledScene) {
    const gl::ShaderLibrary shaders;
    for (auto& [name, scene] : testScenes()) {
        SCOPED_TRACE(name);
        SceneGpu gpu(scene);
        isotropicSampling(gpu);
        PassStates states;
        const GBufferImages classic = renderGBuffer(scene, gpu, shaders, states, GBufferMode::Classic);
        const GBufferImages visibility = renderGBuffer(scene, gpu, shaders, states, GBufferMode::Visibility);
        // Normals: oct24's storage bound; with normal or bump maps oct16's (a texel's normal turns
        // with the last bits of the interpolated uv and tangent frame).
        const double normalBound = hasNormalDetailMaps(scene) ? 0.7 : 0.06;
        const Mismatch m = compareGBuffers(classic, visibility, normalBound);
        const double badFraction = m.covered ? double(m.bad) / m.covered : 0.0;
        std::printf("  %-22s covered %5d, on edges %5d; max: normal %.2e deg, colour %.2e, shininess %.2e, "
                    "position %.2e, uv %.2e, tangent %.2e, velocity %.2e px; out of bounds %d (%.2f%%), %d off edges\n",
                    name.c_str(), m.covered, m.edge, m.normalDeg, m.colour, m.shininess, m.position, m.texcoord,
                    m.tangent, m.velocityPx, m.bad, 100.0 * badFraction, m.badOffEdge);
        EXPECT_GT(m.covered, 0);
        // Off triangle edges: none, but for one pixel in 2000 (at least one), which is where a
        // rasteriser that clips a triangle at the near plane (the floors here pass under the camera)
        // meets its own clipped pieces: their seam is an edge the ids do not show. Measured: none on
        // llvmpipe; on an H100 one pixel of the every-map floor, none elsewhere.
        EXPECT_LE(m.badOffEdge, std::max(1, m.covered / 2000)) << m.firstBad;
        EXPECT_LE(badFraction, 0.02);
    }
}

// ---- texture level of detail ------------------------------------------------------------------

// A 256² base-colour texture whose mip level k (0..8) is one flat colour of linear red k / 8 and blue
// 1 - k / 8: a trilinear sample's red is its level of detail / 8, whatever the filter's footprint
// shape. Uploaded over the levels SceneGpu generated (an sRGB texture: the codes of those values).
constexpr int kLevelTextureSize = 256, kLevelCount = 9;

void uploadLevelColours(GLuint texture) {
    auto code = [](double linear) {
        const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
        return uint8_t(std::lround(std::clamp(s, 0.0, 1.0) * 255.0));
    };
    for (int level = 0; level < kLevelCount; ++level) {
        const int size = kLevelTextureSize >> level;
        const double t = double(level) / (kLevelCount - 1);
        const uint8_t texel[4] = {code(t), code(0.5), code(1.0 - t), 255};
        std::vector<uint8_t> pixels(size_t(size) * size * 4);
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = texel[i % 4];
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(texture, level, 0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    }
}

// The texture those levels are uploaded into: any 256² image (grey), replaced before any frame.
TextureRef levelTexture() {
    Image8 img;
    img.width = img.height = kLevelTextureSize;
    img.rgba.assign(size_t(kLevelTextureSize) * kLevelTextureSize * 4, 128);
    TextureRef t;
    t.encoded = std::make_shared<const std::string>(encodePng(img));
    t.key = "visibility-test-levels";
    return t;
}

// The linear albedo (diffuse rgb) a G-buffer holds at pixel i.
glm::dvec3 storedAlbedo(const GBufferImages& g, size_t i) { return glm::dvec3(g.diffuse[i]); }

// A floor under a grazing view (levels 0 to 8 and anisotropy up to the sampler's 8 and beyond), a
// sphere (every orientation, the pole's pinched texels) and a wall facing the camera (isotropic),
// each with the level-coloured base colour, sampled as the scene's textures are (trilinear,
// anisotropic 8): the default sampler.
Scene levelColouredScene() {
    Scene s;
    auto add = [&](const std::string& name, MeshData mesh, glm::mat4 transform, float uvScale) {
        ModelInstance m;
        m.name = name;
        m.primitive = name;
        m.mesh = std::move(mesh);
        for (Vertex& v : m.mesh.vertices) v.uv *= uvScale;
        for (Material& mat : m.mesh.materials) {
            mat.diffuse = glm::vec3(1.0f);
            mat.diffuseMap = levelTexture();  // its levels are replaced (uploadLevelColours)
        }
        m.transform = transform;
        s.models.push_back(std::move(m));
    };
    add("floor", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(30.0f)), 8.0f);
    add("sphere", makeSphere(0.6f, 32, 16), glm::translate(glm::mat4(1.0f), {-0.7f, 0.6f, 0.0f}), 2.0f);
    add("wall", makePlane(1.0f, 2),
        glm::translate(glm::mat4(1.0f), {1.2f, 0.8f, -1.0f}) * glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), {1, 0, 0}),
        1.0f);
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    s.directionalLights.push_back(sun);
    s.camera.position = {0.0f, 0.5f, 3.0f};
    s.camera.target = {0.0f, 0.3f, 0.0f};
    s.camera.fovYDegrees = 60.0f;
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 60.0f;
    return s;
}

// The visibility resolve samples every map with textureGrad and the uv derivatives of the pixel's
// quad partners, so it must read each texel at the raster's level of detail: with the level-coloured
// texture, the level read back (8 x linear red) at every covered pixel in both modes, on the default
// (anisotropic) sampler, within a tenth of a level. On llvmpipe, whose anisotropic filter takes its
// footprint from SIMD lanes (in a compute shader no 2x2 quad: engine/gl/gradient_probe), the resolve
// read blocks of pixels up to 6 levels away from the raster's before it filtered anisotropically
// itself; measured since: 0 levels apart at all 3738 pixels (llvmpipe).
TEST(VisibilityBuffer, TexturesAreSampledAtTheRastersLevelOfDetail) {
    const gl::ShaderLibrary shaders;
    const Scene scene = levelColouredScene();
    SceneGpu gpu(scene);
    for (const GpuMaterial& m : gpu.materials) uploadLevelColours(m.diffuseMap);
    PassStates states;
    const GBufferImages classic = renderGBuffer(scene, gpu, shaders, states, GBufferMode::Classic);
    const GBufferImages visibility = renderGBuffer(scene, gpu, shaders, states, GBufferMode::Visibility);
    int covered = 0, over = 0;
    double worst = 0.0, minLevel = 1e9, maxLevel = -1e9;
    std::string first;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const size_t i = size_t(y) * kWidth + size_t(x);
            if (classic.depth[i] >= 1.0f) continue;
            ++covered;
            const double lc = (kLevelCount - 1) * storedAlbedo(classic, i).x;
            const double lv = (kLevelCount - 1) * storedAlbedo(visibility, i).x;
            minLevel = std::min(minLevel, lc);
            maxLevel = std::max(maxLevel, lc);
            worst = std::max(worst, std::abs(lc - lv));
            if (std::abs(lc - lv) <= 0.1) continue;
            ++over;
            if (first.empty())
                first = "pixel " + std::to_string(x) + "," + std::to_string(y) + ": classic level " + std::to_string(lc) +
                        ", visibility level " + std::to_string(lv);
        }
    std::printf("  covered %d, levels %.2f..%.2f, largest difference %.3f levels, %d pixels over 0.1\n", covered,
                minLevel, maxLevel, worst, over);
    EXPECT_GT(maxLevel - minLevel, 4.0);  // the scene spans the levels
    EXPECT_EQ(over, 0) << "first: " << first;
}

// The whole frame in both modes: the final HDR image (all lighting passes, emission, sky, AO) and
// every debug view.
ImageF renderHdr(Renderer& r, const RenderSettings& s) { return test::renderHdr(r, s, 1.0f); }

struct HdrError {
    double mean = 0.0, max = 0.0;
    bool finite = true;
};

HdrError compareHdr(const ImageF& got, const ImageF& ref) {
    HdrError e;
    const size_t n = size_t(ref.width) * size_t(ref.height);
    for (size_t i = 0; i < n; ++i) {
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double g = got.rgba[i * 4 + size_t(c)], r = ref.rgba[i * 4 + size_t(c)];
            if (!std::isfinite(g)) e.finite = false;
            worst = std::max(worst, std::abs(g - r) / (std::abs(r) + 0.05));
        }
        e.mean += worst / double(n);
        e.max = std::max(e.max, worst);
    }
    return e;
}

RenderSettings frameSettings(GBufferMode mode, DebugView view = DebugView::Final) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    s.autoExposure = false;       // and 0 EV
    s.width = kWidth;
    s.height = kHeight;
    s.view = view;
    s.gbuffer.mode = mode;
    s.shadows.size = 256;
    s.shadows.cascades = 2;
    s.environment = test::smallIblBake(64);
    return s;
}

// Neither mode clears its colour targets (only the depth): the visibility ids are not cleared, and
// the classic targets get the background by compute where the depth is empty. A frame that sees
// nothing after one that saw the whole box, with the same pool (so the same textures, still holding
// the first frame's values), must hold the background's values (zeros) everywhere in both modes.
TEST(VisibilityBuffer, StaleValuesOfAnEarlierFrameNeverReachTheGBuffer) {
    const gl::ShaderLibrary shaders;
    const Scene box = loadScene(test::repoPath("scenes/cornell.json"));
    Scene away = box;
    away.camera.target = away.camera.position + (away.camera.position - box.camera.target);  // turned round
    const float background = RenderSettings().gbuffer.position == GBufferPositionMode::ReversedZ ? 0.0f : 1.0f;
    for (GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility}) {
        SCOPED_TRACE(mode == GBufferMode::Classic ? "classic" : "visibility");
        SceneGpu gpu(box);
        PassStates states;
        fg::TexturePool pool;
        const GBufferImages first = renderGBuffer(box, gpu, shaders, states, mode, &pool);
        size_t covered = 0;
        for (float d : first.depth) covered += d != background ? 1 : 0;
        ASSERT_GT(covered, first.depth.size() / 2) << "the first frame should see the box";
        const GBufferImages second = renderGBuffer(away, gpu, shaders, states, mode, &pool);
        size_t surfaces = 0, stale = 0;
        for (size_t i = 0; i < second.depth.size(); ++i) {
            surfaces += second.depth[i] != background ? 1 : 0;
            const bool zero = second.diffuse[i] == glm::vec4(0.0f) && second.normal[i] == glm::vec4(0.0f) &&
                              second.position[i] == glm::vec4(0.0f) && second.specular[i] == glm::vec4(0.0f) &&
                              second.tangent[i] == glm::vec4(0.0f) && second.texcoord[i] == glm::vec2(0.0f);
            stale += zero ? 0 : 1;
        }
        EXPECT_EQ(surfaces, 0u) << "the second frame looks away from every surface";
        EXPECT_EQ(stale, 0u) << "pixels whose G-buffer is not the background's";
    }
}

TEST(VisibilityBuffer, FinalImageMatchesClassicOnEveryBundledScene) {
    for (auto& [name, scene] : testScenes()) {
        SCOPED_TRACE(name);
        Renderer r(scene);
        isotropicSampling(r.sceneGpu());
        const ImageF classic = renderHdr(r, frameSettings(GBufferMode::Classic));
        const ImageF visibility = renderHdr(r, frameSettings(GBufferMode::Visibility));
        EXPECT_TRUE(r.graph().isLive("gbuffer_resolve"));
        const HdrError e = compareHdr(visibility, classic);
        std::printf("  %-22s HDR relative error mean %.2e max %.2e\n", name.c_str(), e.mean, e.max);
        EXPECT_TRUE(e.finite);
        EXPECT_LT(e.mean, 2e-3);
        EXPECT_LT(e.max, 0.1);
    }
}

// The settings that change what the G-buffer is asked for or at what size, on the moving camera of
// cornell-flythrough (frames at 30 fps, so motion vectors, motion blur and TAA's history run): other
// normal formats and rebuilt positions (reversed-Z included), SSAA, render scale, TAA's jitter and
// history, motion blur, each local-light method that reads the G-buffer differently.
TEST(VisibilityBuffer, SettingsThatShapeTheGBufferMatchClassic) {
    const Scene scene = loadScene(test::repoPath("scenes/cornell-flythrough.json"));
    struct Variant {
        const char* name;
        std::function<void(RenderSettings&)> set;
        const char* pass = nullptr;  // a pass the variant must run
    };
    const Variant variants[] = {
        {"oct16 + reversed-z", [](RenderSettings& s) { s.gbuffer.normal = GBufferNormalFormat::Oct16;
                                                       s.gbuffer.position = GBufferPositionMode::ReversedZ; }},
        {"seed-packed-signed + depth", [](RenderSettings& s) { s.gbuffer.normal = GBufferNormalFormat::SeedPackedSigned;
                                                               s.gbuffer.position = GBufferPositionMode::Depth; }},
        {"two-angle", [](RenderSettings& s) { s.gbuffer.normal = GBufferNormalFormat::TwoAngle; }},
        {"ssaa 2", [](RenderSettings& s) { s.aa.method = AntiAliasing::Ssaa; }},
        {"render scale 0.5", [](RenderSettings& s) { s.renderScale = 0.5f; }},
        {"taa", [](RenderSettings& s) { s.aa.method = AntiAliasing::Taa; }, "taa"},
        {"motion blur", [](RenderSettings& s) { s.motionBlur.enabled = true; }, "motion_blur"},
        {"clustered lights", [](RenderSettings& s) { s.localLights.method = LocalLightMethod::Clustered; }, "local_lights"},
        {"volumes", [](RenderSettings& s) { s.localLights.method = LocalLightMethod::Volumes; }, "local_lights"},
    };
    auto run = [&](const Variant& v, GBufferMode mode) {
        Renderer r(scene);
        RenderSettings s = frameSettings(mode);
        s.keepHdr = true;
        v.set(s);
        for (int i = 0; i < 4; ++i) r.render(s, 1.0f + float(i) / 30.0f, false);  // a history for motion and TAA
        if (mode == GBufferMode::Visibility) EXPECT_TRUE(r.graph().isLive("gbuffer_resolve"));
        if (v.pass) EXPECT_TRUE(r.graph().isLive(v.pass)) << v.pass;
        return r.readHdr();
    };
    for (const Variant& v : variants) {
        SCOPED_TRACE(v.name);
        const HdrError e = compareHdr(run(v, GBufferMode::Visibility), run(v, GBufferMode::Classic));
        std::printf("  %-28s HDR relative error mean %.2e max %.2e\n", v.name, e.mean, e.max);
        EXPECT_TRUE(e.finite);
        EXPECT_LT(e.mean, 2e-3);
        EXPECT_LT(e.max, 0.1);
    }
}

TEST(VisibilityBuffer, EveryViewMatchesClassic) {
    const Scene scene = loadScene(test::repoPath("scenes/pbr-spheres.json"));
    Renderer r(scene);
    for (DebugView view : everyView()) {
        SCOPED_TRACE(viewName(view));
        r.render(frameSettings(GBufferMode::Classic, view), 1.0f);
        const Image8 classic = r.readDisplay();
        r.render(frameSettings(GBufferMode::Visibility, view), 1.0f);
        const Image8 visibility = r.readDisplay();
        int worst = 0;
        size_t over = 0;
        for (size_t i = 0; i < classic.rgba.size(); ++i) {
            const int d = std::abs(int(classic.rgba[i]) - int(visibility.rgba[i]));
            worst = std::max(worst, d);
            over += d > 2;
        }
        std::printf("  %-16s largest difference %d / 255, %zu channel values over 2\n", viewName(view), worst, over);
        // 8-bit views: the G-buffer channels' 1-2 levels (the formats test's bound), and no more
        // than 1% of values beyond (the final image's dither and tone map amplify HDR noise).
        EXPECT_LE(double(over), 0.01 * double(classic.rgba.size()));
    }
}

}  // namespace
