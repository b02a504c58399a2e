// Image-based lighting on the GL driver: white furnace, split-sum energy, the DFG LUT against
// a double-precision integral, the prefiltered chain of a sun-dominated map, the disk cache and the
// tone-map operators. Bake sizes and sample counts are kept small (llvmpipe).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include <unistd.h>

#include "engine/render/ibl_environment.hpp"
#include "engine/render/ibl_sh.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/primitives.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

constexpr double kPi = 3.14159265358979323846;

EnvironmentSettings smallBake() { return lp::test::smallIblBake(256); }

std::filesystem::path tempPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("lightpass-ibl-test-" + std::to_string(::getpid()) + "-" + name);
}

std::string quarryPath() {
    return std::string(LIGHTPASS_SHARED_ASSETS) + "/hdri-polyhaven-1k/quarry_01_1k.hdr";
}

// Solid angle of texel (i, j) of a cube face of `size` (exact: area element integrated).
double texelSolidAngle(int i, int j, int size) {
    auto area = [](double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); };
    const double x0 = 2.0 * i / size - 1.0, x1 = 2.0 * (i + 1) / size - 1.0;
    const double y0 = 2.0 * j / size - 1.0, y1 = 2.0 * (j + 1) / size - 1.0;
    return area(x0, y0) - area(x0, y1) - area(x1, y0) + area(x1, y1);
}

std::vector<float> readCubeLevel(const gl::Texture& t, int level) {
    const int s = std::max(t.width >> level, 1);
    std::vector<float> data(size_t(s) * s * 6 * 4);
    glGetTextureImage(t.id(), level, GL_RGBA, GL_FLOAT, GLsizei(data.size() * sizeof(float)), data.data());
    return data;
}

// Integral of radiance over the sphere, per channel.
glm::dvec3 cubeEnergy(const std::vector<float>& data, int size) {
    glm::dvec3 e(0.0);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const float* p = &data[((size_t(f) * size + j) * size + i) * 4];
                e += glm::dvec3(p[0], p[1], p[2]) * texelSolidAngle(i, j, size);
            }
    return e;
}

// Double-precision DFG reference: the integral over the half-vector hemisphere after the GGX CDF
// change of variables, by a 1024 x 256 midpoint rule (independent of the shader's Hammersley
// estimator); roughness 0 by its analytic limit (H = N: A = 1 - Fc(N.V), B = Fc(N.V)).
glm::dvec2 dfgReference(double nv, double roughness) {
    if (roughness == 0.0) {
        const double fc = std::pow(1.0 - nv, 5.0);
        return {1.0 - fc, fc};
    }
    const double alpha = roughness * roughness, a2 = alpha * alpha;
    const glm::dvec3 V(std::sqrt(1.0 - nv * nv), 0.0, nv);
    const int nt = 1024, np = 256;
    glm::dvec2 ab(0.0);
    for (int i = 0; i < nt; ++i) {
        const double xi = (i + 0.5) / nt;
        const double cosT = std::sqrt((1.0 - xi) / (1.0 + (a2 - 1.0) * xi)), sinT = std::sqrt(1.0 - cosT * cosT);
        for (int k = 0; k < np; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / np;
            const glm::dvec3 H(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
            const double vh = glm::dot(V, H);
            const glm::dvec3 L = 2.0 * vh * H - V;
            if (L.z <= 0.0 || vh <= 0.0) continue;
            const double nl = L.z;
            const double vis = 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
            const double w = vis * 4.0 * nl * vh / cosT;
            const double fc = std::pow(1.0 - vh, 5.0);
            ab += glm::dvec2((1.0 - fc) * w, fc * w);
        }
    }
    return ab / double(nt * np);
}

}  // namespace

// White furnace: a white Lambertian sphere (kd = 1, ks = 0) in a uniform environment of radiance 1,
// no lights, ambient 0. Bound: every sphere pixel's radiance is 1 +- 1%, with diffuse from SH and
// from the irradiance cube. (global_lights is switched off: without lights and ambient it adds 0.)
TEST(Ibl, WhiteFurnaceSphereReflectsTheEnvironmentExactly) {
    const auto mapPath = tempPath("furnace.exr");
    ImageF white;
    white.width = 32;
    white.height = 16;
    white.rgba.assign(size_t(32 * 16 * 4), 1.0f);
    writeExr(mapPath, white);

    Scene scene;
    ModelInstance m;
    m.name = "sphere";
    m.primitive = "sphere";
    m.mesh = makeSphere(0.5f, 64, 32);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = glm::vec3(1.0f);
        mat.specular = glm::vec3(0.0f);
        mat.shininess = 32.0f;
    }
    scene.models.push_back(std::move(m));
    scene.ambient = glm::vec3(0.0f);
    scene.environment.map = mapPath;
    scene.camera.position = glm::vec3(0.0f, 0.0f, 2.5f);
    scene.camera.target = glm::vec3(0.0f);
    scene.camera.fovYDegrees = 40.0f;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 10.0f;

    Renderer r(scene);
    for (IrradianceSource source : {IrradianceSource::SphericalHarmonics, IrradianceSource::Cubemap}) {
        RenderSettings s;
        s.width = 64;
        s.height = 48;
        s.keepHdr = true;
        s.environment = smallBake();
        s.environment.diffuse = source;
        s.disabledPasses.insert("global_lights");
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        ImageF hdr = r.readHdr();
        const glm::dmat4 inv = glm::inverse(glm::dmat4(scene.camera.projection(64.0f / 48.0f)) * glm::dmat4(scene.camera.view()));
        int onSphere = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) {
                const double nx = (x + 0.5) / 64 * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / 48 * 2.0;
                glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
                // Inside radius 0.45: away from the tessellated silhouette.
                const double bq = glm::dot(o, d), c = glm::dot(o, o) - 0.45 * 0.45;
                if (bq * bq - c <= 0.0) continue;
                ++onSphere;
                const float* p = &hdr.rgba[(size_t(y) * 64 + size_t(x)) * 4];
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_NEAR(p[ch], 1.0, 0.01) << "pixel " << x << "," << y << " source " << int(source);
            }
        EXPECT_GT(onSphere, 200);
    }
    std::filesystem::remove(mapPath);
}

// GGX with F0 = 1: the split sum's white-environment reflectance A + B is at most 1 (a microfacet
// BRDF with Smith shadowing loses energy, never gains it). Bound: A + B <= 1 + 2^-10 (one RG16F
// ulp at 1) for every texel of a 32^2 LUT, and <= 1 + 1e-4 for the float integrator at 11 x 11
// (N.V, roughness) points including 0 and 1.
TEST(Ibl, SplitSumWithF0OneNeverExceedsOne) {
    EnvironmentCache cache;
    EnvironmentSettings s = smallBake();
    gl::ShaderLibrary shaders;
    const gl::Texture& lut = cache.dfgLut(s, shaders);
    std::vector<float> data(size_t(s.dfgSize) * s.dfgSize * 2);
    glGetTextureImage(lut.id(), 0, GL_RG, GL_FLOAT, GLsizei(data.size() * sizeof(float)), data.data());
    for (size_t i = 0; i < data.size(); i += 2) {
        ASSERT_TRUE(std::isfinite(data[i]) && std::isfinite(data[i + 1]));
        EXPECT_GE(data[i], 0.0f);
        EXPECT_GE(data[i + 1], 0.0f);
        EXPECT_LE(data[i] + data[i + 1], 1.0f + 1.0f / 1024.0f) << "texel " << i / 2;
    }
    std::vector<glm::vec4> in;
    for (int a = 0; a <= 10; ++a)
        for (int b = 0; b <= 10; ++b) in.push_back(glm::vec4(a / 10.0f, b / 10.0f, 0, 0));
    auto out = runGlsl({"common/ibl.glsl"}, "return vec4(dfgIntegrate(x.x, x.y, 1024u), 0.0, 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i) EXPECT_LE(out[i].x + out[i].y, 1.0f + 1e-4f) << in[i].x << " " << in[i].y;
}

// The DFG integrator (1024 Hammersley samples, float) against the double-precision reference on a
// 6 x 6 grid including N.V = 0 and roughness = 0. Bound: |A - A_ref|, |B - B_ref| <= 0.01. N.V = 0
// is referenced at the shader's documented clamp N.V = 1e-4 (at roughness 0.1 the exact-0 limit
// differs by 0.01 in B: the lobe is as narrow as that clamp).
TEST(Ibl, DfgMatchesDoublePrecisionIntegral) {
    const double grid[] = {0.0, 0.1, 0.25, 0.5, 0.75, 1.0};
    std::vector<glm::vec4> in;
    for (double nv : grid)
        for (double r : grid) in.push_back(glm::vec4(float(nv), float(r), 0, 0));
    auto out = runGlsl({"common/ibl.glsl"}, "return vec4(dfgIntegrate(x.x, x.y, 1024u), 0.0, 0.0);", in);
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec2 ref = dfgReference(std::max(double(in[i].x), 1e-4), in[i].y);
        EXPECT_NEAR(out[i].x, ref.x, 0.01) << "N.V " << in[i].x << " roughness " << in[i].y;
        EXPECT_NEAR(out[i].y, ref.y, 0.01) << "N.V " << in[i].x << " roughness " << in[i].y;
        worst = std::max({worst, std::abs(out[i].x - ref.x), std::abs(out[i].y - ref.y)});
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
}

// The prefiltered chain of quarry_01 (sun 86,528): no NaN/Inf; no texel of any mip brighter than the
// brightest source texel (a normalised positive kernel cannot make fireflies); each mip's integral
// over the sphere within 5% of mip 0's (per channel). Skipped when the asset is absent.
TEST(Ibl, PrefilteredChainOfSunnyMapIsFiniteAndKeepsEnergy) {
    if (!std::filesystem::exists(quarryPath())) GTEST_SKIP() << quarryPath() << " absent";
    Scene scene;
    scene.environment.map = quarryPath();
    EnvironmentCache cache;
    EnvironmentSettings s = smallBake();
    s.cubeSize = 64;
    s.specularSize = 32;
    s.specularLevels = 6;
    s.specularSamples = 128;
    gl::ShaderLibrary shaders;
    const BakedEnvironment& env = cache.get(scene, s, shaders, true);
    float sourceMax = 0.0f;
    for (float v : readCubeLevel(env.cube, 0)) sourceMax = std::max(sourceMax, v);
    const glm::dvec3 e0 = cubeEnergy(readCubeLevel(env.prefiltered, 0), 32);
    for (int level = 0; level < s.specularLevels; ++level) {
        const int size = 32 >> level;
        auto data = readCubeLevel(env.prefiltered, level);
        for (float v : data) {
            ASSERT_TRUE(std::isfinite(v)) << "mip " << level;
            ASSERT_LE(v, sourceMax) << "mip " << level;
        }
        const glm::dvec3 e = cubeEnergy(data, size);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c] / e0[c], 1.0, 0.05) << "mip " << level << " channel " << c;
    }
}

// The disk cache (--ibl-cache) returns exactly what was baked: same SH, byte-equal cube levels.
TEST(Ibl, DiskCacheRoundTripsTheBake) {
    const auto mapPath = tempPath("gradient.exr");
    const auto dir = tempPath("cache");
    ImageF img;
    img.width = 64;
    img.height = 32;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) img.rgba.insert(img.rgba.end(), {x / 64.0f, y / 32.0f, 0.5f, 1.0f});
    writeExr(mapPath, img);
    Scene scene;
    scene.environment.map = mapPath;
    scene.environment.rotationDegrees = 30.0f;
    EnvironmentSettings s = smallBake();
    s.cacheDir = dir.string();
    gl::ShaderLibrary shaders;
    EnvironmentCache first, second;
    const BakedEnvironment& a = first.get(scene, s, shaders, true);
    ASSERT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 2);
    const BakedEnvironment& b = second.get(scene, s, shaders, true);
    for (int i = 0; i < 9; ++i) EXPECT_EQ(a.sh[size_t(i)], b.sh[size_t(i)]);
    for (int l = 0; l < a.cube.levels; ++l) EXPECT_EQ(readCubeLevel(a.cube, l), readCubeLevel(b.cube, l));
    for (int l = 0; l < a.prefiltered.levels; ++l)
        EXPECT_EQ(readCubeLevel(a.prefiltered, l), readCubeLevel(b.prefiltered, l));
    EXPECT_EQ(readCubeLevel(a.irradiance, 0), readCubeLevel(b.irradiance, 0));
    std::filesystem::remove_all(dir);
    std::filesystem::remove(mapPath);
}

// forgetBakes (lightpass sweep times each IBL setting's bake): the cube stays, the bake is redone
// on the next get and its GPU time is reported; a disk-cache hit reports 0 (nothing was baked).
TEST(Ibl, ForgetBakesBakesAgainAndReportsItsGpuTime) {
    const auto mapPath = tempPath("forget.exr");
    ImageF img;
    img.width = 32;
    img.height = 16;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) img.rgba.insert(img.rgba.end(), {x / 32.0f, 1.0f, y / 16.0f, 1.0f});
    writeExr(mapPath, img);
    Scene scene;
    scene.environment.map = mapPath;
    const EnvironmentSettings s = smallBake();
    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    EXPECT_EQ(cache.lastBakeGpuMs(), 0.0);
    const GLuint cube = cache.get(scene, s, shaders, true).cube.id();
    cache.dfgLut(s, shaders);  // ready(.., true) also wants the LUT, which forgetBakes keeps
    EXPECT_GT(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, true));
    cache.forgetBakes();
    EXPECT_EQ(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, false));  // the cube is kept
    EXPECT_FALSE(cache.ready(scene, s, true));  // the bake is not
    EXPECT_EQ(cache.get(scene, s, shaders, true).cube.id(), cube);
    EXPECT_GT(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, true));

    EnvironmentSettings cached = s;
    cached.cacheDir = tempPath("forget-cache").string();
    EnvironmentCache writer, reader;
    writer.get(scene, cached, shaders, true);
    reader.get(scene, cached, shaders, true);
    EXPECT_EQ(reader.lastBakeGpuMs(), 0.0);
    std::filesystem::remove_all(cached.cacheDir);
    std::filesystem::remove(mapPath);
}

// The shader's SH irradiance equals the CPU (double) one. Bound: relative 1e-4 at 64 normals.
TEST(Ibl, ShaderShIrradianceMatchesCpu) {
    ShCoefficients sh{};
    for (int i = 0; i < 9; ++i) sh[size_t(i)] = glm::dvec3(1.0 - 0.1 * i, 0.3 + 0.05 * i, (i % 3) * 0.2);
    std::string body = "vec3 sh[9];\n";
    for (int i = 0; i < 9; ++i)
        body += "sh[" + std::to_string(i) + "] = vec3(" + std::to_string(sh[size_t(i)].x) + ", " +
                std::to_string(sh[size_t(i)].y) + ", " + std::to_string(sh[size_t(i)].z) + ");\n";
    body += "return vec4(shIrradiance(sh, normalize(x.xyz)), 0.0);";
    std::vector<glm::vec4> in;
    for (int i = 0; i < 64; ++i) {
        double z = 1.0 - (i + 0.5) / 32.0, phi = i * 2.399963;
        double r = std::sqrt(1.0 - z * z);
        in.push_back(glm::vec4(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z), 0.0f));
    }
    auto out = runGlsl({"common/ibl.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        glm::dvec3 ref = shIrradiance(sh, glm::normalize(glm::dvec3(in[i])));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[i][c], ref[c], 1e-4 * std::max(1.0, std::abs(ref[c])));
    }
}

// Every tone map at 0, 1e-30, 1, 1e38, +Inf, NaN: finite and in [0, 1]; NaN maps like 0 and +Inf
// like 65504 (sanitised first); non-decreasing over 2001 grey levels 1e-6 .. 1e5 (bound: each step
// >= -1e-6). ACES and PBR Neutral also match double references within 1e-5.
TEST(Ibl, ToneMapOperatorsAreFiniteAndMonotone) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::vec4> in;
    for (float h : {0.0f, 1e-30f, 1.0f, 1e38f, inf, nan, 65504.0f}) in.push_back(glm::vec4(h));
    const size_t sweepStart = in.size();
    for (int i = 0; i <= 2000; ++i) in.push_back(glm::vec4(float(std::pow(10.0, -6.0 + 11.0 * i / 2000.0))));
    auto aces = [](double x) {
        return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
    };
    auto neutral = [](double x) {  // grey input: offset, then the highlight compression
        double off = x < 0.08 ? x - 6.25 * x * x : 0.04;
        double c = x - off;
        if (c < 0.76) return c;
        double d = 0.24, np = 1.0 - d * d / (c + d - 0.76);
        return np;  // grey stays grey: the desaturation mix is the identity
    };
    for (int op = 0; op < 4; ++op) {
        auto out = runGlsl({"common/tonemap.glsl"}, "return vec4(applyToneMap(x.xyz, " + std::to_string(op) + "), 0.0);", in);
        for (size_t i = 0; i < in.size(); ++i) {
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(out[i][c])) << "op " << op << " input " << in[i].x;
                EXPECT_GE(out[i][c], 0.0f);
                EXPECT_LE(out[i][c], 1.0f);
            }
        }
        EXPECT_EQ(out[5].x, out[0].x) << "op " << op << ": NaN maps like 0";
        EXPECT_EQ(out[4].x, out[6].x) << "op " << op << ": +Inf maps like 65504";
        EXPECT_EQ(out[3].x, out[6].x) << "op " << op << ": 1e38 maps like 65504";
        for (size_t i = sweepStart + 1; i < in.size(); ++i)
            EXPECT_GE(out[i].x - out[i - 1].x, -1e-6f) << "op " << op << " at " << in[i].x;
        if (op == 1 || op == 2)
            for (size_t i = sweepStart; i < in.size(); ++i)
                EXPECT_NEAR(out[i].x, op == 1 ? aces(in[i].x) : neutral(in[i].x), 1e-5) << "op " << op << " at " << in[i].x;
    }
}
