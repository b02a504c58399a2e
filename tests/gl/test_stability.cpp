// Stability suite on the real driver (llvmpipe in CI, NVIDIA on a GPU machine): the GLSL of
// shaders/common/ over adversarial inputs against double-precision C++ references, and full frames
// built to break the renderer (a light at the camera and one on a surface, a 1e5 sun with IBL on,
// degenerate meshes, a light parallel to the surface) scanned for NaN/Inf. Every test states the
// bound it proves. Cases already covered elsewhere are listed in the README's "Stability suite".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include <unistd.h>

#include "engine/io/image_io.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/render/local_lights.hpp"
#include "frame/renderer.hpp"
#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/primitives.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/tonemap_reference.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

constexpr double kPi = 3.14159265358979323846;
const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

std::filesystem::path tempPath(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("lp_stability_gl_" + std::to_string(getpid()) + "_" + name);
}

// ---- double references of shaders/common/tonemap.glsl ----
glm::dvec3 sanitizeRef(glm::dvec3 c) { return test::sanitizeHdrRef(c); }
glm::dvec3 pbrNeutralRef(glm::dvec3 c) {
    c = sanitizeRef(c);
    const double start = 0.8 - 0.04, desat = 0.15;
    const double x = std::min(c.x, std::min(c.y, c.z));
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    const double peak = std::max(c.x, std::max(c.y, c.z));
    if (peak < start) return glm::clamp(c, 0.0, 1.0);
    const double d = 1.0 - start;
    const double newPeak = 1.0 - d * d / (peak + d - start);
    c *= newPeak / peak;
    const double g = 1.0 - 1.0 / (desat * (peak - newPeak) + 1.0);
    return glm::clamp(c * (1.0 - g) + glm::dvec3(newPeak) * g, 0.0, 1.0);
}
glm::dvec3 agxRef(glm::dvec3 c) {
    c = sanitizeRef(c);
    const glm::dmat3 inset(0.842479062253094, 0.0423282422610123, 0.0423756549057051, 0.0784335999999992,
                           0.878468636469772, 0.0784336, 0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const glm::dmat3 outset(1.19687900512017, -0.0528968517574562, -0.0529716355144438, -0.0980208811401368,
                            1.15190312990417, -0.0980434501171241, -0.0990297440797205, -0.0989611768448433,
                            1.15107367264116);
    const double minEv = -12.47393, maxEv = 4.026069;
    glm::dvec3 v = inset * c;
    for (int i = 0; i < 3; ++i) {
        double e = std::clamp(std::log2(std::max(v[i], 1e-10)), minEv, maxEv);
        e = (e - minEv) / (maxEv - minEv);
        const double e2 = e * e, e4 = e2 * e2;
        v[i] = 15.5 * e4 * e2 - 40.14 * e4 * e + 31.96 * e4 - 6.868 * e2 * e + 0.4298 * e2 + 0.1191 * e - 0.00232;
    }
    v = outset * v;
    for (int i = 0; i < 3; ++i) v[i] = std::pow(std::clamp(v[i], 0.0, 1.0), 2.2);
    return v;
}

Scene baseScene() {
    Scene s;
    s.ambient = glm::vec3(0.0f);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 50.0f;
    s.camera.fovYDegrees = 60.0f;
    return s;
}

ModelInstance coloured(const std::string& name, MeshData mesh, glm::mat4 transform, glm::vec3 kd, glm::vec3 ks, float n) {
    ModelInstance m;
    m.name = name;
    m.mesh = std::move(mesh);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = ks;
        mat.shininess = n;
    }
    m.transform = transform;
    return m;
}

// Counts non-finite and negative values; `largest` gets the largest finite one.
struct Scan {
    size_t bad = 0;
    float largest = 0.0f;
};
Scan scan(const ImageF& hdr) {
    Scan s;
    for (float v : hdr.rgba) {
        if (!std::isfinite(v) || v < 0.0f) ++s.bad;
        else s.largest = std::max(s.largest, v);
    }
    return s;
}

// World point on the plane y = 0 seen through pixel (x, y) (row 0 = top), or false.
bool floorPoint(const Scene& s, int w, int h, int x, int y, glm::dvec3& hit) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    glm::dvec3 p0 = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - p0;
    if (std::abs(d.y) < 1e-12) return false;
    double t = -p0.y / d.y;
    if (t <= 0.0 || t >= 1.0) return false;
    hit = p0 + t * d;
    return true;
}

EnvironmentSettings smallBake() { return lp::test::smallIblBake(64); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Tone map operators (ACES, PBR Neutral, AgX; lightpass's own is in ShaderToneMap) at 0, 1e-30, a
// denormal, 1, 65504, 1e38, +Inf, NaN, -1, -Inf, mixed channels and a log grid 1e-6 .. 1e5. Bound:
// |GLSL - double| <= 2e-5 (both ACES, PBR Neutral) and <= 2e-4 (AgX: float log2 and a degree-6 polynomial
// with coefficients up to 40), every output finite and in [0, 1].
TEST(StabilityToneMap, EveryOperatorMatchesDoubleReferenceAtHardInputs) {
    std::vector<glm::vec4> in;
    const float hard[] = {0.0f, 1e-30f, 1e-40f, 1.0f, 65504.0f, 1e38f, kInf, kNaN, -1.0f, -kInf, 0.76f, 0.08f};
    for (float h : hard) in.push_back(glm::vec4(h, h, h, 0.0f));
    in.push_back(glm::vec4(kInf, 0.0f, kNaN, 0.0f));
    in.push_back(glm::vec4(1e38f, 1e-30f, 2.0f, 0.0f));
    in.push_back(glm::vec4(-kInf, 0.5f, 100.0f, 0.0f));
    in.push_back(glm::vec4(0.9f, 0.05f, 0.01f, 0.0f));
    for (int i = 0; i <= 400; ++i) {
        const float g = float(std::pow(10.0, -6.0 + 11.0 * i / 400.0));
        in.push_back(glm::vec4(g, g * 0.5f, g * 0.1f, 0.0f));
    }
    const struct {
        const char* name;
        const char* call;
        glm::dvec3 (*ref)(glm::dvec3);
        double bound;
    } ops[] = {{"aces", "tonemapAces", test::filamentAcesRef, 2e-5},
               {"aces-legacy", "tonemapAcesLegacy", test::acesLegacyRef, 2e-5},
               {"pbr-neutral", "tonemapPbrNeutral", pbrNeutralRef, 2e-5},
               {"agx", "tonemapAgx", agxRef, 2e-4}};
    for (const auto& op : ops) {
        auto out = runGlsl({"common/tonemap.glsl"}, std::string("return vec4(") + op.call + "(x.xyz), 0.0);", in);
        double worst = 0.0;
        for (size_t i = 0; i < in.size(); ++i) {
            const glm::dvec3 ref = op.ref(glm::dvec3(in[i]));
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(out[i][c])) << op.name << " input " << in[i][c];
                EXPECT_GE(out[i][c], 0.0f) << op.name;
                EXPECT_LE(out[i][c], 1.0f) << op.name;
                worst = std::max(worst, std::abs(out[i][c] - ref[c]));
                EXPECT_NEAR(out[i][c], ref[c], op.bound)
                    << op.name << " input (" << in[i].x << ", " << in[i].y << ", " << in[i].z << ") channel " << c
                    << ": bound " << op.bound;
            }
        }
        std::printf("  %-12s worst |GLSL - double| = %.3g (bound %.0e)\n", op.name, worst, op.bound);
    }
}

// Exposure then tone map at the extremes of --exposure: exp2(+-20) times 1e38, Inf and NaN stays
// finite (the operators sanitise after exposure). Bound: every output finite and in [0, 1].
TEST(StabilityToneMap, ExposureOverflowStaysFinite) {
    std::vector<glm::vec4> in;
    for (float ev : {-20.0f, 0.0f, 20.0f})
        for (float v : {0.0f, 1e-30f, 1e38f, kInf, kNaN, 3e38f}) in.push_back(glm::vec4(v, v, v, ev));
    for (int op = 0; op < int(allToneMapOperators().size()); ++op) {
        auto out = runGlsl({"common/tonemap.glsl"},
                           "return vec4(applyToneMap(applyExposure(x.xyz, x.w), " + std::to_string(op) + "), 0.0);", in);
        for (size_t i = 0; i < in.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(out[i][c])) << "operator " << op << " input " << in[i].x << " EV " << in[i].w;
                EXPECT_GE(out[i][c], 0.0f);
                EXPECT_LE(out[i][c], 1.0f);
            }
    }
}

// ---------------------------------------------------------------------------------------------
// Attenuation over adversarial distances (0, -0, a denormal, 1e-30, around the clamp and the range
// to 1 float ulp, 1e30, +Inf) for ranges 1e-3, 1, 1e4, 1e6 and 1e30 (the near clamp is capped at 1 cm,
// so a long-range light is not dimmed to nothing). Bound: relative 1e-5 of the double
// reference (plus 1e-7 of its d = 0 value, for the cancellation in the window's 1 - x^4 near the
// range); exactly 0 at and beyond the range; finite everywhere.
TEST(StabilityAttenuation, ExtremeDistancesAndRangesMatchDoubleReference) {
    std::vector<glm::vec4> in;
    for (float range : {1e-3f, 1.0f, 1e4f, 1e6f, 1e30f}) {
        const float ds[] = {0.0f,         -0.0f,        1e-40f,       1e-30f,         0.005f * range,
                            0.01f * range, 0.02f * range, 0.5f * range, std::nextafter(range, 0.0f), range,
                            std::nextafter(range, kInf), 2.0f * range, 1e30f, kInf};
        for (float d : ds) in.push_back(glm::vec4(d, range, 0.0f, 0.0f));
    }
    auto out = runGlsl({"common/attenuation.glsl"}, "return vec4(lpPointAttenuation(x.x, x.y));", in);
    for (size_t i = 0; i < in.size(); ++i) {
        const double d = std::abs(double(in[i].x)), r = in[i].y;
        const double x = d / r, w = std::pow(std::clamp(1.0 - x * x * x * x, 0.0, 1.0), 2.0);
        const double dMin = std::min(0.01 * r, 0.01);
        const double ref = (std::isinf(d) ? 0.0 : 1.0 / std::max(d * d, dMin * dMin)) * w;
        const double atZero = 1.0 / (dMin * dMin);
        ASSERT_TRUE(std::isfinite(out[i].x)) << "d " << in[i].x << " range " << r;
        EXPECT_NEAR(out[i].x, ref, 1e-5 * ref + 1e-7 * atZero) << "d " << in[i].x << " range " << r << ": bound 1e-5 relative";
        if (d >= r) EXPECT_EQ(out[i].x, 0.0f) << "d " << in[i].x << " range " << r;
    }
}

// ---------------------------------------------------------------------------------------------
// Receiver-plane shadow bias at grazing light: the depth gradient of a receiver whose light-space
// normal has n.z in {1, 0.5, 0.02, 0.01, 1e-3, 1e-8, 0, -0, -1e-3} (light parallel to and behind the
// surface). Bound: equals xy / max(z, 0.01) * texel/range to 1e-6 relative; finite; never larger
// than 100 texel/range (the clamp at 89.4 degrees).
TEST(StabilityShadow, ReceiverGradientAtGrazingLightIsBounded) {
    std::vector<glm::vec4> in;
    const float tor = 1e-4f;
    for (float z : {1.0f, 0.5f, 0.02f, 0.01f, 1e-3f, 1e-8f, 0.0f, -0.0f, -1e-3f})
        for (double phi : {0.0, 1.0, 2.5}) {
            const double s = std::sqrt(std::max(0.0, 1.0 - double(z) * z));
            in.push_back(glm::vec4(float(s * std::cos(phi)), float(s * std::sin(phi)), z, tor));
        }
    auto out = runGlsl({"common/shadow.glsl"}, "return vec4(shadowReceiverGradient(x.xyz, x.w), 0.0, 0.0);", in);
    for (size_t i = 0; i < in.size(); ++i)
        for (int c = 0; c < 2; ++c) {
            const double ref = double(in[i][c]) / std::max(double(in[i].z), 0.01) * tor;
            ASSERT_TRUE(std::isfinite(out[i][c])) << "n.z " << in[i].z;
            EXPECT_NEAR(out[i][c], ref, 1e-6 * std::abs(ref) + 1e-12) << "n.z " << in[i].z;
            EXPECT_LE(std::abs(out[i][c]), 100.0f * tor * 1.000001f) << "n.z " << in[i].z;
        }
}

// A directional light exactly parallel to a floor (N.L = 0) and one a hair below it, shadows on,
// every filter and both BRDFs: the floor must get exactly its ambient (no acne can appear where no
// light arrives, and the bias clamp must not produce NaN). Bound: |HDR - ambient * kd| <= 2^-10
// relative (one fp16 rounding), no NaN/Inf; kd the G-buffer's diffuse albedo: Kd under Blinn-Phong,
// Kd (1 - Ks) under GGX (the diffuse layer beneath F0 = Ks).
TEST(StabilityShadow, LightParallelToTheSurfaceAddsNothing) {
    Scene s = baseScene();
    // Kd 0.62: Kd and Kd (1 - Ks) both clear of 8-bit rounding ties.
    s.models.push_back(coloured("floor", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)),
                                glm::vec3(0.62f), glm::vec3(0.5f), 64.0f));
    s.ambient = glm::vec3(0.25f);
    s.camera.position = {0.0f, 3.0f, 4.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    for (glm::vec3 dir : {glm::vec3(1.0f, 0.0f, 0.0f), glm::normalize(glm::vec3(1.0f, 1e-3f, 0.3f))}) {
        s.directionalLights = {DirectionalLight{dir, glm::vec3(1.0f), 5.0f, true}};
        Renderer r(s);
        for (auto filter : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                            ShadowSettings::Filter::Poisson})
            for (Brdf brdf : {Brdf::BlinnPhong, Brdf::Ggx}) {
                RenderSettings rs;
                rs.width = 48;
                rs.height = 32;
                rs.keepHdr = true;
                rs.brdf = brdf;
                rs.shadows.filter = filter;
                rs.shadows.size = 256;
                r.render(rs, 0.0f, false);
                ImageF hdr = r.readHdr();
                EXPECT_EQ(scan(hdr).bad, 0u);
                const double kd = brdf == Brdf::Ggx ? 0.62 * (1.0 - 0.5) : 0.62;
                const double expected = 0.25 * test::srgb8Stored(kd);  // the 8-bit sRGB G-buffer
                int floorPixels = 0;
                for (int y = 0; y < rs.height; ++y)
                    for (int x = 0; x < rs.width; ++x) {
                        glm::dvec3 p;
                        if (!floorPoint(s, rs.width, rs.height, x, y, p) || std::abs(p.x) > 9.5 || std::abs(p.z) > 9.5)
                            continue;
                        ++floorPixels;
                        const float got = hdr.rgba[(size_t(y) * rs.width + x) * 4];
                        ASSERT_NEAR(got, expected, expected * std::ldexp(1.0, -10))
                            << "pixel " << x << "," << y << " light y " << dir.y << " filter "
                            << ShadowSettings::filterName(filter) << " brdf " << brdfName(brdf);
                    }
                EXPECT_GT(floorPixels, rs.width * rs.height / 3);
            }
    }
}

// ---------------------------------------------------------------------------------------------
// Full frame (a): a point light exactly at the camera (the camera inside its range, the range sphere
// crossing the near plane) over a Lambertian floor seen straight down, and a second, very bright
// light (1e6) lying on the floor, which adds exactly nothing to it (N.L = 0). Both G-buffer modes
// (the visibility resolve must keep the floor's points on its plane as the raster does: one ulp of
// eye z off it is 55% at 0.38 m from the light), every local-light method, both BRDFs. Bound: every
// floor pixel farther than 2 cm from the light on the floor equals kd/pi * I * att(d) * N.L of the
// camera's light to 2e-3 relative (fp16 storage, float positions); the whole buffer has no NaN/Inf
// and nothing above 65504.
TEST(StabilityRender, LightAtTheCameraAndOnTheSurface) {
    Scene s = baseScene();
    s.models.push_back(coloured("floor", makePlane(1.0f, 8), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)),
                                glm::vec3(0.55f, 0.32f, 0.21f), glm::vec3(0.0f), 16.0f));
    s.camera.position = {0.0f, 2.0f, 0.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 0.0f, -1.0f};
    PointLight atCamera;
    atCamera.position = s.camera.position;
    atCamera.intensity = 3.0f;
    atCamera.range = 10.0f;
    PointLight onFloor;
    onFloor.position = {1.2f, 0.0f, 0.0f};
    onFloor.intensity = 1e6f;
    onFloor.range = 0.4f;
    s.pointLights = {atCamera, onFloor};
    Renderer r(s);
    const glm::dvec3 kd = test::srgb8Stored(glm::dvec3(0.55, 0.32, 0.21));  // the 8-bit sRGB G-buffer, away from rounding ties
    for (GBufferMode mode : allGBufferModes())
        for (LocalLightMethod method : allLocalLightMethods())
            for (Brdf brdf : {Brdf::BlinnPhong, Brdf::Ggx}) {
                SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer, " + localLightMethodName(method) + " " + brdfName(brdf));
                RenderSettings rs;
                rs.width = 64;
                rs.height = 48;
                rs.keepHdr = true;
                rs.brdf = brdf;
                rs.localLights.method = method;
                rs.gbuffer.mode = mode;
                r.render(rs, 0.0f, false);
                ImageF hdr = r.readHdr();
                Scan sc = scan(hdr);
                EXPECT_EQ(sc.bad, 0u) << "NaN, Inf or negative texels";
                EXPECT_LE(sc.largest, 65504.0f);
                int checked = 0;
                double worst = 0.0;
                std::string worstAt;
                for (int y = 0; y < rs.height; ++y)
                    for (int x = 0; x < rs.width; ++x) {
                        glm::dvec3 p;
                        if (!floorPoint(s, rs.width, rs.height, x, y, p)) continue;
                        // The light on the floor adds N.L = 0 everywhere on it; pixels within 2 cm of it are
                        // left out (their G-buffer position's float error gives N.L ~ 1e-7 / d there).
                        if (glm::length(p - glm::dvec3(onFloor.position)) < 0.02) continue;
                        const glm::dvec3 toLight = glm::dvec3(atCamera.position) - p;
                        const double d = glm::length(toLight), nl = toLight.y / d, xr = d / atCamera.range;
                        const double att = 1.0 / (d * d) * std::pow(std::max(1.0 - xr * xr * xr * xr, 0.0), 2.0);
                        for (int c = 0; c < 3; ++c) {
                            const double e = kd[c] / kPi * atCamera.intensity * att * nl;
                            const double got = hdr.rgba[(size_t(y) * rs.width + x) * 4 + c];
                            if (std::abs(got - e) / e > worst) {
                                worst = std::abs(got - e) / e;
                                worstAt = "pixel " + std::to_string(x) + "," + std::to_string(y) + " channel " + std::to_string(c) +
                                          " got " + std::to_string(got) + " expected " + std::to_string(e);
                            }
                        }
                        ++checked;
                    }
                EXPECT_GT(checked, rs.width * rs.height / 2);
                EXPECT_LT(worst, 2e-3) << "relative error against kd/pi * I * att(d) * N.L (bound 2e-3), worst at " << worstAt;
            }
}

// Full frame (b): an HDR map holding a 1e5 sun (above the half-float maximum, like quarry_01's
// 86,528) with IBL on: a mirror-like, a rough and a Lambertian sphere on a floor, both BRDFs, SH and
// cube irradiance; then quarry_01 itself when the shared assets are present. Bound: no NaN/Inf or
// negative texel anywhere in the HDR buffer; every texel <= 65504; the sun lights the Lambertian
// sphere (some texel > 1).
TEST(StabilityRender, SunOf1e5InTheEnvironmentWithIbl) {
    const auto mapPath = tempPath("sun.exr");
    ImageF map;
    map.width = 64;
    map.height = 32;
    map.rgba.assign(size_t(64 * 32 * 4), 0.3f);
    for (int y = 9; y <= 10; ++y)
        for (int x = 40; x <= 41; ++x)
            for (int c = 0; c < 3; ++c) map.rgba[(size_t(y) * 64 + size_t(x)) * 4 + c] = 1e5f;
    for (size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    writeExr(mapPath, map);

    const std::filesystem::path quarry = std::filesystem::path(LIGHTPASS_SHARED_ASSETS) / "hdri-polyhaven-1k/quarry_01_1k.hdr";
    std::vector<std::filesystem::path> maps = {mapPath};
    if (std::filesystem::exists(quarry)) maps.push_back(quarry);
    else std::printf("  %s absent: only the synthetic 1e5 sun is rendered\n", quarry.string().c_str());

    for (const auto& path : maps) {
        Scene s = baseScene();
        s.models.push_back(coloured("floor", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)),
                                    glm::vec3(0.5f), glm::vec3(0.04f), 8.0f));
        const float shininess[] = {10000.0f, 16.0f, 0.0f};
        const glm::vec3 ks[] = {glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(0.0f)};
        for (int i = 0; i < 3; ++i)
            s.models.push_back(coloured("sphere", makeSphere(0.5f, 24, 12),
                                        glm::translate(glm::mat4(1.0f), {float(i) * 1.2f - 1.2f, 0.5f, 0.0f}),
                                        glm::vec3(0.8f), ks[i], shininess[i]));
        s.environment.map = path;
        s.environment.rotationDegrees = 30.0f;
        s.camera.position = {0.0f, 1.2f, 3.5f};
        s.camera.target = {0.0f, 0.5f, 0.0f};
        s.directionalLights = {DirectionalLight{glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f)), glm::vec3(1.0f), 3.0f, true}};
        Renderer r(s);
        for (Brdf brdf : {Brdf::BlinnPhong, Brdf::Ggx})
            for (IrradianceSource source : {IrradianceSource::SphericalHarmonics, IrradianceSource::Cubemap}) {
                SCOPED_TRACE(path.filename().string() + " " + brdfName(brdf) + (source == IrradianceSource::Cubemap ? " cube" : " sh"));
                RenderSettings rs;
                rs.width = 64;
                rs.height = 48;
                rs.keepHdr = true;
                rs.brdf = brdf;
                rs.environment = smallBake();
                rs.environment.diffuse = source;
                rs.shadows.size = 256;
                r.render(rs, 0.0f, false);
                ASSERT_TRUE(r.graph().isLive("ibl"));
                Scan sc = scan(r.readHdr());
                EXPECT_EQ(sc.bad, 0u) << "NaN, Inf or negative texels in the HDR buffer";
                EXPECT_LE(sc.largest, 65504.0f);
                EXPECT_GT(sc.largest, 1.0f);
            }
    }
    std::filesystem::remove(mapPath);
}

// Full frame (c): degenerate meshes. A mesh made in code with zero-area, collinear, NaN and Inf
// triangles beside one good triangle (nothing filters it), a code-made model of only degenerate
// faces, and an OBJ with zero-area, collinear and non-finite faces among two good ones (the loader
// drops the bad ones), over a floor with a shadow-casting sun and a point light, both BRDFs.
// Bound: no NaN/Inf or negative texel in the HDR buffer; with the code-made meshes, the floor away
// from the good triangle equals the render without them to 2^-10 relative (a NaN/Inf vertex neither
// draws nor stretches the shadow cascades).
TEST(StabilityRender, DegenerateMeshesRenderFinite) {
    const auto objPath = tempPath("degenerate.obj");
    std::ofstream(objPath) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0.5 0.5 0\nv 2 0 0\nv 0 1e39 0\n"
                              "f 1 2 3\nf 2 4 3\nf 1 1 2\nf 1 4 5\nf 1 2 6\nf 1 2 7\n";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    MeshData raw;
    const glm::vec3 positions[] = {{0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0},       // good
                                   {1, 1, 1}, {1, 1, 1}, {1, 1, 1},             // a point
                                   {0, 0, 0}, {0.3f, 0.3f, 0}, {0.6f, 0.6f, 0}, // collinear
                                   {nan, 0, 0}, {0, 1, 0}, {1, 0, 0},           // NaN
                                   {kInf, 0, 0}, {0, 1, 0}, {0, 0, -kInf}};     // Inf
    for (const auto& p : positions) {
        Vertex v;
        v.position = p;
        raw.vertices.push_back(v);
    }
    for (uint32_t i = 0; i < raw.vertices.size(); ++i) raw.indices.push_back(i);
    raw.subMeshes.push_back(SubMesh{0, uint32_t(raw.indices.size()), 0});
    raw.materials.push_back(Material{});
    computeNormals(raw);
    computeTangents(raw);
    computeBounds(raw);
    MeshData onlyDegenerate = raw;  // the point and the collinear faces alone
    onlyDegenerate.indices.assign(raw.indices.begin() + 3, raw.indices.begin() + 9);
    onlyDegenerate.subMeshes[0].indexCount = 6;

    Scene plain = baseScene();
    plain.models.push_back(coloured("floor", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(10.0f)),
                                    glm::vec3(0.5f), glm::vec3(0.2f), 32.0f));
    plain.ambient = glm::vec3(0.05f);
    plain.camera.position = {0.0f, 2.5f, 4.0f};
    plain.camera.target = {0.0f, 0.3f, 0.0f};
    plain.directionalLights = {DirectionalLight{glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f)), glm::vec3(1.0f), 3.0f, true}};
    PointLight pl;
    pl.position = {1.0f, 0.8f, 1.0f};
    pl.range = 3.0f;
    pl.intensity = 2.0f;
    plain.pointLights = {pl};
    // `broken`: the code-made degenerate meshes only (they must change nothing); `withObj`: also the
    // loaded OBJ, whose two good faces cast a real shadow (checked for finiteness only).
    Scene broken = plain;
    const glm::mat4 up = glm::translate(glm::mat4(1.0f), {0.0f, 0.3f, 0.0f});
    broken.models.push_back(coloured("raw", raw, up, glm::vec3(0.7f), glm::vec3(0.3f), 64.0f));
    broken.models.push_back(coloured("only-degenerate", onlyDegenerate, glm::translate(up, {1.0f, 0.0f, 0.0f}),
                                     glm::vec3(0.7f), glm::vec3(0.3f), 64.0f));
    Scene withObj = broken;
    withObj.models.push_back(coloured("obj", loadObj(objPath), glm::translate(up, {-1.5f, 0.0f, 0.0f}), glm::vec3(0.7f),
                                      glm::vec3(0.3f), 64.0f));
    std::filesystem::remove(objPath);

    Renderer rPlain(plain), rBroken(broken), rWithObj(withObj);
    for (Brdf brdf : {Brdf::BlinnPhong, Brdf::Ggx}) {
        SCOPED_TRACE(brdfName(brdf));
        RenderSettings rs;
        rs.width = 64;
        rs.height = 48;
        rs.keepHdr = true;
        rs.brdf = brdf;
        rs.shadows.size = 512;
        rPlain.render(rs, 0.0f, false);
        rBroken.render(rs, 0.0f, false);
        rWithObj.render(rs, 0.0f, false);
        ImageF a = rPlain.readHdr(), b = rBroken.readHdr();
        EXPECT_EQ(scan(b).bad, 0u) << "NaN, Inf or negative texels in the HDR buffer";
        EXPECT_EQ(scan(rWithObj.readHdr()).bad, 0u) << "NaN, Inf or negative texels with the loaded OBJ";
        int compared = 0;
        for (int y = 0; y < rs.height; ++y)
            for (int x = 0; x < rs.width; ++x) {
                glm::dvec3 p;
                if (!floorPoint(plain, rs.width, rs.height, x, y, p) || std::abs(p.x) > 4.5 || std::abs(p.z) > 4.5) continue;
                // under the good triangle, behind it as the camera sees it, and its shadow
                if (p.z > -2.5 && p.z < 1.5 && p.x > -1.0 && p.x < 2.5) continue;
                ++compared;
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * rs.width + x) * 4 + c;
                    EXPECT_NEAR(b.rgba[i], a.rgba[i], std::abs(a.rgba[i]) * std::ldexp(1.0, -10) + 1e-6)
                        << "pixel " << x << "," << y << " (floor at " << p.x << ", " << p.z << ")";
                }
            }
        EXPECT_GT(compared, 100);
    }
}
