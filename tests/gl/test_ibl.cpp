// Image-based lighting on the GL driver: white furnace, split-sum energy, the DFG LUT against
// a double-precision integral, the prefiltered chain of a sun-dominated map, the disk cache and the
// tone-map operators. Bake sizes and sample counts are kept small (llvmpipe).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include <unistd.h>

#include "engine/render/gltf_brdf.hpp"
#include "engine/render/ibl_environment.hpp"
#include "engine/render/ibl_sh.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/primitives.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/tonemap_reference.hpp"

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
// estimator); roughness 0 by its analytic limit (H = N: A = 1 - Fc(N.V), B = Fc(N.V)). Smith of `masking`
// (the renderer's default unless given).
glm::dvec2 dfgReference(double nv, double roughness, SpecularMasking masking = RenderSettings{}.specularMasking) {
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
            const double w = lp::test::ggxVisibilityRef(masking, nv, nl, alpha) * 4.0 * nl * vh / cosT;
            const double fc = std::pow(1.0 - vh, 5.0);
            ab += glm::dvec2((1.0 - fc) * w, fc * w);
        }
    }
    return ab / double(nt * np);
}

// One sphere of radius 0.5 at the origin under the environment map `map`, seen from 2.5 m with a
// 40 degree field of view, no ambient: the furnace and small-lamp tests' scene.
Scene sphereUnderMap(const std::filesystem::path& map, glm::vec3 diffuse, glm::vec3 specular, float shininess) {
    Scene scene;
    ModelInstance m;
    m.name = "sphere";
    m.primitive = "sphere";
    m.mesh = makeSphere(0.5f, 64, 32);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = diffuse;
        mat.specular = specular;
        mat.shininess = shininess;
    }
    scene.models.push_back(std::move(m));
    scene.ambient = glm::vec3(0.0f);
    scene.environment.map = map;
    scene.camera.position = glm::vec3(0.0f, 0.0f, 2.5f);
    scene.camera.target = glm::vec3(0.0f);
    scene.camera.fovYDegrees = 40.0f;
    scene.camera.nearPlane = 0.1f;
    scene.camera.farPlane = 10.0f;
    return scene;
}

// The pixels of a w x h image of sphereUnderMap's scene whose ray meets the sphere inside radius
// 0.45 (away from the tessellated silhouette), with the normal of the radius-0.5 sphere there, the
// direction to the eye and N.V (clamped to [1e-4, 1]).
struct SpherePixel {
    int x, y;
    glm::dvec3 normal, view;
    double nv;
};
std::vector<SpherePixel> spherePixels(const Scene& scene, int w, int h) {
    const glm::dmat4 inv = glm::inverse(glm::dmat4(scene.camera.projection(float(w) / float(h))) * glm::dmat4(scene.camera.view()));
    std::vector<SpherePixel> pixels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
            const glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            const double bq = glm::dot(o, d);
            if (bq * bq - (glm::dot(o, o) - 0.45 * 0.45) <= 0.0) continue;
            const glm::dvec3 n = (o + (-bq - std::sqrt(bq * bq - (glm::dot(o, o) - 0.25))) * d) / 0.5;
            pixels.push_back({x, y, n, -d, std::clamp(glm::dot(n, -d), 1e-4, 1.0)});
        }
    return pixels;
}

// The directional albedo A + B of lightpass's GGX (F0 = 1, Smith of `masking`) at N.V, computed once per
// N.V (the sphere images are symmetric) into `memo` (one memo per roughness and masking).
double memoAlbedo(std::map<long, double>& memo, double nv, double roughness,
                  SpecularMasking masking = RenderSettings{}.specularMasking) {
    const long key = std::lround(nv * 1e7);
    auto it = memo.find(key);
    if (it == memo.end()) {
        const glm::dvec2 ab = dfgReference(nv, roughness, masking);
        it = memo.emplace(key, ab.x + ab.y).first;
    }
    return it->second;
}

}  // namespace

// White furnace: a Lambertian sphere (ks = 0) of albedo 1 and of albedo 0.5 in a uniform environment
// of radiance 1, no lights, ambient 0. Bound: every sphere pixel's radiance is the albedo +- 0.5%,
// with diffuse from SH and from the irradiance cube, and with either specular method (--ibl-specular
// split-sum and sampled). Ks = 0 must be exactly Lambertian: the IBL's
// F0 A + f90 B has f90 = 0 there, as the analytic GGX (a grey sphere used to get B at its rim, +18%).
// (global_lights is switched off: without lights and ambient it adds 0.)
TEST(Ibl, WhiteFurnaceSphereReflectsTheEnvironmentExactly) {
  for (float albedo : {1.0f, 0.5f}) {
    const test::WhiteFurnaceMap map("furnace");
    const auto& mapPath = map.path;

    const Scene scene = sphereUnderMap(mapPath, glm::vec3(albedo), glm::vec3(0.0f), 32.0f);

    Renderer r(scene);
    for (IrradianceSource source : {IrradianceSource::SphericalHarmonics, IrradianceSource::Cubemap})
    for (IblSpecular specular : {IblSpecular::SplitSum, IblSpecular::Sampled}) {
        RenderSettings s;
        s.width = 64;
        s.height = 48;
        s.keepHdr = true;
        s.environment = smallBake();
        s.environment.diffuse = source;
        s.environment.specular = specular;
        s.disabledPasses.insert("global_lights");
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        ImageF hdr = r.readHdr();
        const std::vector<SpherePixel> sphere = spherePixels(scene, 64, 48);
        for (const SpherePixel& px : sphere) {
            const float* p = &hdr.rgba[(size_t(px.y) * 64 + size_t(px.x)) * 4];
            const double stored = test::srgb8Stored(albedo);  // the 8-bit sRGB G-buffer's albedo
            for (int ch = 0; ch < 3; ++ch)
                EXPECT_NEAR(p[ch], stored, 0.005 * stored)
                    << "pixel " << px.x << "," << px.y << " source " << int(source) << " albedo " << albedo
                    << " specular " << iblSpecularName(specular);
        }
        EXPECT_GT(sphere.size(), 200u);
    }
  }
}

// White furnace with a GGX sphere (diffuse 0, specular 1: F0 = f90 = 1) at alpha 0.5 and 1: every
// pixel reflects the directional albedo of lightpass's own BRDF at its N.V, here the double-precision
// A + B, under each masking model (--specular-masking; at alpha 1 the two albedos differ by up to 5%, so
// a LUT baked with the wrong one fails). Bound: the sphere mean within 0.5% of the exact mean (issue
// #16's furnace target), each pixel within 2% (the 32^2 LUT's bilinear and Hammersley error). Both
// specular methods: the sampled one (4 samples a pixel) takes its magnitude from the same LUT, so a
// uniform environment must come out exactly as the split sum's.
TEST(Ibl, WhiteFurnaceGgxSphereReflectsItsExactAlbedo) {
    const test::WhiteFurnaceMap map("furnace-ggx");
    const auto& mapPath = map.path;
    for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated})
    for (IblSpecular specular : {IblSpecular::SplitSum, IblSpecular::Sampled})
    for (float shininess : {6.0f, 0.0f}) {  // alpha = sqrt(2 / (n + 2)): 0.5 and 1
        SCOPED_TRACE(std::string(iblSpecularName(specular)) + ", " + specularMaskingName(masking));
        const Scene scene = sphereUnderMap(mapPath, glm::vec3(0.0f), glm::vec3(1.0f), shininess);
        Renderer r(scene);
        RenderSettings s;
        s.specularMasking = masking;
        s.width = 48;
        s.height = 36;
        s.keepHdr = true;
        s.environment = lp::test::smallIblBake(512);
        s.environment.specular = specular;
        s.environment.specularRuntimeSamples = 4;  // the fewest the sampled method is meant for
        s.disabledPasses.insert("global_lights");
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        ImageF hdr = r.readHdr();
        const double roughness = std::sqrt(std::sqrt(2.0 / (shininess + 2.0)));
        double sum = 0.0, sumExact = 0.0;
        std::map<long, double> albedoAt;
        const std::vector<SpherePixel> sphere = spherePixels(scene, 48, 36);
        for (const SpherePixel& px : sphere) {
            const double exact = memoAlbedo(albedoAt, px.nv, roughness, masking);
            const float* p = &hdr.rgba[(size_t(px.y) * 48 + size_t(px.x)) * 4];
            EXPECT_NEAR(p[1], exact, 0.02 * exact) << "pixel " << px.x << "," << px.y << " N.V " << px.nv << " n " << shininess;
            sum += p[1];
            sumExact += exact;
        }
        ASSERT_GT(sphere.size(), 100u);
        EXPECT_NEAR(sum / sumExact, 1.0, 0.005) << "shininess " << shininess;
        RecordProperty(std::string(iblSpecularName(specular)) + "_" + specularMaskingName(masking) +
                           "_mean_rel_error_n" + std::to_string(int(shininess)),
                       std::to_string(sum / sumExact - 1.0));
    }
}

// GGX with F0 = 1: the split sum's white-environment reflectance A + B is at most 1 (a microfacet
// BRDF with Smith shadowing loses energy, never gains it). Bound: A + B <= 1 + 2^-10 (one RG16F
// ulp at 1) for every texel of a 32^2 LUT, and <= 1 + 1e-4 for the float integrator at 11 x 11
// (N.V, roughness) points including 0 and 1.
TEST(Ibl, SplitSumWithF0OneNeverExceedsOne) {
  for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated}) {
    SCOPED_TRACE(specularMaskingName(masking));
    EnvironmentCache cache;
    EnvironmentSettings s = smallBake();
    gl::ShaderLibrary shaders;
    const gl::Texture& lut = cache.dfgLut(s, masking, shaders);
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
    auto out = runGlsl({"common/ibl.glsl"}, "return vec4(dfgIntegrate(x.x, x.y, 1024u, " + std::to_string(int(masking)) +
                       "), 0.0, 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i) EXPECT_LE(out[i].x + out[i].y, 1.0f + 1e-4f) << in[i].x << " " << in[i].y;
  }
}

// The DFG integrator (1024 Hammersley samples, float) against the double-precision reference on a
// 6 x 6 grid including N.V = 0 and roughness = 0, for each masking model. Bound: |A - A_ref|, |B - B_ref| <= 0.01. N.V = 0
// is referenced at the shader's documented clamp N.V = 1e-4 (at roughness 0.1 the exact-0 limit
// differs by 0.01 in B: the lobe is as narrow as that clamp).
TEST(Ibl, DfgMatchesDoublePrecisionIntegral) {
    const double grid[] = {0.0, 0.1, 0.25, 0.5, 0.75, 1.0};
    std::vector<glm::vec4> in;
    for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated})
        for (double nv : grid)
            for (double r : grid) in.push_back(glm::vec4(float(nv), float(r), float(int(masking)), 0));
    auto out = runGlsl({"common/ibl.glsl"}, "return vec4(dfgIntegrate(x.x, x.y, 1024u, int(x.z)), 0.0, 0.0);", in);
    double worst = 0.0;
    for (size_t i = 0; i < in.size(); ++i) {
        const SpecularMasking m = SpecularMasking(int(in[i].z));  // = LP_SPECULAR_MASKING_*
        glm::dvec2 ref = dfgReference(std::max(double(in[i].x), 1e-4), in[i].y, m);
        EXPECT_NEAR(out[i].x, ref.x, 0.01) << "N.V " << in[i].x << " roughness " << in[i].y;
        EXPECT_NEAR(out[i].y, ref.y, 0.01) << "N.V " << in[i].x << " roughness " << in[i].y;
        worst = std::max({worst, std::abs(out[i].x - ref.x), std::abs(out[i].y - ref.y)});
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
}

// The prefiltered chain of quarry_01 (sun 86,528): no NaN/Inf; no texel of any mip brighter than the
// brightest source texel (a normalised positive kernel cannot make fireflies); the integral over
// the sphere of each mip whose lobe spans two texels or more within 5% of mip 0's (per channel).
// Skipped when the asset is absent.
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
        // Texel-centre values are a quadrature of the integral only where the level's lobe spans two
        // texels or more (alpha >= 2 x the texel's angle, pi / 2 / size); in this 32^2 chain that is
        // the last level, roughness 1 (the perceptual mapping gives each level a lobe of 1-3 texels).
        const double alpha = std::pow(double(prefilteredLevelRoughness(level, s.specularLevels)), 2.0);
        if (alpha < 2.0 * (kPi / 2.0) / size) continue;
        const glm::dvec3 e = cubeEnergy(data, size);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(e[c] / e0[c], 1.0, 0.05) << "mip " << level << " channel " << c;
    }
}

namespace {

// A 128 x 64 equirect map: radiance 1 everywhere plus a 2 x 2-texel lamp of 5000 centred on `lampDir`
// (about 1% of the sphere's solid angle per texel row near the equator; the lamp holds ~80% of the
// map's energy).
ImageF lampMap(glm::dvec3 lampDir) {
    ImageF img;
    img.width = 128;
    img.height = 64;
    img.rgba.assign(size_t(128 * 64 * 4), 1.0f);
    lampDir = glm::normalize(lampDir);
    const double u = std::atan2(lampDir.x, -lampDir.z) / (2.0 * kPi) + 0.5, v = std::acos(lampDir.y) / kPi;
    const int cx = int(std::lround(u * 128.0)), cy = int(std::lround(v * 64.0));
    for (int y = cy - 1; y <= cy; ++y)
        for (int x = cx - 1; x <= cx; ++x) {
            float* p = &img.rgba[(size_t((y + 64) % 64) * 128 + size_t((x + 128) % 128)) * 4];
            p[0] = p[1] = p[2] = 5000.0f;
        }
    return img;
}

// The two lamp tests' sphere (Ks = 1, alpha = sqrt(2 / (n + 2)) = 0.5) under lampMap in kLampDirection,
// and their 40 x 30 HDR frame: AO off, a small bake on a 128^2 cube, a 64^2 DFG LUT of 1024 samples,
// the sun's pass off (the map alone lights it).
const glm::dvec3 kLampDirection = glm::normalize(glm::dvec3(0.2, 0.45, 0.85));
constexpr float kLampSphereShininess = 6.0f;

Scene lampSphere(const char* mapFile) {
    const auto mapPath = tempPath(mapFile);
    writeExr(mapPath, lampMap(kLampDirection));
    return sphereUnderMap(mapPath, glm::vec3(0.0f), glm::vec3(1.0f), kLampSphereShininess);
}

RenderSettings lampSphereSettings() {
    RenderSettings s;
    s.width = 40;
    s.height = 30;
    s.keepHdr = true;
    s.ao.enabled = false;
    s.environment = smallBake();
    s.environment.cubeSize = 128;
    s.environment.dfgSize = 64;
    s.environment.dfgSamples = 1024;
    s.disabledPasses.insert("global_lights");
    return s;
}

// Unit direction through the centre of texel (i, j) of face f (shaders/common/ibl.glsl cubeDirection).
glm::dvec3 cubeTexelDir(int f, int i, int j, int size) {
    const double s = (i + 0.5) / size * 2.0 - 1.0, t = (j + 0.5) / size * 2.0 - 1.0;
    glm::dvec3 d;
    switch (f) {
        case 0: d = {1.0, -t, -s}; break;
        case 1: d = {-1.0, -t, s}; break;
        case 2: d = {s, 1.0, t}; break;
        case 3: d = {s, -1.0, -t}; break;
        case 4: d = {s, -t, 1.0}; break;
        default: d = {-s, -t, -1.0}; break;
    }
    return glm::normalize(d);
}

}  // namespace

// The environment cube's mips average their children by solid angle: each mip's radiance integrated
// over the sphere equals mip 0's, whether the lamp sits at a face centre (texels 5.2x a corner's
// solid angle) or near a cube corner. A plain box filter lost up to half of a face-centre lamp in
// the coarse mips that filtered importance sampling reads. Bound: 0.5% per mip and channel.
TEST(Ibl, EnvironmentCubeMipsKeepALampsEnergy) {
    for (glm::dvec3 lamp : {glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.93, 0.9, -0.95)}) {
        const auto mapPath = tempPath("lamp-mips.exr");
        writeExr(mapPath, lampMap(lamp));
        Scene scene;
        scene.environment.map = mapPath;
        EnvironmentSettings s = smallBake();
        s.cubeSize = 64;
        s.specularSize = 32;
        gl::ShaderLibrary shaders;
        EnvironmentCache cache;
        const BakedEnvironment& env = cache.get(scene, s, shaders, false);
        const glm::dvec3 e0 = cubeEnergy(readCubeLevel(env.cube, 0), 64);
        for (int level = 1; level < env.cube.levels; ++level) {
            const glm::dvec3 e = cubeEnergy(readCubeLevel(env.cube, level), 64 >> level);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(e[c] / e0[c], 1.0, 0.005) << "mip " << level << " lamp " << lamp.x << "," << lamp.y << "," << lamp.z;
        }
        std::filesystem::remove(mapPath);
    }
}

// Irradiance cube against the SH on a lamp map: the mean of E over the sphere is pi times the mean
// radiance for any map, and the SH's l = 0 band holds it exactly, so the cube's solid-angle-weighted
// mean must equal the SH's. Bound: 1% at the default sample count (512 samples read 3% high under
// bench/mitsuba's lamp; at 256 this test's cube is 2% low).
TEST(Ibl, IrradianceCubeKeepsTheEnergyOfTheSh) {
    const auto mapPath = tempPath("lamp-irr.exr");
    writeExr(mapPath, lampMap(glm::dvec3(1.0, 0.0, 0.0)));
    Scene scene;
    scene.environment.map = mapPath;
    EnvironmentSettings s = smallBake();
    s.cubeSize = 64;
    s.specularSize = 32;
    s.irradianceSize = 8;
    s.irradianceSamples = EnvironmentSettings{}.irradianceSamples;
    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    const BakedEnvironment& env = cache.get(scene, s, shaders, true);
    const glm::dvec3 cubeMean = cubeEnergy(readCubeLevel(env.irradiance, 0), 8) / (4.0 * kPi);
    const glm::dvec3 shMean = kPi * 0.282095 * glm::dvec3(env.sh[0]);  // A0 Y00 L00 = mean over n of E
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(cubeMean[c] / shMean[c], 1.0, 0.01) << "channel " << c;
    std::filesystem::remove(mapPath);
}

// The prefiltered chain of a lamp map against the exact prefilter on the CPU: every level at the
// texel nearest the lamp and at 45 degrees from it equals sum L(l) D(h) (R.l)+ dOmega / sum D (R.l)+
// dOmega over the source cube's texels (N = V = R), both at the texel's centre direction. Bound:
// 7%: filtered importance sampling at 1024 samples is within 6% of the exact integral at a texel
// (the worst: roughness 0.106 at the lamp, +5.3%, and roughness 1, -5.8%). The default sample
// count; source 128^2, chain 64^2 x 6.
TEST(Ibl, PrefilteredChainDoesNotLoseASmallLamp) {
    const glm::dvec3 lampDir(1.0, 0.0, 0.0);
    const auto mapPath = tempPath("lamp-spec.exr");
    writeExr(mapPath, lampMap(lampDir));
    Scene scene;
    scene.environment.map = mapPath;
    EnvironmentSettings s = smallBake();
    s.cubeSize = 128;
    s.specularSize = 64;
    s.specularLevels = 6;
    s.specularSamples = EnvironmentSettings{}.specularSamples;
    s.extractLights = 0;  // the chain itself must hold the lamp here
    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    const BakedEnvironment& env = cache.get(scene, s, shaders, true);
    const auto source = readCubeLevel(env.cube, 0);
    auto exact = [&](glm::dvec3 R, double roughness) {
        const double a2 = std::pow(roughness, 4.0);
        glm::dvec3 sum(0.0);
        double weight = 0.0;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < 128; ++j)
                for (int i = 0; i < 128; ++i) {
                    const glm::dvec3 L = cubeTexelDir(f, i, j, 128);
                    const double c = glm::dot(R, L);
                    if (c <= 0.0) continue;
                    const double nh2 = (1.0 + c) / 2.0, d = nh2 * (a2 - 1.0) + 1.0;
                    const double w = a2 / (kPi * d * d) * c * texelSolidAngle(i, j, 128);
                    const float* p = &source[((size_t(f) * 128 + j) * 128 + i) * 4];
                    sum += w * glm::dvec3(p[0], p[1], p[2]);
                    weight += w;
                }
        return sum / weight;
    };
    for (int level = 1; level < s.specularLevels; ++level) {
        const int size = 64 >> level;
        const double roughness = prefilteredLevelRoughness(level, s.specularLevels);
        const auto data = readCubeLevel(env.prefiltered, level);
        // Texels of face +X: the one nearest the lamp (the face centre's corner) and one 45 degrees off.
        for (glm::ivec2 t : {glm::ivec2(size / 2, size / 2), glm::ivec2(size - 1, size / 2)}) {
            const glm::dvec3 R = cubeTexelDir(0, t.x, t.y, size);
            const glm::dvec3 want = exact(R, roughness);
            const float* p = &data[((size_t(0) * size + size_t(t.y)) * size + size_t(t.x)) * 4];
            EXPECT_NEAR(p[0] / want.x, 1.0, 0.07) << "mip " << level << " (roughness " << roughness << ") texel " << t.x << "," << t.y;
        }
    }
    std::filesystem::remove(mapPath);
}

// A rough GGX sphere (Ks = 1, alpha 0.5) under a 2 x 2-texel lamp of 5000 behind the camera (issue
// #16's lamp50k case, small) against the exact split sum on the CPU: per pixel, the prefiltered
// integral sum L D(h) (R'.l)+ dOmega / sum D (R'.l)+ dOmega over the source cube's texels along
// lightpass's dominant direction R' = normalize(mix(R, N, alpha^2)), times A + B from the
// double-precision DFG. What this pins is lightpass's chain (filtered importance sampling, the
// levels, their trilinear blend and face sizes, the LUT, the lookup direction). Measured: -2.3%
// over the sphere, -4.9% over N.V >= 0.7 (where the lamp's reflection is: alpha 0.5 is read as a
// blend of the alpha 0.31 level, 8^2 here, and the alpha 1 level; at 256^2, the default, -2.0% /
// -4.2%; 8 levels instead of 6 make the faces of those levels smaller and the error -7% / -13%).
// Bound: 3% over the sphere, 6% over N.V >= 0.7. The split sum itself is 12% below the exact
// integral of the BRDF over the sphere under this light (recorded, not bounded; see
// bench/mitsuba/split_sum_budget.py for the lamp50k sphere).
TEST(Ibl, RoughSphereUnderASmallLampMatchesTheExactSplitSum) {
    const glm::dvec3 lampDir = kLampDirection;
    const float shininess = kLampSphereShininess;
    const Scene scene = lampSphere("lamp-sphere.exr");
    Renderer r(scene);
    RenderSettings s = lampSphereSettings();
    s.environment.specularSize = 128;  // level 4 (alpha 0.31) 8^2: coarser faces flatten its lobe's peak
    s.environment.specularLevels = 6;
    s.environment.specularSamples = EnvironmentSettings{}.specularSamples;
    s.environment.extractLights = 0;  // what is pinned is the chain's handling of the lamp
    r.render(s, 0.0f, false);
    ASSERT_TRUE(r.graph().isLive("ibl"));
    const ImageF hdr = r.readHdr();
    s.environment.specular = IblSpecular::Sampled;  // the lobe's shape: closer to the exact integral
    r.render(s, 0.0f, false);
    const ImageF sampledHdr = r.readHdr();

    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    const BakedEnvironment& env = cache.get(scene, s.environment, shaders, false);
    const auto source = readCubeLevel(env.cube, 0);
    const int n = 128;
    std::vector<glm::dvec3> dirs;
    std::vector<double> radiance, omega;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                dirs.push_back(cubeTexelDir(f, i, j, n));
                radiance.push_back(source[((size_t(f) * n + j) * n + i) * 4 + 1]);
                omega.push_back(texelSolidAngle(i, j, n));
            }
    const double roughness = std::sqrt(std::sqrt(2.0 / (shininess + 2.0))), alpha = roughness * roughness, a2 = alpha * alpha;
    auto ggxD = [&](double nh) {
        const double dd = nh * nh * (a2 - 1.0) + 1.0;
        return a2 / (kPi * dd * dd);
    };
    double got = 0.0, want = 0.0, exact = 0.0, gotCore = 0.0, wantCore = 0.0, sampled = 0.0;
    std::map<long, double> albedoAt;
    const std::vector<SpherePixel> sphere = spherePixels(scene, 40, 30);
    for (const SpherePixel& px : sphere) {
        const glm::dvec3 N = px.normal, V = px.view;
        const double nv = px.nv;
        const glm::dvec3 R = 2.0 * nv * N - V, Rd = glm::normalize(glm::mix(R, N, a2));
        double sum = 0.0, weight = 0.0, direct = 0.0;
        for (size_t t = 0; t < dirs.size(); ++t) {
            const double rl = glm::dot(Rd, dirs[t]);
            if (rl > 0.0) {
                const double w = ggxD(std::sqrt((1.0 + rl) / 2.0)) * rl * omega[t];
                sum += w * radiance[t];
                weight += w;
            }
            const double nl = glm::dot(N, dirs[t]);
            if (nl > 0.0) {  // the BRDF itself (F = 1, the default masking)
                const glm::dvec3 h = glm::normalize(V + dirs[t]);
                const double vis = lp::test::ggxVisibilityRef(RenderSettings{}.specularMasking, nv, nl, alpha);
                direct += radiance[t] * ggxD(glm::dot(N, h)) * vis * nl * omega[t];
            }
        }
        const double splitSum = sum / weight * memoAlbedo(albedoAt, nv, roughness);
        const double pixel = hdr.rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4 + 1];
        const double sampledPixel = sampledHdr.rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4 + 1];
        ASSERT_TRUE(std::isfinite(pixel) && std::isfinite(sampledPixel));
        got += pixel, want += splitSum, exact += direct, sampled += sampledPixel;
        if (nv >= 0.7) gotCore += pixel, wantCore += splitSum;
    }
    ASSERT_GT(sphere.size(), 100u);
    EXPECT_NEAR(got / want, 1.0, 0.03) << "whole sphere";
    EXPECT_NEAR(gotCore / wantCore, 1.0, 0.06) << "N.V >= 0.7";
    RecordProperty("lightpass_over_split_sum", std::to_string(got / want) + " / " + std::to_string(gotCore / wantCore));
    RecordProperty("split_sum_over_exact", std::to_string(want / exact));
    RecordProperty("sampled_over_exact", std::to_string(sampled / exact));
    EXPECT_LT(std::abs(sampled / exact - 1.0), 0.5 * std::abs(got / exact - 1.0)) << "sampled specular";
    std::filesystem::remove(tempPath("lamp-sphere.exr"));
}

namespace {
// The exact integral of lightpass's BRDF (GGX D of `alpha`, Smith of `masking`, F = 1) over lampMap's
// texels (directions and solid angles as engine/render/ibl_sh.cpp's), summed over the sphere's pixels
// of a 40 x 30 frame of sphereUnderMap's scene (green channel).
double exactLampSphereSum(const Scene& scene, double alpha, SpecularMasking masking) {
    const ImageF original = lampMap(kLampDirection);
    std::vector<glm::dvec3> dirs;
    std::vector<double> radiance;
    for (int y = 0; y < original.height; ++y)
        for (int x = 0; x < original.width; ++x) {
            dirs.push_back(equirectDirection((x + 0.5) / original.width, (y + 0.5) / original.height));
            const double dOmega = (2.0 * kPi / original.width) * (kPi / original.height) * std::sin((y + 0.5) / original.height * kPi);
            radiance.push_back(original.rgba[(size_t(y) * size_t(original.width) + size_t(x)) * 4 + 1] * dOmega);
        }
    const double a2 = alpha * alpha;
    double exact = 0.0;
    for (const SpherePixel& px : spherePixels(scene, 40, 30)) {
        const glm::dvec3 N = px.normal, V = px.view;
        for (size_t t = 0; t < dirs.size(); ++t) {
            const glm::dvec3 L = dirs[t];
            const double nl = glm::dot(N, L);
            if (nl <= 0.0) continue;
            const double nh = glm::dot(N, glm::normalize(V + L)), dd = nh * nh * (a2 - 1.0) + 1.0;
            exact += radiance[t] * a2 / (kPi * dd * dd) * lp::test::ggxVisibilityRef(masking, px.nv, nl, alpha) * nl;
        }
    }
    return exact;
}
}  // namespace

// Issue #16's lamp case with the lamp taken out of the map (--ibl-extract-lights, the default): the
// same sphere (Ks = 1, alpha 0.5) and 2 x 2-texel lamp of 5000 as above, against the exact integral of
// lightpass's BRDF (GGX D, the default Smith masking, F = 1) over the ORIGINAL equirectangular map's
// texels. The split sum alone is 12% low here (recorded above; -9% on the Mitsuba lamp50k sphere);
// with the lamp lit analytically and the residual (a uniform sky) through the chain, bound 2% over
// the sphere, with either specular method. The extraction itself: one light, in the lamp's direction.
// White furnace with extraction on: nothing taken out, the mean within 0.5% of the exact albedo, and
// the image bit-identical to the one with extraction off.
TEST(Ibl, RoughSphereUnderASmallLampMatchesTheExactIntegralWithTheLampExtracted) {
    const glm::dvec3 lampDir = kLampDirection;
    const float shininess = kLampSphereShininess;
    const Scene scene = lampSphere("lamp-extracted.exr");
    Renderer r(scene);
    RenderSettings s = lampSphereSettings();
    s.environment.specularSize = 64;
    ASSERT_GT(s.environment.extractLights, 0) << "extraction is on by default";
    std::vector<ImageF> images;
    for (IblSpecular specular : {IblSpecular::SplitSum, IblSpecular::Sampled}) {
        s.environment.specular = specular;
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        images.push_back(r.readHdr());
    }
    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    const BakedEnvironment& env = cache.get(scene, s.environment, shaders, true);
    ASSERT_EQ(env.lights.size(), 1u);
    EXPECT_GT(glm::dot(glm::dvec3(env.lights[0].direction), lampDir), std::cos(3.0 * kPi / 180.0));
    const double roughness = std::sqrt(std::sqrt(2.0 / (shininess + 2.0)));
    const double exact = exactLampSphereSum(scene, roughness * roughness, s.specularMasking);
    std::vector<double> got(images.size(), 0.0);
    const std::vector<SpherePixel> sphere = spherePixels(scene, 40, 30);
    for (const SpherePixel& px : sphere)
        for (size_t k = 0; k < images.size(); ++k) {
            const double pixel = images[k].rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4 + 1];
            ASSERT_TRUE(std::isfinite(pixel));
            got[k] += pixel;
        }
    ASSERT_GT(sphere.size(), 100u);
    EXPECT_NEAR(got[0] / exact, 1.0, 0.02) << "split sum + extracted lamp, whole sphere";
    EXPECT_NEAR(got[1] / exact, 1.0, 0.02) << "sampled specular + extracted lamp, whole sphere";
    RecordProperty("split_sum_with_lamp_over_exact", std::to_string(got[0] / exact));
    RecordProperty("sampled_with_lamp_over_exact", std::to_string(got[1] / exact));
    std::filesystem::remove(tempPath("lamp-extracted.exr"));

    // White furnace, extraction on: nothing is taken out, the sphere keeps its exact albedo.
    const test::WhiteFurnaceMap furnaceMap("furnace-extract");
    const auto& furnacePath = furnaceMap.path;
    const Scene furnace = sphereUnderMap(furnacePath, glm::vec3(0.0f), glm::vec3(1.0f), shininess);
    Renderer rf(furnace);
    s.environment.specular = IblSpecular::SplitSum;
    rf.render(s, 0.0f, false);
    const ImageF hdr = rf.readHdr();
    EXPECT_TRUE(cache.get(furnace, s.environment, shaders, true).lights.empty());
    double sum = 0.0, sumExact = 0.0;
    std::map<long, double> albedoAt;
    for (const SpherePixel& px : spherePixels(furnace, 40, 30)) {
        sum += hdr.rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4 + 1];
        sumExact += memoAlbedo(albedoAt, px.nv, roughness);
    }
    EXPECT_NEAR(sum / sumExact, 1.0, 0.005) << "white furnace, extraction on";
    s.environment.extractLights = 0;  // a map with no lamp renders exactly as without extraction
    rf.render(s, 0.0f, false);
    EXPECT_EQ(rf.readHdr().rgba, hdr.rgba) << "white furnace, extraction on vs off";
}

// --specular-masking reaches the extracted lights (ibl_lights.glsl) and the IBL's DFG LUT: the lamp
// sphere at alpha 1 (Ns 0), where the two models differ most, with the lamp extracted (most of the light
// on the sphere), rendered under each model. Height-correlated over separable, summed over the sphere,
// equals the ratio of the two models' exact integrals over the original map within 1%; that ratio is
// above 1.02, so a shader left on one model fails.
TEST(Ibl, SpecularMaskingReachesTheExtractedLights) {
    const auto mapPath = tempPath("lamp-masking.exr");
    writeExr(mapPath, lampMap(kLampDirection));
    const Scene scene = sphereUnderMap(mapPath, glm::vec3(0.0f), glm::vec3(1.0f), 0.0f);  // alpha 1
    Renderer r(scene);
    RenderSettings s = lampSphereSettings();
    s.environment.specularSize = 64;
    std::map<SpecularMasking, double> got, exact;
    for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated}) {
        s.specularMasking = masking;
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        const ImageF hdr = r.readHdr();
        for (const SpherePixel& px : spherePixels(scene, 40, 30)) got[masking] += hdr.rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4 + 1];
        exact[masking] = exactLampSphereSum(scene, 1.0, masking);
    }
    gl::ShaderLibrary shaders;
    EnvironmentCache cache;
    ASSERT_EQ(cache.get(scene, s.environment, shaders, true).lights.size(), 1u);
    const double want = exact[SpecularMasking::HeightCorrelated] / exact[SpecularMasking::Separable];
    const double ratio = got[SpecularMasking::HeightCorrelated] / got[SpecularMasking::Separable];
    EXPECT_GT(want, 1.02);
    EXPECT_NEAR(ratio / want, 1.0, 0.01) << "rendered " << ratio << ", exact " << want;
    RecordProperty("height_correlated_over_separable", std::to_string(ratio) + " (exact " + std::to_string(want) + ")");
    std::filesystem::remove(mapPath);
}

namespace {
// sphereUnderMap's sphere with glTF material `g` (metallic-roughness; the dielectric's F0 from its ior).
// 48 x 36, the image-based light alone (no suns' pass, no AO), a small bake; the HDR buffer kept.
RenderSettings iblOnlySettings() {
    RenderSettings s;
    s.width = 48;
    s.height = 36;
    s.keepHdr = true;
    s.ao.enabled = false;
    s.environment = lp::test::smallIblBake(512);
    s.disabledPasses.insert("global_lights");
    return s;
}

Scene gltfSphereUnderMap(const std::filesystem::path& map, const GltfBrdfMaterial& g) {
    Scene scene = sphereUnderMap(map, glm::vec3(g.baseColor), glm::vec3(float(gltfDielectricF0(g.ior))),
                                 shininessFromRoughness(float(g.roughness)));
    for (auto& mat : scene.models[0].mesh.materials) {
        mat.metallic = float(g.metallic);
        mat.roughness = float(g.roughness);
        mat.clearcoat = float(g.clearcoat);
        mat.clearcoatRoughness = float(g.clearcoatRoughness);
    }
    return scene;
}

// The directional albedo at N.V = nv (N = +Z) of a GGX specular lobe of alpha with the weight
// `fresnel(L)` in it, by a 128 x 128 rule over the GGX half vectors: f cos / pdf(L) = f N.L 4 V.H / (D N.H).
template <class Lobe>
double specularAlbedo(double nv, double alpha, Lobe lobe) {
    const double a2 = alpha * alpha;
    const glm::dvec3 V(std::sqrt(1.0 - nv * nv), 0.0, nv);
    double sum = 0.0;
    for (int i = 0; i < 128; ++i)
        for (int j = 0; j < 128; ++j) {
            const double u = (i + 0.5) / 128.0, phi = (j + 0.5) / 128.0 * 2.0 * kPi;
            const double ct = std::sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u)), st = std::sqrt(std::max(1.0 - ct * ct, 0.0));
            const glm::dvec3 H(st * std::cos(phi), st * std::sin(phi), ct);
            const double vh = glm::dot(V, H);
            const glm::dvec3 L = 2.0 * vh * H - V;
            if (vh <= 0.0 || L.z <= 0.0) continue;
            sum += lobe(V, L) * L.z * 4.0 * vh / (gltfGgxDistribution(ct, alpha) * ct);
        }
    return sum / (128.0 * 128.0);
}
// The diffuse lobe's directional albedo (green channel) by a 64 x 128 cosine-weighted midpoint rule.
double diffuseAlbedo(const GltfBrdfMaterial& m, double nv) {
    const glm::dvec3 N(0, 0, 1), V(std::sqrt(1.0 - nv * nv), 0.0, nv);
    double sum = 0.0;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 128; ++j) {  // cosine-weighted: f cos / pdf = f pi
            const double u = (i + 0.5) / 64.0, phi = (j + 0.5) / 128.0 * 2.0 * kPi;
            const glm::dvec3 L(std::sqrt(u) * std::cos(phi), std::sqrt(u) * std::sin(phi), std::sqrt(1.0 - u));
            sum += gltfBrdfLobes(m, N, V, L).diffuse.y * kPi;
        }
    return sum / (64.0 * 128.0);
}
}  // namespace

// glTF 2.0's BRDF under image-based light: a rough gold sphere (metallic 1, roughness 1, base
// (1, 0.766, 0.336)) under the small-lamp map of the tests above (the lamp extracted, the default),
// in the default frame's BRDF and masking, against the exact integral of the specification's BRDF
// (engine/render/gltf_brdf.hpp, Fresnel of the base colour at each texel's V.H) over the original
// equirectangular map's texels at each sphere pixel: the path tracer's answer at that pixel. Bound: the
// sphere's sum within 3% per channel.
TEST(Ibl, GltfRoughMetalUnderASmallLampMatchesTheSpecificationsIntegral) {
    const auto mapPath = tempPath("lamp-gltf-metal.exr");
    const ImageF original = lampMap(kLampDirection);
    writeExr(mapPath, original);
    const GltfBrdfMaterial gold{{1.0, 0.766, 0.336}, 1.0, 1.0};
    const Scene scene = gltfSphereUnderMap(mapPath, gold);
    Renderer r(scene);
    RenderSettings s = lampSphereSettings();
    s.environment.specularSize = 64;
    ASSERT_EQ(s.brdf, Brdf::Ggx);
    r.render(s, 0.0f, false);
    ASSERT_TRUE(r.graph().isLive("ibl"));
    const ImageF hdr = r.readHdr();
    std::vector<glm::dvec3> dirs;
    std::vector<double> weighted;  // radiance x solid angle
    for (int y = 0; y < original.height; ++y)
        for (int x = 0; x < original.width; ++x) {
            dirs.push_back(equirectDirection((x + 0.5) / original.width, (y + 0.5) / original.height));
            const double dOmega = (2.0 * kPi / original.width) * (kPi / original.height) * std::sin((y + 0.5) / original.height * kPi);
            weighted.push_back(original.rgba[(size_t(y) * size_t(original.width) + size_t(x)) * 4 + 1] * dOmega);
        }
    glm::dvec3 got(0.0), exact(0.0);
    const std::vector<SpherePixel> sphere = spherePixels(scene, 40, 30);
    for (const SpherePixel& px : sphere) {
        for (size_t t = 0; t < dirs.size(); ++t)
            exact += gltfBrdf(gold, px.normal, px.view, dirs[t]) * weighted[t] * std::max(glm::dot(px.normal, dirs[t]), 0.0);
        const float* p = &hdr.rgba[(size_t(px.y) * 40 + size_t(px.x)) * 4];
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(p[c]));
            got[c] += p[c];
        }
    }
    ASSERT_GT(sphere.size(), 100u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c] / exact[c], 1.0, 0.03) << "channel " << c;
    RecordProperty("rendered_over_exact", std::to_string(got.x / exact.x) + " " + std::to_string(got.y / exact.y) +
                                              " " + std::to_string(got.z / exact.z));
    std::filesystem::remove(mapPath);
}

// glTF 2.0's dielectric in a white furnace (a uniform map of radiance 1): each pixel reflects the
// directional albedo of the specification's BRDF at its N.V, the diffuse lobe's (1 - F(V.H)) base / pi
// (by a 64 x 128 cosine-weighted midpoint rule) plus the specular lobe's (by a 128 x 128 rule over the
// GGX half vectors), for base 0.8 at roughness 0.5 and base 0.5 at roughness 1 (F0 0.04). The IBL's
// diffuse (ggxDiffuseFresnelMeanWeight) and specular (split sum) under the default BRDF and masking.
// Bound: the sphere mean within 0.5%, each pixel within 2% (the 32^2 DFG LUT's bilinear error).
TEST(Ibl, WhiteFurnaceGltfDielectricReflectsTheSpecificationsAlbedo) {
    const test::WhiteFurnaceMap map("furnace-gltf");
    const auto& mapPath = map.path;
    for (const GltfBrdfMaterial& m : {GltfBrdfMaterial{glm::dvec3(0.8), 0.0, 0.5}, GltfBrdfMaterial{glm::dvec3(0.5), 0.0, 1.0}}) {
        SCOPED_TRACE("roughness " + std::to_string(m.roughness));
        const Scene scene = gltfSphereUnderMap(mapPath, m);
        Renderer r(scene);
        r.render(iblOnlySettings(), 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        const ImageF hdr = r.readHdr();
        const double alpha = m.roughness * m.roughness, a2 = alpha * alpha;
        std::map<long, double> albedoAt;
        auto albedo = [&](double nv) {  // green channel
            const long key = std::lround(nv * 1e4);
            if (auto it = albedoAt.find(key); it != albedoAt.end()) return it->second;
            const glm::dvec3 N(0, 0, 1), V(std::sqrt(1.0 - nv * nv), 0.0, nv);
            double diffuse = 0.0, specular = 0.0;
            for (int i = 0; i < 64; ++i)
                for (int j = 0; j < 128; ++j) {  // cosine-weighted: f cos / pdf = f pi
                    const double u = (i + 0.5) / 64.0, phi = (j + 0.5) / 128.0 * 2.0 * kPi;
                    const glm::dvec3 L(std::sqrt(u) * std::cos(phi), std::sqrt(u) * std::sin(phi), std::sqrt(1.0 - u));
                    diffuse += gltfBrdfLobes(m, N, V, L).diffuse.y * kPi;
                }
            for (int i = 0; i < 128; ++i)
                for (int j = 0; j < 128; ++j) {  // H from D(h) N.H: f cos / pdf(L) = f N.L 4 V.H / (D N.H)
                    const double u = (i + 0.5) / 128.0, phi = (j + 0.5) / 128.0 * 2.0 * kPi;
                    const double ct = std::sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u)), st = std::sqrt(std::max(1.0 - ct * ct, 0.0));
                    const glm::dvec3 H(st * std::cos(phi), st * std::sin(phi), ct);
                    const double vh = glm::dot(V, H);
                    const glm::dvec3 L = 2.0 * vh * H - V;
                    if (vh <= 0.0 || L.z <= 0.0) continue;
                    specular += gltfBrdfLobes(m, N, V, L).specular.y * L.z * 4.0 * vh / (gltfGgxDistribution(ct, alpha) * ct);
                }
            return albedoAt[key] = diffuse / (64.0 * 128.0) + specular / (128.0 * 128.0);
        };
        double sum = 0.0, sumExact = 0.0;
        const std::vector<SpherePixel> sphere = spherePixels(scene, 48, 36);
        for (const SpherePixel& px : sphere) {
            const double exact = albedo(px.nv);
            const float got = hdr.rgba[(size_t(px.y) * 48 + size_t(px.x)) * 4 + 1];
            EXPECT_NEAR(got, exact, 0.02 * exact) << "pixel " << px.x << "," << px.y << " N.V " << px.nv;
            sum += got;
            sumExact += exact;
        }
        ASSERT_GT(sphere.size(), 100u);
        EXPECT_NEAR(sum / sumExact, 1.0, 0.005);
        RecordProperty("mean_over_exact_roughness_" + std::to_string(m.roughness), std::to_string(sum / sumExact));
    }
}

// KHR_materials_clearcoat in a white furnace (a uniform map of radiance 1): a white dielectric (base 1,
// metallic 0, roughness 0.5) under a full coat (clearcoat 1) of roughness 0.3 and 0.8 reflects, at each
// pixel's N.V, the energy the extension's layering gives: (1 - w) A_base + w A_coat, w = 0.04 + 0.96
// (1 - N.V)^5, A_base the specification's dielectric albedo (diffuse and specular lobes integrated as in
// the test above), A_coat the coat lobe's D Vis N.L integrated (no Fresnel inside). The coat adds no
// energy: where A_base <= 1 the layering's energy is <= 1, and where the base itself reflects more than
// it receives (the specification's fresnel_mix weights the diffuse by 1 - F(V.H) but the mirror lobe by
// F near N.V: a white base reaches 1.01 at N.V 0.5, more at grazing) the coat's share lowers it. Bound:
// each pixel within 2% of that energy (the 32^2 DFG LUT's bilinear error), the sphere's mean within 0.5%,
// and no pixel above 1.005 where the energy is at most 0.98.
TEST(Ibl, WhiteFurnaceClearcoatStaysAtOrUnderOneWithTheLayeringsEnergy) {
    const test::WhiteFurnaceMap map("furnace-clearcoat");
    for (const double coatRoughness : {0.3, 0.8}) {
        SCOPED_TRACE("coat roughness " + std::to_string(coatRoughness));
        GltfBrdfMaterial m{glm::dvec3(1.0), 0.0, 0.5};
        m.clearcoat = 1.0;
        m.clearcoatRoughness = coatRoughness;
        const Scene scene = gltfSphereUnderMap(map.path, m);
        Renderer r(scene);
        r.render(iblOnlySettings(), 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        const ImageF hdr = r.readHdr();
        std::map<long, double> energyAt;
        double highestBase = 0.0;
        auto energy = [&](double nv) {
            const long key = std::lround(nv * 1e4);
            if (auto it = energyAt.find(key); it != energyAt.end()) return it->second;
            const glm::dvec3 N(0, 0, 1);
            const double base = diffuseAlbedo(m, nv) + specularAlbedo(nv, m.roughness * m.roughness, [&](glm::dvec3 V, glm::dvec3 L) {
                                    return gltfBrdfLobes(m, N, V, L).specular.y;
                                });
            const double coat = specularAlbedo(nv, coatRoughness * coatRoughness, [&](glm::dvec3 V, glm::dvec3 L) {
                return gltfClearcoatLobe(m, N, V, L);
            });
            const double w = gltfClearcoatWeight(1.0, N, glm::dvec3(std::sqrt(1.0 - nv * nv), 0.0, nv));
            const double e = (1.0 - w) * base + w * coat;
            EXPECT_LE(coat, 1.0) << "N.V " << nv << ": the coat lobe's albedo";
            if (base <= 1.0) EXPECT_LE(e, 1.0) << "N.V " << nv << ": the layering's energy over a base of " << base;
            else EXPECT_LT(e, base) << "N.V " << nv << ": the coat added energy to a base of " << base;
            highestBase = std::max(highestBase, base);
            return energyAt[key] = e;
        };
        double sum = 0.0, sumExact = 0.0, highest = 0.0;
        const std::vector<SpherePixel> sphere = spherePixels(scene, 48, 36);
        for (const SpherePixel& px : sphere) {
            const double exact = energy(px.nv);
            const float got = hdr.rgba[(size_t(px.y) * 48 + size_t(px.x)) * 4 + 1];
            EXPECT_NEAR(got, exact, 0.02 * exact) << "pixel " << px.x << "," << px.y << " N.V " << px.nv;
            if (exact <= 0.98) EXPECT_LE(got, 1.005f) << "pixel " << px.x << "," << px.y << " N.V " << px.nv;
            highest = std::max(highest, double(got));
            sum += got;
            sumExact += exact;
        }
        ASSERT_GT(sphere.size(), 100u);
        EXPECT_NEAR(sum / sumExact, 1.0, 0.005);
        RecordProperty("coat_roughness_" + std::to_string(coatRoughness) + "_mean_over_exact", std::to_string(sum / sumExact));
        RecordProperty("coat_roughness_" + std::to_string(coatRoughness) + "_highest_pixel", std::to_string(highest));
        RecordProperty("coat_roughness_" + std::to_string(coatRoughness) + "_highest_base_albedo", std::to_string(highestBase));
    }
}

// The extracted lights' shading (shaders/common/ibl_lights.glsl) on the driver: a source of radius 0
// is the point-light GGX itself; and, however the source's size widens the lobe, the light a surface
// sends out over all view directions, the integral of f(V, D) N.V dV (by reciprocity the directional
// albedo for light from D), stays the point light's: at normal incidence and at grazing (N.D 0.1),
// alpha 0.05 and 0.2, disc radius 0.05 rad (2.9 degrees). Integrated on a 401^2 grid of V around the
// mirror direction of D, +-0.6 rad. Bounds below (Karis's representative-point normalisation, which
// this replaced, was 3x too bright at grazing view).
TEST(Ibl, ExtractedLightKeepsTheLobesEnergyAtEveryAngle) {
    const std::string body = R"(
        vec3 N = vec3(0.0, 0.0, 1.0);
        float nd = x.z;
        vec3 D = vec3(sqrt(1.0 - nd * nd), 0.0, nd);
        vec3 R = vec3(-D.x, 0.0, D.z);
        vec3 T1 = normalize(cross(R, vec3(0.0, 1.0, 0.0))), T2 = vec3(0.0, 1.0, 0.0);
        vec3 V = normalize(R + x.x * T1 + x.y * T2);
        float dOmega = pow(1.0 + x.x * x.x + x.y * x.y, -1.5);
        if (dot(N, V) <= 0.0) return vec4(0.0);
        float point = environmentLightSpecular(N, V, D, 0.0, vec3(1.0), x.w).x;
        float disc = environmentLightSpecular(N, V, D, 0.05, vec3(1.0), x.w).x;
        float reference = ggxSpecular(N, V, D, vec3(1.0), x.w).x;
        return vec4(point, disc, reference, 0.0) * dot(N, V) * dOmega;
    )";
    for (float nd : {1.0f, 0.1f})
        for (float alpha : {0.05f, 0.2f}) {
            std::vector<glm::vec4> in;
            const int n = 401;
            const double range = 0.6, step = 2.0 * range / (n - 1);
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    in.push_back(glm::vec4(float(-range + i * step), float(-range + j * step), nd, alpha));
            const auto out = runGlsl({"common/ibl_lights.glsl"}, body, in);
            glm::dvec3 sum(0.0);
            for (const glm::vec4& o : out) sum += glm::dvec3(o) * (step * step);
            EXPECT_NEAR(sum.x, sum.z, 1e-6 * sum.z) << "radius 0 is the point light";
            // Normal incidence: within 1%. Grazing: the anisotropic lobe keeps a little more than the
            // point light's (measured +7% at alpha 0.05, +2% at 0.2): bound 10%.
            EXPECT_NEAR(sum.y / sum.x, 1.0, nd > 0.5f ? 0.01 : 0.10) << "N.D " << nd << " alpha " << alpha;
            RecordProperty("disc_over_point_nd" + std::to_string(nd) + "_a" + std::to_string(alpha), std::to_string(sum.y / sum.x));
        }
}

namespace {

// sampledSpecularSample (shaders/common/ibl_sampled.glsl) in double precision: sample i of n for the
// tangent-space view Ve and GGX alpha. Returns L (tangent space), the lod of a chain of maxLod, and the
// (1 - Fc), Fc weights of f cos / pdf.
struct SampledSpecularSample {
    glm::dvec3 L;
    double lod = 0.0;
    glm::dvec2 weights{0.0};
};
double radicalInverse(unsigned bits) {
    double r = 0.0, f = 0.5;
    for (; bits; bits >>= 1, f *= 0.5) r += f * (bits & 1u);
    return r;
}
double smithLambda(double c, double alpha) {
    const double c2 = std::max(c * c, 1e-12);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2) - 1.0);
}
double ggxDistribution(double nh, double alpha) {
    const double a2 = alpha * alpha, d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}
SampledSpecularSample sampledSpecularReference(int i, int n, glm::dvec3 Ve, double alpha, double maxLod,
                                               SpecularMasking masking) {
    const double span = 2.0;  // LP_SAMPLED_SUBLOBE_SPAN
    const double peak = alpha * std::sqrt(std::min(span / n, 1.0));
    const double sa = std::sqrt(std::max(alpha * alpha - peak * peak, 0.01 * alpha * alpha));
    const double u0 = (i + 0.5) / n, u1 = radicalInverse(unsigned(i));
    // Heitz 2018
    const glm::dvec3 Vh = glm::normalize(glm::dvec3(sa * Ve.x, sa * Ve.y, Ve.z));
    const double lensq = Vh.x * Vh.x + Vh.y * Vh.y;
    const glm::dvec3 T1 = lensq > 0.0 ? glm::dvec3(-Vh.y, Vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1.0, 0.0, 0.0);
    const glm::dvec3 T2 = glm::cross(Vh, T1);
    const double r = std::sqrt(u0), phi = 2.0 * kPi * u1;
    const double t1 = r * std::cos(phi), s = 0.5 * (1.0 + Vh.z);
    const double t2 = (1.0 - s) * std::sqrt(std::max(1.0 - t1 * t1, 0.0)) + s * r * std::sin(phi);
    const glm::dvec3 Nh = t1 * T1 + t2 * T2 + std::sqrt(std::max(1.0 - t1 * t1 - t2 * t2, 0.0)) * Vh;
    const glm::dvec3 H = glm::normalize(glm::dvec3(sa * Nh.x, sa * Nh.y, std::max(Nh.z, 0.0)));
    SampledSpecularSample out;
    const double vh = glm::dot(Ve, H);
    out.L = 2.0 * vh * H - Ve;
    if (out.L.z <= 0.0 || vh <= 0.0) return out;
    const double nv = std::max(Ve.z, 1e-4), lv = smithLambda(nv, sa);
    const double w = lp::test::smithShadowingGivenMaskingRef(masking, lv, smithLambda(out.L.z, sa));
    const double pdf = ggxDistribution(H.z, sa) / ((1.0 + lv) * 4.0 * nv);
    const double subAlpha = std::min(std::sqrt(span / (n * pdf) / (4.0 * kPi)), alpha);
    const double sr = std::sqrt(subAlpha);
    out.lod = maxLod * sr * (2.0 - sr);
    const double fc = std::pow(1.0 - vh, 5.0);
    out.weights = w * glm::dvec2(1.0 - fc, fc);
    return out;
}
glm::dvec3 tangentView(double nv, double azimuth) {
    const double st = std::sqrt(1.0 - nv * nv);
    return {st * std::cos(azimuth), st * std::sin(azimuth), nv};
}

}  // namespace

// The sampled specular's per-sample math (GGX VNDF direction, sub-lobe lod, f cos / pdf split by
// Fresnel) on the driver against its double-precision reference above, at N.V from 1 to 0.05,
// alpha 0.05 to 1 and 1 to 64 samples. Bounds: L within 2e-3 per component, lod within 0.01,
// weights within 0.5% + 1e-5 (float against double on the same formulas: a wrong term is off by far more).
TEST(Ibl, SampledSpecularSampleMatchesCpuReference) {
  for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated}) {
    SCOPED_TRACE(specularMaskingName(masking));
    std::vector<glm::vec4> in;
    for (float nv : {1.0f, 0.7f, 0.3f, 0.05f})
        for (float alpha : {0.05f, 0.2f, 0.5f, 1.0f})
            for (int n : {1, 4, 16, 64})
                for (int i = 0; i < n; i += std::max(n / 8, 1)) in.push_back(glm::vec4(float(i), float(n), nv, alpha));
    const std::string view = "vec3 Ve = vec3(sqrt(1.0 - x.z * x.z) * cos(0.7 * x.x), sqrt(1.0 - x.z * x.z) * sin(0.7 * x.x), x.z);"
                             "vec3 L; float lod; vec2 w;"
                             "sampledSpecularSample(int(x.x), int(x.y), Ve, x.w, 5.0, " + std::to_string(int(masking)) +
                             ", L, lod, w);";
    auto dirLod = runGlsl({"common/ibl_sampled.glsl"}, view + "return vec4(L, lod);", in);
    auto weights = runGlsl({"common/ibl_sampled.glsl"}, view + "return vec4(w, 0.0, 0.0);", in);
    int below = 0;
    for (size_t k = 0; k < in.size(); ++k) {
        const double nv = double(in[k].z), az = 0.7 * double(in[k].x);
        const SampledSpecularSample ref = sampledSpecularReference(int(in[k].x), int(in[k].y), tangentView(nv, az), in[k].w, 5.0, masking);
        const std::string at = "sample " + std::to_string(int(in[k].x)) + " of " + std::to_string(int(in[k].y)) +
                               " N.V " + std::to_string(nv) + " alpha " + std::to_string(in[k].w);
        EXPECT_NEAR(weights[k].x, ref.weights.x, 0.005 * ref.weights.x + 1e-5) << at;
        EXPECT_NEAR(weights[k].y, ref.weights.y, 0.005 * ref.weights.y + 1e-5) << at;
        if (ref.weights.x + ref.weights.y <= 0.0) {
            ++below;
            continue;
        }
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(dirLod[k][c], ref.L[c], 2e-3) << at << " L[" << c << "]";
        EXPECT_NEAR(dirLod[k].w, ref.lod, 0.01) << at;
    }
    EXPECT_LT(below, int(in.size()) / 4);  // the set reaches the grazing views' horizon, not mostly below it
  }
}

// At the extremes (N.V 0 to 1, alpha from the 0.02 roughness floor to 1, 1 and 256 samples) every
// sample is finite, its lod within the chain, and its weight f cos / pdf = G2 / G1 within [0, 1]
// (masking never adds energy): a NaN here blacks out a pixel (sanitizeHdr), as Schlick's pow of a
// negative 1 - V.H once did on a Lambertian furnace sphere.
TEST(Ibl, SampledSpecularIsFiniteAndBoundedAtTheExtremes) {
  for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated}) {
    SCOPED_TRACE(specularMaskingName(masking));
    std::vector<glm::vec4> in;
    for (float nv : {0.0f, 1e-4f, 1e-3f, 0.5f, 0.999999f, 1.0f})
        for (float alpha : {0.0004f, 0.01f, 0.3f, 1.0f})
            for (int n : {1, 2, 256})
                for (int i : {0, n / 2, n - 1}) in.push_back(glm::vec4(float(i), float(n), nv, alpha));
    const std::string view = "vec3 Ve = normalize(vec3(sqrt(1.0 - x.z * x.z), 0.0, max(x.z, 1e-4)));"
                             "vec3 L; float lod; vec2 w;"
                             "sampledSpecularSample(int(x.x), int(x.y), Ve, x.w, 5.0, " + std::to_string(int(masking)) +
                             ", L, lod, w);";
    auto dirLod = runGlsl({"common/ibl_sampled.glsl"}, view + "return vec4(L, lod);", in);
    auto weights = runGlsl({"common/ibl_sampled.glsl"}, view + "return vec4(w, 0.0, 0.0);", in);
    for (size_t k = 0; k < in.size(); ++k) {
        const std::string at = "sample " + std::to_string(int(in[k].x)) + " of " + std::to_string(int(in[k].y)) +
                               " N.V " + std::to_string(in[k].z) + " alpha " + std::to_string(in[k].w);
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(dirLod[k][c])) << at;
        ASSERT_TRUE(std::isfinite(weights[k].x) && std::isfinite(weights[k].y)) << at;
        EXPECT_GE(dirLod[k].w, 0.0f) << at;
        EXPECT_LE(dirLod[k].w, 5.0f + 1e-4f) << at;
        EXPECT_GE(weights[k].x, 0.0f) << at;
        EXPECT_GE(weights[k].y, 0.0f) << at;
        EXPECT_LE(weights[k].x + weights[k].y, 1.0f + 1e-5f) << at;
    }
  }
    // Schlick's weight where V.H rounds just above 1 (H = V), and across [0, 1].
    const std::vector<glm::vec4> vh = {glm::vec4(1.0000001f), glm::vec4(1.001f), glm::vec4(1.0f), glm::vec4(0.5f),
                                       glm::vec4(0.0f)};
    auto fc = runGlsl({"common/ibl_sampled.glsl"}, "return vec4(schlickFresnelWeight(x.x));", vh);
    for (size_t k = 0; k < vh.size(); ++k) {
        ASSERT_TRUE(std::isfinite(fc[k].x)) << "V.H " << vh[k].x;
        EXPECT_NEAR(fc[k].x, std::pow(std::max(1.0 - double(vh[k].x), 0.0), 5.0), 1e-6) << "V.H " << vh[k].x;
    }
}

// The samples' weights are f cos / pdf of GGX sampled by its visible normals: their mean over 256
// samples is the directional albedo A + B of the lobe they are drawn from (alpha narrowed by the
// sub-lobe at the peak: sampledSpecularAlpha), against the double-precision DFG integral. Bound: 1%
// (Hammersley at 256 on a smooth integrand); a wrong G or pdf term is off by tens of %.
TEST(Ibl, SampledSpecularWeightsIntegrateToTheAlbedo) {
  for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated})
    for (double nv : {1.0, 0.5, 0.15})
        for (double alpha : {0.1, 0.35, 0.7, 1.0}) {
            const int n = 256;
            std::vector<glm::vec4> in;
            for (int i = 0; i < n; ++i) in.push_back(glm::vec4(float(i), float(n), float(nv), float(alpha)));
            auto out = runGlsl({"common/ibl_sampled.glsl"},
                               "vec3 Ve = vec3(sqrt(1.0 - x.z * x.z), 0.0, x.z); vec3 L; float lod; vec2 w;"
                               "sampledSpecularSample(int(x.x), int(x.y), Ve, x.w, 5.0, " + std::to_string(int(masking)) +
                               ", L, lod, w); return vec4(w, 0.0, 0.0);",
                               in);
            glm::dvec2 mean(0.0);
            for (const glm::vec4& o : out) mean += glm::dvec2(o.x, o.y) / double(n);
            const double peak = alpha * std::sqrt(2.0 / n), sampled = std::sqrt(alpha * alpha - peak * peak);
            const glm::dvec2 ref = dfgReference(nv, std::sqrt(sampled), masking);
            EXPECT_NEAR(mean.x + mean.y, ref.x + ref.y, 0.01 * (ref.x + ref.y))
                << "N.V " << nv << " alpha " << alpha << " " << specularMaskingName(masking);
        }
}

// A smooth GGX plane (Ks = 1) seen at grazing angles under lamps 6-20 degrees above the horizon,
// against the exact split sum on the CPU: per plane pixel, the prefiltered integral (N = V = R')
// over the source cube's texels along lightpass's dominant direction R' = normalize(mix(R, N,
// alpha^2)), times A + B from a double-precision DFG integral. What differs is the prefiltered
// chain: its levels, their roughness and the roughness -> mip mapping. With steps of 0.2 in
// roughness a smooth plane blended a mirror with an r = 0.2 lobe. Bound: the mean radiance over the
// plane and over the pixels that reflect a lamp within 10%, at roughness 0.119 (n = 10000). (This
// test's 64^2 chain is too coarse for rougher planes at grazing angles: roughness 0.3 reads its
// 16^2 and 8^2 levels and comes out 19% low; bench/mitsuba/grazing_plane.py checks the default
// 256^2 chain. Smoother lobes are narrower than the test's 0.7 degree source texels.)
TEST(Ibl, SmoothPlaneAtGrazingAnglesMatchesTheExactSplitSum) {
    const auto mapPath = tempPath("lamps-low.exr");
    ImageF map;
    map.width = 256;
    map.height = 128;
    map.rgba.assign(size_t(256 * 128 * 4), 0.0f);
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 256; ++x) {
            const double up = std::cos((y + 0.5) / 128.0 * kPi);
            const float sky = up > 0.0 ? float(0.3 + 0.7 * up) : 0.15f;
            float* p = &map.rgba[(size_t(y) * 256 + size_t(x)) * 4];
            p[0] = p[1] = p[2] = sky;
            p[3] = 1.0f;
        }
    for (double elevation : {6.0, 12.0, 20.0}) {  // lamps ahead (-Z), 2 x 2 texels of 2000
        const int cy = int(std::lround((90.0 - elevation) / 180.0 * 128.0)), cx = 128;
        for (int y = cy - 1; y <= cy; ++y)
            for (int x = cx - 1; x <= cx; ++x) {
                float* p = &map.rgba[(size_t(y) * 256 + size_t(x)) * 4];
                p[0] = p[1] = p[2] = 2000.0f;
            }
    }
    writeExr(mapPath, map);

    for (float roughness : {0.119f}) {
        Scene scene;
        ModelInstance m;
        m.name = "plane";
        m.primitive = "plane";
        m.mesh = makePlane(400.0f, 1);
        for (auto& mat : m.mesh.materials) {
            mat.diffuse = glm::vec3(0.0f);
            mat.specular = glm::vec3(1.0f);
            mat.shininess = 2.0f / std::pow(roughness, 4.0f) - 2.0f;
        }
        scene.models.push_back(std::move(m));
        scene.ambient = glm::vec3(0.0f);
        scene.environment.map = mapPath;
        scene.camera.position = glm::vec3(0.0f, 0.3f, 0.0f);
        scene.camera.target = glm::vec3(0.0f, 0.3f - 10.0f * std::tan(glm::radians(6.0f)), -10.0f);
        scene.camera.fovYDegrees = 24.0f;
        scene.camera.nearPlane = 0.05f;
        scene.camera.farPlane = 300.0f;
        Renderer r(scene);
        RenderSettings s;
        s.width = 64;
        s.height = 48;
        s.keepHdr = true;
        s.environment = smallBake();
        s.environment.cubeSize = 128;
        s.environment.specularSize = 64;
        s.environment.specularLevels = 6;
        s.environment.specularSamples = EnvironmentSettings{}.specularSamples;
        s.environment.dfgSize = 64;
        s.environment.dfgSamples = 1024;
        s.environment.extractLights = 0;  // what is pinned is the chain (its levels and mapping)
        s.disabledPasses.insert("global_lights");
        r.render(s, 0.0f, false);
        ASSERT_TRUE(r.graph().isLive("ibl"));
        const ImageF hdr = r.readHdr();

        // The source the bake read: the environment cube's mip 0, with exact texel solid angles.
        gl::ShaderLibrary shaders;
        EnvironmentCache cache;
        const BakedEnvironment& env = cache.get(scene, s.environment, shaders, false);
        const auto source = readCubeLevel(env.cube, 0);
        const int n = 128;
        std::vector<glm::dvec3> dirs, radiance;
        std::vector<double> omega;
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const glm::dvec3 d = cubeTexelDir(f, i, j, n);
                    if (d.y < -0.3) continue;  // the lobes around R' (above the plane) never reach there
                    const float* p = &source[((size_t(f) * n + j) * n + i) * 4];
                    dirs.push_back(d);
                    radiance.push_back(glm::dvec3(p[0], p[1], p[2]));
                    omega.push_back(texelSolidAngle(i, j, n));
                }
        const double alpha = double(roughness) * roughness, a2 = alpha * alpha;
        std::vector<double> dfgTable(33);
        for (int k = 0; k <= 32; ++k) {
            const glm::dvec2 ab = dfgReference(std::max(k / 32.0, 1e-4), roughness);
            dfgTable[size_t(k)] = ab.x + ab.y;
        }
        const glm::dmat4 inv = glm::inverse(glm::dmat4(scene.camera.projection(64.0f / 48.0f)) * glm::dmat4(scene.camera.view()));
        double gotAll = 0.0, wantAll = 0.0, gotLamp = 0.0, wantLamp = 0.0;
        int plane = 0, lamp = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) {
                const double nx = (x + 0.5) / 64 * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / 48 * 2.0;
                glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
                const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
                if (d.y >= 0.0 || -o.y / d.y > 150.0) continue;  // sky, or too far for the plane's tessellation
                const glm::dvec3 N(0, 1, 0), V = -d;
                const double nv = V.y;
                const glm::dvec3 R = 2.0 * nv * N - V;
                const glm::dvec3 Rd = glm::normalize(glm::mix(R, N, a2));
                glm::dvec3 sum(0.0);
                double weight = 0.0;
                for (size_t t = 0; t < dirs.size(); ++t) {
                    const double c = glm::dot(Rd, dirs[t]);
                    if (c <= 0.9) continue;  // beyond 25 degrees the lobes of r <= 0.12 are below 1e-6 of their peak
                    const double nh2 = (1.0 + c) / 2.0, dd = nh2 * (a2 - 1.0) + 1.0;
                    const double w = a2 / (kPi * dd * dd) * c * omega[t];
                    sum += w * radiance[t];
                    weight += w;
                }
                const double kf = nv * 32.0;
                const int k0 = std::min(int(kf), 31);
                const double dfg = glm::mix(dfgTable[size_t(k0)], dfgTable[size_t(k0) + 1], kf - k0);
                const double want = (sum.x / weight) * dfg;
                const double got = hdr.rgba[(size_t(y) * 64 + size_t(x)) * 4];
                ASSERT_TRUE(std::isfinite(got));
                gotAll += got, wantAll += want, ++plane;
                if (want > 20.0) gotLamp += got, wantLamp += want, ++lamp;
            }
        ASSERT_GT(plane, 1000);
        ASSERT_GT(lamp, 10);
        EXPECT_NEAR(gotAll / wantAll, 1.0, 0.10) << "roughness " << roughness << ", whole plane";
        EXPECT_NEAR(gotLamp / wantLamp, 1.0, 0.10) << "roughness " << roughness << ", " << lamp << " lamp pixels";
        RecordProperty("ratio_r" + std::to_string(roughness), std::to_string(gotAll / wantAll) + " / " + std::to_string(gotLamp / wantLamp));
    }
    std::filesystem::remove(mapPath);
}

// The G-buffer's half-float shininess channel (gbufferEncodeShininess): exponents up to 2048 come
// back exactly (integers), larger ones through log2 within 0.6%, up to the roughness floor's 1.25e7;
// the roughness it gives is within 0.2% of the exponent's.
TEST(Ibl, GbufferShininessSurvivesHalfFloatStorage) {
    std::vector<glm::vec4> in;
    for (float n : {0.0f, 1.0f, 32.0f, 798.0f, 2047.0f, 2048.0f, 2049.0f, 10000.0f, 65504.0f, 1e6f, 12499998.0f})
        in.push_back(glm::vec4(n, 0, 0, 0));
    auto out = runGlsl({"common/ibl.glsl", "common/gbuffer_layout.glsl"},
                       "float stored = unpackHalf2x16(packHalf2x16(vec2(gbufferEncodeShininess(x.x), 0.0))).x;\n"
                       "float n = gbufferDecodeShininess(stored);\n"
                       "return vec4(n, roughnessFromShininess(n), roughnessFromShininess(x.x), stored);",
                       in);
    for (size_t i = 0; i < in.size(); ++i) {
        const float n = in[i].x;
        if (n <= 2048.0f) EXPECT_EQ(out[i].x, n);
        else EXPECT_NEAR(out[i].x / n, 1.0, 0.006) << n;
        EXPECT_NEAR(out[i].y / out[i].z, 1.0, 0.002) << n;
        EXPECT_LE(out[i].w, 65504.0f);
    }
}

// The disk cache (--ibl-cache) returns exactly what was baked: same SH, byte-equal cube levels.
// With a lamp in the map the extracted light round-trips too, and the extraction setting is part of the key.
TEST(Ibl, DiskCacheRoundTripsTheBake) {
    const auto mapPath = tempPath("gradient.exr");
    const auto dir = tempPath("cache");
    ImageF img;
    img.width = 64;
    img.height = 32;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) img.rgba.insert(img.rgba.end(), {x / 64.0f, y / 32.0f, 0.5f, 1.0f});
    for (int c = 0; c < 3; ++c) img.rgba[(size_t(10) * 64 + 20) * 4 + size_t(c)] = 3000.0f;  // a lamp: extracted
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
    ASSERT_EQ(a.lights.size(), 1u);
    ASSERT_EQ(b.lights.size(), 1u);
    EXPECT_EQ(a.lights[0].direction, b.lights[0].direction);
    EXPECT_EQ(a.lights[0].irradiance, b.lights[0].irradiance);
    EXPECT_EQ(a.lights[0].angularRadius, b.lights[0].angularRadius);
    for (int l = 0; l < a.cube.levels; ++l) EXPECT_EQ(readCubeLevel(a.cube, l), readCubeLevel(b.cube, l));
    for (int l = 0; l < a.prefiltered.levels; ++l)
        EXPECT_EQ(readCubeLevel(a.prefiltered, l), readCubeLevel(b.prefiltered, l));
    EXPECT_EQ(readCubeLevel(a.irradiance, 0), readCubeLevel(b.irradiance, 0));
    // Another extraction setting is another bake: a third file.
    s.extractLights = 0;
    EXPECT_TRUE(second.get(scene, s, shaders, true).lights.empty());
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 3);
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
    const SpecularMasking masking = RenderSettings{}.specularMasking, other = SpecularMasking::Separable;
    ASSERT_NE(masking, other);
    cache.dfgLut(s, masking, shaders);  // ready(.., true) also wants the LUT, which forgetBakes keeps
    EXPECT_GT(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, masking, true));
    EXPECT_FALSE(cache.ready(scene, s, other, true));  // the LUT is baked per masking
    EXPECT_TRUE(cache.ready(scene, s, other, false));  // nothing else depends on it
    cache.forgetBakes();
    EXPECT_EQ(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, masking, false));  // the cube is kept
    EXPECT_FALSE(cache.ready(scene, s, masking, true));  // the bake is not
    EXPECT_EQ(cache.get(scene, s, shaders, true).cube.id(), cube);
    EXPECT_GT(cache.lastBakeGpuMs(), 0.0);
    EXPECT_TRUE(cache.ready(scene, s, masking, true));

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
// >= -1e-6; ACES -2e-6, float rounding where Filament's curve has flattened near 0.994). ACES (Filament's) and PBR Neutral also match double references within 2e-5 and 1e-5.
TEST(Ibl, ToneMapOperatorsAreFiniteAndMonotone) {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<glm::vec4> in;
    for (float h : {0.0f, 1e-30f, 1.0f, 1e38f, inf, nan, 65504.0f}) in.push_back(glm::vec4(h));
    const size_t sweepStart = in.size();
    for (int i = 0; i <= 2000; ++i) in.push_back(glm::vec4(float(std::pow(10.0, -6.0 + 11.0 * i / 2000.0))));
    auto aces = [](double x) { return test::filamentAcesRef(glm::dvec3(x)).x; };
    auto neutral = [](double x) {  // grey input: offset, then the highlight compression
        double off = x < 0.08 ? x - 6.25 * x * x : 0.04;
        double c = x - off;
        if (c < 0.76) return c;
        double d = 0.24, np = 1.0 - d * d / (c + d - 0.76);
        return np;  // grey stays grey: the desaturation mix is the identity
    };
    for (int op = 0; op < int(allToneMapOperators().size()); ++op) {
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
            EXPECT_GE(out[i].x - out[i - 1].x, op == 1 ? -2e-6f : -1e-6f) << "op " << op << " at " << in[i].x;
        if (op == 1 || op == 2)
            for (size_t i = sweepStart; i < in.size(); ++i)
                EXPECT_NEAR(out[i].x, op == 1 ? aces(in[i].x) : neutral(in[i].x), op == 1 ? 2e-5 : 1e-5)
                    << "op " << op << " at " << in[i].x;
    }
}
