// GGX on the real driver against double-precision references, the BRDF switch, and shadow
// maps checked against the geometry (analytic shadow edges, no acne, no NaN/Inf).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "frame/renderer.hpp"
#include "engine/render/shadows.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

// ---- double-precision GGX, the same definitions as shaders/common/brdf.glsl ----------------------
constexpr double kMinAlpha = 1e-3, kMinNv = 1e-4;

double alphaFromRoughness(double r) { return std::max(std::clamp(r, 0.0, 1.0) * std::clamp(r, 0.0, 1.0), kMinAlpha); }

double ggxDRef(glm::dvec3 N, glm::dvec3 H, double alpha) {
    double a2 = std::max(alpha, kMinAlpha) * std::max(alpha, kMinAlpha);
    double nh = std::min(glm::dot(N, H), 1.0);
    if (nh <= 0.0) return 0.0;
    double sin2 = std::min(glm::dot(glm::cross(N, H), glm::cross(N, H)), 1.0);
    double d = nh * nh * a2 + sin2;
    return a2 / (M_PI * d * d);
}

// Vis = G2 / (4 N.L N.V) of `masking` (RenderSettings{}'s by default), with the shader's clamps; N.L > 0.
double ggxVisRef(double nv, double nl, double alpha, SpecularMasking masking = RenderSettings{}.specularMasking) {
    return lp::test::ggxVisibilityRef(masking, std::max(nv, kMinNv), nl, std::max(alpha, kMinAlpha));
}

double fresnelRef(double f0, double vh) {
    double f90 = std::clamp(50.0 * f0, 0.0, 1.0);
    return f0 + (f90 - f0) * std::pow(std::clamp(1.0 - vh, 0.0, 1.0), 5.0);
}

glm::dvec3 halfVector(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L) {
    glm::dvec3 h = V + L;
    return glm::dot(h, h) > 1e-12 ? glm::normalize(h) : N;
}

double ggxSpecRef(glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, double f0, double alpha,
                  SpecularMasking masking = RenderSettings{}.specularMasking) {
    double nl = glm::dot(N, L);
    if (nl <= 0.0) return 0.0;
    glm::dvec3 H = halfVector(N, V, L);
    return ggxDRef(N, H, alpha) * ggxVisRef(glm::dot(N, V), nl, alpha, masking) *
           fresnelRef(f0, std::clamp(glm::dot(V, H), 0.0, 1.0));
}

// Directions of the hard-case harness: L in the xz plane at N.L = x.x, V at N.V = x.y, azimuth x.w.
const char* kDirections = R"(
        vec3 N = vec3(0.0, 0.0, 1.0);
        float sl = sqrt(max(1.0 - x.x * x.x, 0.0)), sv = sqrt(max(1.0 - x.y * x.y, 0.0));
        vec3 L = vec3(sl, 0.0, x.x);
        vec3 V = vec3(sv * cos(x.w), sv * sin(x.w), x.y);
)";
void directions(const glm::vec4& x, glm::dvec3& V, glm::dvec3& L) {
    double sl = std::sqrt(std::max(1.0 - double(x.x) * x.x, 0.0)), sv = std::sqrt(std::max(1.0 - double(x.y) * x.y, 0.0));
    L = glm::dvec3(sl, 0, x.x);
    V = glm::dvec3(sv * std::cos(double(x.w)), sv * std::sin(double(x.w)), x.y);
}

}  // namespace

// Bound: D, Vis and the whole specular radiance D Vis F N.L agree with double precision to 2e-4
// relative (+1e-6 absolute) at N.L, N.V in {1, 0.5, 1e-8, 0, -1e-3} and roughness in {0, 1e-4, 0.5, 1}
// (alpha clamped to 1e-3, N.V to 1e-4 on both sides); every value finite, exactly 0 for N.L <= 0.
TEST(ShaderGgx, HardCasesMatchDoubleReference) {
    std::vector<glm::vec4> in;
    const float cosines[] = {1.0f, 0.5f, 1e-8f, 0.0f, -1e-3f};
    const float roughness[] = {0.0f, 1e-4f, 0.5f, 1.0f};
    for (float nl : cosines)
        for (float nv : cosines)
            for (float r : roughness)
                for (float phi : {0.0f, 3.14159265f}) in.push_back(glm::vec4(nl, nv, r, phi));
    const std::string body = std::string(kDirections) + R"(
        float a = ggxAlphaFromRoughness(x.z);
        vec3 H = normalize(V + L);
        if (dot(V + L, V + L) <= 1e-12) H = N;
        float spec = ggxSpecular(N, V, L, vec3(0.5), a).x * max(dot(N, L), 0.0);
        return vec4(spec, ggxDistribution(N, H, a), ggxVisibility(dot(N, V), dot(N, L), a), a);)";
    auto out = runGlsl({"common/brdf.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::vec4 x = in[i];
        glm::dvec3 V, L, N(0, 0, 1);
        directions(x, V, L);
        const double alpha = alphaFromRoughness(x.z);
        const glm::dvec3 H = halfVector(N, V, L);
        const double spec = ggxSpecRef(N, V, L, 0.5, alpha) * std::max(double(x.x), 0.0);
        const double D = ggxDRef(N, H, alpha), vis = ggxVisRef(x.y, x.x, alpha);
        const std::string where = "N.L=" + std::to_string(x.x) + " N.V=" + std::to_string(x.y) + " r=" + std::to_string(x.z);
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(out[i][c])) << where;
        EXPECT_NEAR(out[i].w, alpha, 1e-7 * alpha) << where;
        EXPECT_NEAR(out[i].x, spec, 2e-4 * std::abs(spec) + 1e-6) << where;
        EXPECT_NEAR(out[i].y, D, 2e-4 * D + 1e-6) << where;
        if (x.x > 0.0f) EXPECT_NEAR(out[i].z, vis, 2e-4 * vis + 1e-6) << where;
        if (x.x <= 0.0f) EXPECT_EQ(out[i].x, 0.0f) << where;
    }
}

// Both Smith masking models (--specular-masking) on the driver against double precision: the isotropic
// visibility ggxVisibilityOf, the anisotropic smithVisibilityFromLengths (extracted lights) with
// lengths |(alpha_x v_x, alpha_y v_y, N.V)|, and smithShadowingGivenMasking (the sampled IBL's G2 / G1(V)).
// Bound: 2e-4 relative (+1e-6) at N.L, N.V in {1, 0.5, 0.1, 0.01}, alpha 0.05..1. Property: the
// separable G2 is never above the height-correlated one ((1 + a)(1 + b) >= 1 + a + b), equal at normal
// incidence, and 0.95x or less of it for alpha 1 at N.V = N.L = 0.1.
TEST(ShaderGgx, BothMaskingModelsMatchDoubleReference) {
    std::vector<glm::vec4> in;
    const float cosines[] = {1.0f, 0.5f, 0.1f, 0.01f};
    for (SpecularMasking masking : {SpecularMasking::Separable, SpecularMasking::HeightCorrelated})
        for (float nl : cosines)
            for (float nv : cosines)
                for (float a : {0.05f, 0.3f, 1.0f}) in.push_back(glm::vec4(nl, nv, a, float(int(masking))));
    const std::string body = R"(
        int m = int(x.w);
        float lv = length(vec3(0.7 * x.z * sqrt(1.0 - x.y * x.y), 0.0, x.y));
        float ll = length(vec3(0.0, 1.3 * x.z * sqrt(1.0 - x.x * x.x), x.x));
        float lambdaV = smithGgxLambda(x.y, x.z), lambdaL = smithGgxLambda(x.x, x.z);
        return vec4(ggxVisibilityOf(m, x.y, x.x, x.z), smithVisibilityFromLengths(m, x.y, x.x, lv, ll),
                    smithShadowingGivenMasking(m, lambdaV, lambdaL), 0.0);)";
    auto out = runGlsl({"common/ibl_sampled.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::vec4 x = in[i];
        const SpecularMasking m = SpecularMasking(int(x.w));  // = LP_SPECULAR_MASKING_*
        const double nl = x.x, nv = x.y, a = x.z;
        const std::string where = std::string(specularMaskingName(m)) + " N.L=" + std::to_string(nl) +
                                  " N.V=" + std::to_string(nv) + " alpha=" + std::to_string(a);
        // Isotropic, from Smith's Lambdas (independent of the shader's and the fixture's length form).
        const double lamV0 = lp::test::smithLambdaRef(nv, a), lamL0 = lp::test::smithLambdaRef(nl, a);
        const double vis = (m == SpecularMasking::HeightCorrelated ? 1.0 / (1.0 + lamV0 + lamL0)
                                                                   : 1.0 / ((1.0 + lamV0) * (1.0 + lamL0))) / (4.0 * nl * nv);
        EXPECT_NEAR(lp::test::ggxVisibilityRef(m, nv, nl, a), vis, 1e-9 * vis) << where << " (fixture)";
        // Anisotropic: Lambda from the stretched length, 1 + 2 Lambda = l / cos.
        const double lv = std::hypot(0.7 * a * std::sqrt(1.0 - nv * nv), nv);
        const double ll = std::hypot(1.3 * a * std::sqrt(1.0 - nl * nl), nl);
        const double lamV = 0.5 * (lv / nv - 1.0), lamL = 0.5 * (ll / nl - 1.0);
        const double g2 = m == SpecularMasking::HeightCorrelated ? 1.0 / (1.0 + lamV + lamL)
                                                                 : 1.0 / ((1.0 + lamV) * (1.0 + lamL));
        const double visAniso = g2 / (4.0 * nl * nv);
        const double shadowing = lp::test::smithShadowingGivenMaskingRef(m, lp::test::smithLambdaRef(nv, a),
                                                                         lp::test::smithLambdaRef(nl, a));
        EXPECT_NEAR(out[i].x, vis, 2e-4 * vis + 1e-6) << where;
        EXPECT_NEAR(out[i].y, visAniso, 2e-4 * visAniso + 1e-6) << where;
        EXPECT_NEAR(out[i].z, shadowing, 2e-4 * shadowing + 1e-6) << where;
        if (m == SpecularMasking::HeightCorrelated) {
            const double sep = out[i - in.size() / 2].x;  // the same point, separable
            EXPECT_LE(sep, out[i].x * (1.0 + 1e-5)) << where;
            if (nl == 1.0 && nv == 1.0) EXPECT_NEAR(sep, out[i].x, 1e-5 * out[i].x) << where;
            if (a == 1.0 && nv == 0.1f && nl == 0.1f) EXPECT_LT(sep, 0.95 * out[i].x) << where;
        }
    }
}

// MTL Ns -> GGX alpha = sqrt(2 / (Ns + 2)) to 1e-6 relative; Ns = 0 is the roughest (alpha 1). Past
// Blinn-Phong's 10000 the exponent keeps its alpha (a glTF roughness below 0.119: 1.25e7 is the 0.02
// floor, alpha 4e-4) down to the BRDF's alpha floor 1e-3; negative exponents read as 0.
TEST(ShaderGgx, ShininessMapsToAlpha) {
    std::vector<glm::vec4> in;
    for (float n : {0.0f, 1.0f, 10.0f, 128.0f, 1000.0f, 10000.0f, 1e5f, 1.25e7f, -5.0f, 1e9f}) in.push_back(glm::vec4(n));
    auto out = runGlsl({"common/brdf.glsl"}, "return vec4(ggxAlphaFromShininess(x.x));", in);
    for (size_t i = 0; i < in.size(); ++i) {
        double n = std::max(double(in[i].x), 0.0);
        EXPECT_NEAR(out[i].x, std::max(std::sqrt(2.0 / (n + 2.0)), 1e-3), 1e-6) << in[i].x;
    }
    EXPECT_FLOAT_EQ(out[0].x, 1.0f);
    EXPECT_NEAR(out[6].x, std::sqrt(2.0 / 100002.0), 1e-6) << "10^5: roughness 0.067, not clamped to 0.119";
}

// Energy: with F0 = 1 the directional albedo  integral of D Vis F N.L over the hemisphere  is <= 1
// (+2e-3 integration error) for every roughness and N.V; GLSL and the double estimator agree to 2e-3.
// Estimator: H drawn from D(h) (N.H) on a stratified 64x64 grid, L = reflect(-V, H), weight
// f N.L / pdf(L) with pdf(L) = D N.H / (4 V.H) using the shader's own D - so a wrongly normalised D
// shows up as an albedo off by its factor.
TEST(ShaderGgx, DirectionalAlbedoWithUnitFresnelIsAtMostOne) {
    std::vector<glm::vec4> in;
    for (float nv : {1.0f, 0.7f, 0.3f, 0.05f})
        for (float r : {0.1f, 0.3f, 0.5f, 0.8f, 1.0f}) in.push_back(glm::vec4(nv, r, 0, 0));
    const std::string body = R"(
        vec3 N = vec3(0.0, 0.0, 1.0);
        vec3 V = vec3(sqrt(1.0 - x.x * x.x), 0.0, x.x);
        float a = ggxAlphaFromRoughness(x.y);
        float sum = 0.0;
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 64; ++i) {
                float u1 = (float(i) + 0.5) / 64.0, u2 = (float(j) + 0.5) / 64.0;
                float phi = 2.0 * LP_PI * u2;
                float ct = sqrt((1.0 - u1) / (1.0 + (a * a - 1.0) * u1));
                float st = sqrt(max(1.0 - ct * ct, 0.0));
                vec3 H = vec3(st * cos(phi), st * sin(phi), ct);
                float vh = dot(V, H);
                if (vh <= 0.0) continue;
                vec3 L = 2.0 * vh * H - V;
                if (L.z <= 0.0) continue;
                float pdf = ggxDistribution(N, H, a) * ct / (4.0 * vh);
                sum += ggxSpecular(N, V, L, vec3(1.0), a).x * L.z / pdf;
            }
        return vec4(sum / 4096.0);)";
    auto out = runGlsl({"common/brdf.glsl"}, body, in);
    for (size_t k = 0; k < in.size(); ++k) {
        const double nv = in[k].x, alpha = alphaFromRoughness(in[k].y);
        glm::dvec3 N(0, 0, 1), V(std::sqrt(1.0 - nv * nv), 0, nv);
        double sum = 0.0;
        for (int j = 0; j < 64; ++j)
            for (int i = 0; i < 64; ++i) {
                double u1 = (i + 0.5) / 64.0, u2 = (j + 0.5) / 64.0, phi = 2.0 * M_PI * u2;
                double ct = std::sqrt((1.0 - u1) / (1.0 + (alpha * alpha - 1.0) * u1)), st = std::sqrt(std::max(1.0 - ct * ct, 0.0));
                glm::dvec3 H(st * std::cos(phi), st * std::sin(phi), ct);
                double vh = glm::dot(V, H);
                if (vh <= 0.0) continue;
                glm::dvec3 L = 2.0 * vh * H - V;
                if (L.z <= 0.0) continue;
                sum += ggxSpecRef(N, V, L, 1.0, alpha) * L.z / (ggxDRef(N, H, alpha) * ct / (4.0 * vh));
            }
        const double ref = sum / 4096.0;
        EXPECT_LE(out[k].x, 1.0 + 2e-3) << "N.V=" << nv << " alpha=" << alpha;
        EXPECT_LE(ref, 1.0 + 2e-3);
        EXPECT_NEAR(out[k].x, ref, 2e-3) << "N.V=" << nv << " alpha=" << alpha;
        if (alpha <= 0.01 && nv >= 0.7) EXPECT_GT(out[k].x, 0.97);  // smooth: almost no loss
        EXPECT_GT(out[k].x, 0.2);
    }
}

namespace {

double tonemapRef(double c) {
    c = std::clamp(c, 0.0, 65504.0);
    return std::pow(c / (c + 1.0), 1.2);
}

ModelInstance planeModel(float size, glm::vec3 kd, glm::vec3 ks, float shininess) {
    ModelInstance m;
    m.name = "ground";
    m.primitive = "plane";
    m.mesh = makePlane(1.0f, 4);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = ks;
        mat.shininess = shininess;
    }
    m.transform = glm::scale(glm::mat4(1.0f), glm::vec3(size));
    return m;
}

// The ground (20 m), optionally a 2 m square occluder at y = 1 above it, one directional light.
Scene shadowScene(glm::vec3 lightDir, bool occluder, glm::vec3 ks = glm::vec3(0.0f), float shininess = 1.0f) {
    Scene s;
    s.models.push_back(planeModel(20.0f, glm::vec3(0.55f, 0.42f, 0.33f), ks, shininess));
    if (occluder) {
        ModelInstance o = planeModel(1.0f, glm::vec3(0.5f), glm::vec3(0.0f), 1.0f);
        o.name = "occluder";
        o.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 2));
        s.models.push_back(std::move(o));
    }
    DirectionalLight light;
    light.direction = glm::normalize(lightDir);
    light.color = glm::vec3(1.0f, 0.9f, 0.8f);
    light.intensity = 2.0f;
    light.castsShadows = true;
    s.directionalLights.push_back(light);
    s.ambient = glm::vec3(0.01f, 0.02f, 0.03f);
    s.camera.position = glm::vec3(0.5f, 6.0f, 6.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.5f);
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 60.0f;
    return s;
}

struct Ray {
    glm::dvec3 origin, dir;
};
Ray pixelRay(const Scene& s, int w, int h, int x, int y) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
    return {p0, glm::normalize(p1 - p0)};
}
// Where the ray meets the plane y = height, if t > 0.
bool hitY(const Ray& r, double height, glm::dvec3& p) {
    if (std::abs(r.dir.y) < 1e-12) return false;
    double t = (height - r.origin.y) / r.dir.y;
    if (t <= 0.0) return false;
    p = r.origin + t * r.dir;
    return true;
}
// Signed distance (xz) from q to the boundary of the square |x|, |z| <= 1: negative inside.
double squareDistance(glm::dvec3 q) {
    glm::dvec2 d(std::abs(q.x) - 1.0, std::abs(q.z) - 1.0);
    glm::dvec2 outside = glm::max(d, glm::dvec2(0.0));
    return glm::length(outside) + std::min(std::max(d.x, d.y), 0.0);
}

// The point p of the ground (y = 0, within 9.5 m of the centre) that pixel (x, y) sees; false where
// the occluder hides it or the pixel misses the ground.
bool visibleGroundPoint(const Scene& s, int w, int h, int x, int y, glm::dvec3& p) {
    const Ray ray = pixelRay(s, w, h, x, y);
    glm::dvec3 o;
    if (hitY(ray, 1.0, o) && squareDistance(o) <= 0.0) return false;  // sees the occluder
    return hitY(ray, 0.0, p) && std::abs(p.x) <= 9.5 && std::abs(p.z) <= 9.5;
}

glm::dvec3 lambertRadiance(const Scene& s, double nl) {
    const auto& mat = s.models[0].mesh.materials[0];
    const glm::dvec3 kd = test::srgb8Stored(glm::dvec3(mat.diffuse));  // the 8-bit sRGB G-buffer
    const auto& light = s.directionalLights[0];
    return kd / M_PI * glm::dvec3(light.color) * double(light.intensity) * std::max(nl, 0.0) + glm::dvec3(s.ambient) * kd;
}

ImageF renderHdr(const Scene& s, RenderSettings settings, int w, int h) {
    settings.width = w;
    settings.height = h;
    return test::renderHdr(s, settings);
}

// Shadow on the ground where the occluder square's projection along the light says, with every
// ground pixel farther than (filter radius + 1.5) shadow texels (plus the normal offset's shift)
// from the analytic edge exactly lit (the unshadowed analytic radiance, 2e-3 relative) or exactly
// shadowed (ambient only).
void checkShadowEdge(glm::vec3 lightDir, ShadowSettings::Filter filter) {
    const int w = 96, h = 64;
    Scene s = shadowScene(lightDir, true);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = w;
    settings.height = h;
    settings.shadows.size = 512;
    settings.shadows.filter = filter;
    ImageF hdr = renderHdr(s, settings, w, h);
    FrameData frame = makeFrameData(s, settings, 0.0f);
    const ShadowFrustum fr = fitShadowFrustum(frame, s.directionalLights[0].direction);
    const glm::dvec3 toLight = -glm::normalize(glm::dvec3(s.directionalLights[0].direction));
    const double radius = filter == ShadowSettings::Filter::Off ? 1.0 : filter == ShadowSettings::Filter::Pcf3x3 ? 2.0
                          : filter == ShadowSettings::Filter::Pcf5x5 ? 3.0 : 3.6;
    const double tanTheta = std::sqrt(std::max(1.0 - toLight.y * toLight.y, 0.0)) / toLight.y;
    int lit = 0, shadowed = 0;
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::dvec3 p;
            if (!visibleGroundPoint(s, w, h, x, y, p)) continue;
            const glm::dvec3 q = p + toLight * (1.0 / toLight.y);  // up the light ray to y = 1
            const double depth = -(glm::dmat4(frame.view) * glm::dvec4(p, 1.0)).z;
            size_t c = 0;
            while (c + 1 < fr.cascades.size() && depth > fr.cascades[c].splitFar) ++c;
            const double texel = fr.cascades[c].texelWorld;
            // A texel on the ground stretches by 1 / cos(theta) along the tilt.
            const double margin = (radius + 1.5) * texel / toLight.y + settings.shadows.normalBias * texel * tanTheta;
            const double d = squareDistance(q);
            if (std::abs(d) < margin) continue;
            glm::dvec3 expected = lambertRadiance(s, d > 0.0 ? toLight.y : 0.0);
            for (int ch = 0; ch < 3; ++ch) {
                double got = hdr.rgba[(size_t(y) * w + x) * 4 + ch];
                worst = std::max(worst, std::abs(got - expected[ch]) / std::max(expected[ch], 1e-3));
            }
            (d > 0.0 ? lit : shadowed)++;
        }
    EXPECT_GT(lit, 500) << ShadowSettings::filterName(filter);
    EXPECT_GT(shadowed, 60) << ShadowSettings::filterName(filter);
    EXPECT_LT(worst, 2e-3) << "relative error, filter " << ShadowSettings::filterName(filter);
}

}  // namespace

TEST(ShadowRender, OccluderShadowMatchesGeometryLightStraightDown) {
    for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                   ShadowSettings::Filter::Poisson})
        checkShadowEdge(glm::vec3(0.0f, -1.0f, 0.0f), f);
}

TEST(ShadowRender, OccluderShadowMatchesGeometryLightAtAnAngle) {
    for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf5x5})
        checkShadowEdge(glm::vec3(0.5f, -1.0f, 0.3f), f);
}

// No acne: a plane lit at 89 degrees from its normal (1 degree above the horizon), no occluder: with
// shadows on, every ground pixel equals the render with shadows off (bound: relative 1e-3, i.e.
// no texel shadowed at all), for every filter. Ambient 0, so the grazing light is all there is.
TEST(ShadowRender, GrazingLightDoesNotAcne) {
    const double grazing = glm::radians(89.0);
    Scene s = shadowScene(glm::vec3(float(std::sin(grazing)), -float(std::cos(grazing)), 0.0f), false);
    s.ambient = glm::vec3(0.0f);
    s.directionalLights[0].intensity = 40.0f;
    const int w = 80, h = 60;
    RenderSettings off;
    off.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    off.autoExposure = false;       // and 0 EV
    off.shadows.enabled = false;
    ImageF reference = renderHdr(s, off, w, h);
    for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                   ShadowSettings::Filter::Poisson}) {
        RenderSettings on;
        on.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        on.autoExposure = false;       // and 0 EV
        on.shadows.size = 512;
        on.shadows.filter = f;
        ImageF img = renderHdr(s, on, w, h);
        int ground = 0, acne = 0;
        for (size_t i = 0; i < img.rgba.size(); i += 4) {
            if (reference.rgba[i] <= 0.0f) continue;  // background
            ++ground;
            if (img.rgba[i] < reference.rgba[i] * (1.0f - 1e-3f)) ++acne;
        }
        EXPECT_GT(ground, w * h / 3);
        EXPECT_EQ(acne, 0) << "shadowed ground pixels, filter " << ShadowSettings::filterName(f);
    }
}

// The BRDF switch: a diffuse-only plane (Ks = 0) is the same Lambertian image under both BRDFs
// (bound: 1e-6 relative), a glossy sphere is not (mean difference > 1% of its mean radiance).
TEST(ShadowRender, BrdfSwitchChangesGlossyButNotLambert) {
    const int w = 64, h = 48;
    Scene lambert = shadowScene(glm::vec3(-0.3f, -1.0f, -0.2f), false);
    RenderSettings bp, ggx;
    bp.brdf = Brdf::BlinnPhong;
    ggx.brdf = Brdf::Ggx;
    ImageF a = renderHdr(lambert, bp, w, h), b = renderHdr(lambert, ggx, w, h);
    for (size_t i = 0; i < a.rgba.size(); ++i) ASSERT_NEAR(a.rgba[i], b.rgba[i], 1e-6 * std::abs(a.rgba[i]) + 1e-7) << i;

    Scene glossy = shadowScene(glm::vec3(-0.3f, -1.0f, -0.2f), false);
    glossy.models.clear();
    ModelInstance sphere;
    sphere.name = "sphere";
    sphere.primitive = "sphere";
    sphere.mesh = makeSphere(0.5f, 48, 24);
    for (auto& mat : sphere.mesh.materials) {
        mat.diffuse = glm::vec3(0.2f);
        mat.specular = glm::vec3(0.6f);
        mat.shininess = 200.0f;
    }
    sphere.transform = glm::scale(glm::mat4(1.0f), glm::vec3(4.0f));
    glossy.models.push_back(std::move(sphere));
    a = renderHdr(glossy, bp, w, h);
    b = renderHdr(glossy, ggx, w, h);
    double diff = 0.0, mean = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4) {
        diff += std::abs(double(a.rgba[i]) - b.rgba[i]);
        mean += a.rgba[i];
    }
    EXPECT_GT(diff, 0.01 * mean);
}

// GGX end to end: a glossy plane under one light equals the double-precision GGX of its MTL values
// (alpha = sqrt(2 / (Ns + 2)), F0 = Ks), the diffuse layered under the specular as glTF's dielectric,
// kd (1 - F(V.H)) / pi (the ambient lights kd (1 - F0)), to 2e-3 relative in the HDR buffer.
TEST(ShadowRender, GgxPlaneMatchesAnalyticRadiance) {
    const int w = 96, h = 64;
    Scene s = shadowScene(glm::vec3(-0.3f, -1.0f, -0.2f), false, glm::vec3(0.5f), 40.0f);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.brdf = Brdf::Ggx;
    ImageF hdr = renderHdr(s, settings, w, h);
    const auto& mat = s.models[0].mesh.materials[0];
    // The G-buffer holds kd (1 - F0) in 8-bit sRGB.
    const double f0 = 0.5;
    const glm::dvec3 kdStored = test::srgb8Stored(glm::dvec3(mat.diffuse) * (1.0 - f0));
    const glm::dvec3 L = -glm::normalize(glm::dvec3(s.directionalLights[0].direction)), N(0, 1, 0);
    const double alpha = std::sqrt(2.0 / (40.0 + 2.0));
    int checked = 0;
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Ray ray = pixelRay(s, w, h, x, y);
            glm::dvec3 p;
            if (!hitY(ray, 0.0, p) || std::abs(p.x) > 9.5 || std::abs(p.z) > 9.5) continue;
            const glm::dvec3 V = glm::normalize(glm::dvec3(s.camera.position) - p);
            const double spec = ggxSpecRef(N, V, L, f0, alpha);
            const double diffuseWeight = (1.0 - fresnelRef(f0, glm::dot(V, halfVector(N, V, L)))) / (1.0 - f0);
            for (int c = 0; c < 3; ++c) {
                const double e = (kdStored[c] * diffuseWeight / M_PI + spec) * double(s.directionalLights[0].color[c]) *
                                     double(s.directionalLights[0].intensity) * glm::dot(N, L) +
                                 double(s.ambient[c]) * kdStored[c];
                worst = std::max(worst, std::abs(hdr.rgba[(size_t(y) * w + x) * 4 + c] - e) / std::max(e, 1e-3));
            }
            ++checked;
        }
    EXPECT_GT(checked, w * h / 4);
    EXPECT_LT(worst, 2e-3);
}

// --specular-masking reaches the suns' GGX in both render paths (deferred global_light.comp, forward+
// forward.frag): a rough (alpha 1, Ns 0), purely specular (Kd 0, Ks 1) plane under one grazing sun,
// height-correlated over separable per pixel equals the analytic ratio of the two visibilities at that
// pixel's N.V and N.L (D and F cancel). Bound: 1% (two fp16 HDR values; the ratio reaches above 1.1
// on the plane, so a masking that did not reach the shader is off by more).
TEST(ShadowRender, SpecularMaskingReachesTheSunInBothRenderPaths) {
    const int w = 64, h = 48;
    Scene s = shadowScene(glm::vec3(-0.9f, -0.25f, 0.1f), false, glm::vec3(1.0f), 0.0f);
    s.models[0].mesh.materials[0].diffuse = glm::vec3(0.0f);
    s.ambient = glm::vec3(0.0f);
    const glm::dvec3 L = -glm::normalize(glm::dvec3(s.directionalLights[0].direction)), N(0, 1, 0);
    for (RenderPath path : {RenderPath::Deferred, RenderPath::ForwardPlus}) {
        SCOPED_TRACE(renderPathName(path));
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.brdf = Brdf::Ggx;
        settings.renderPath = path;
        settings.shadows.enabled = false;
        settings.specularMasking = SpecularMasking::Separable;
        const ImageF separable = renderHdr(s, settings, w, h);
        settings.specularMasking = SpecularMasking::HeightCorrelated;
        const ImageF correlated = renderHdr(s, settings, w, h);
        int checked = 0;
        double worst = 0.0, lo = 1e9, hi = 0.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Ray ray = pixelRay(s, w, h, x, y);
                glm::dvec3 p;
                if (!hitY(ray, 0.0, p) || std::abs(p.x) > 9.5 || std::abs(p.z) > 9.5) continue;
                const double nv = glm::dot(N, glm::normalize(glm::dvec3(s.camera.position) - p)), nl = glm::dot(N, L);
                const double want = ggxVisRef(nv, nl, 1.0, SpecularMasking::HeightCorrelated) /
                                    ggxVisRef(nv, nl, 1.0, SpecularMasking::Separable);
                const size_t i = (size_t(y) * w + x) * 4;
                ASSERT_GT(separable.rgba[i], 1e-3f);
                const double got = correlated.rgba[i] / double(separable.rgba[i]);
                worst = std::max(worst, std::abs(got / want - 1.0));
                lo = std::min(lo, want), hi = std::max(hi, want);
                ++checked;
            }
        EXPECT_GT(checked, w * h / 4);
        EXPECT_LT(worst, 0.01) << "expected ratios " << lo << ".." << hi;
        EXPECT_GT(hi, 1.1);
    }
}

// The sun shadows' programs are compiled for one filter (sunShadowFilterDefine): one renderer switching
// --pcf frame to frame renders each filter exactly as a fresh renderer does, in both render paths, and
// the filters differ (the occluder's penumbra), so a program kept for the wrong filter would show.
TEST(ShadowRender, SwitchingTheFilterOnOneRendererMatchesAFreshRenderer) {
    const Scene s = shadowScene(glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f)), true);
    const int w = 64, h = 48;
    for (RenderPath path : {RenderPath::Deferred, RenderPath::ForwardPlus}) {
        SCOPED_TRACE(renderPathName(path));
        Renderer renderer(s);
        ImageF offImage;
        for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Poisson,
                       ShadowSettings::Filter::Pcf5x5, ShadowSettings::Filter::Off}) {
            RenderSettings settings;
            settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
            settings.autoExposure = false;       // and 0 EV
            settings.renderPath = path;
            settings.shadows.size = 256;
            settings.shadows.filter = f;
            const ImageF fresh = renderHdr(s, settings, w, h);
            settings.width = w;
            settings.height = h;
            const ImageF kept = test::renderHdr(renderer, settings);
            EXPECT_TRUE(test::imagesNear(kept, fresh, 0.0f, std::string("filter ") + ShadowSettings::filterName(f)));
            if (f == ShadowSettings::Filter::Off) {
                offImage = kept;
            } else {
                size_t differ = 0;
                for (size_t i = 0; i < kept.rgba.size(); ++i) differ += kept.rgba[i] != offImage.rgba[i];
                EXPECT_GT(differ, 20u) << "filter " << ShadowSettings::filterName(f) << " renders like off";
            }
        }
    }
}

// No NaN/Inf anywhere in the HDR buffer: the bundled Cornell scene (sun with shadows) under both BRDFs
// and every filter, and a 10,000 km plane (huge bounds) with shadows.
TEST(ShadowRender, HdrIsFiniteForEveryFilterAndBrdf) {
    Scene cornell = loadScene(lp::test::repoPath("scenes/cornell.json"));
    Renderer renderer(cornell);  // one renderer: its environment is converted once
    for (Brdf brdf : {Brdf::BlinnPhong, Brdf::Ggx})
        for (auto f : {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                       ShadowSettings::Filter::Poisson}) {
            RenderSettings settings;
            settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
            settings.autoExposure = false;       // and 0 EV
            settings.width = 48;
            settings.height = 36;
            settings.keepHdr = true;
            settings.brdf = brdf;
            settings.shadows.filter = f;
            settings.shadows.size = 256;
            renderer.render(settings);
            ASSERT_TRUE(renderer.graph().isLive("shadow_map_0"));
            ImageF img = renderer.readHdr();
            for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v)) << brdfName(brdf) << " " << ShadowSettings::filterName(f);
        }
    Scene huge = shadowScene(glm::vec3(-0.3f, -1.0f, -0.2f), true);
    huge.models[0].transform = glm::scale(glm::mat4(1.0f), glm::vec3(1e7f));
    huge.camera.farPlane = 1e7f;
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.shadows.size = 256;
    ImageF img = renderHdr(huge, settings, 48, 36);
    for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
}

// The shadowmap view shows light-space depth: looking straight down the light, the occluder (1 m
// nearer the light) is darker than the ground around it, and the view culls the camera's passes.
TEST(ShadowRender, ShadowMapViewShowsOccluderNearerThanGround) {
    Scene s = shadowScene(glm::vec3(0.0f, -1.0f, 0.0f), true);
    Renderer r(s);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = 64;
    settings.height = 64;
    settings.view = DebugView::ShadowMap;
    settings.shadows.cascades = 1;
    settings.shadows.size = 128;
    r.render(settings);
    for (const char* pass : {"gbuffer", "gbuffer_visibility", "gbuffer_resolve", "global_lights"})
        EXPECT_FALSE(r.graph().isLive(pass)) << pass;
    Image8 img = r.readDisplay();
    auto grey = [&](int x, int y) { return int(img.rgba[(size_t(y) * 64 + x) * 4]); };
    // The whole 20 m ground fills the single tile: its centre is the occluder, its corner ground.
    EXPECT_LT(grey(32, 32) + 5, grey(4, 4));
}

namespace {

// A concave corner: a 2 m floor (y = 0, x in [0, 2], z in [-1, 1]) and a 2 m wall (x = 0, facing +x)
// sharing the crease x = y = 0, nothing beyond the wall. The sun (travelling along `sun`) comes over
// the wall from -x, so the floor strip next to the crease lies in the wall's shadow.
// kRedWallSun: 16 degrees off the wall's plane, as on the Cornell box's red wall and floor.
// kCeilingSun: the Cornell box's ceiling and back wall (scenes/cornell.json's sun, the back wall
// turned onto the floor and the ceiling onto the wall: Cornell (x, y, z) -> (-y, -z, x) here), the
// wall 22 degrees off the light and the floor lit at 31 degrees from its normal.
const glm::vec3 kRedWallSun(0.3f, -1.0f, 0.2f);
const glm::vec3 kCeilingSun(0.45f, -1.0f, -0.25f);

Scene cornerScene(glm::vec3 sun) {
    Scene s;
    ModelInstance floor = planeModel(1.0f, glm::vec3(0.6f), glm::vec3(0.0f), 1.0f);
    floor.name = "floor";
    floor.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1, 0, 0)) * glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 2));
    s.models.push_back(std::move(floor));
    ModelInstance wall = planeModel(1.0f, glm::vec3(0.6f, 0.1f, 0.1f), glm::vec3(0.0f), 1.0f);
    wall.name = "wall";
    wall.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)) *
                     glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(0, 0, 1)) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 2));
    s.models.push_back(std::move(wall));
    DirectionalLight light;
    light.direction = glm::normalize(sun);
    light.color = glm::vec3(1.0f);
    light.intensity = 3.0f;
    light.castsShadows = true;
    s.directionalLights.push_back(light);
    s.ambient = glm::vec3(0.02f);
    s.camera.position = glm::vec3(1.4f, 0.9f, -1.3f);
    s.camera.target = glm::vec3(0.15f, 0.0f, 0.1f);
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 10.0f;
    return s;
}

}  // namespace

namespace {

// The conservative raster the last frame's shadow_map_0 used, from its notes in the graph
// ("..., hardware conservative" or "..., geometry shader conservative").
std::string conservativeRasterUsed(const Renderer& r) {
    for (const fg::PassDecision& d : r.graph().explain())
        if (d.name == "shadow_map_0")
            for (const std::string& note : d.notes) {
                if (note.find("hardware conservative") != std::string::npos) return "hardware";
                if (note.find("geometry shader conservative") != std::string::npos) return "geometry shader";
            }
    return "none";
}

// Renders cornerScene() with `raster` grown by `conservative`, at zero and default biases, and checks
// the crease: with the conservative raster (its atlas marked: shadow_caster_depth.glsl) under both
// suns with every filter; with split (unmarked) under the red-wall sun with the filter off. Returns
// the conservative raster the shadow pass used (checked the same for every render).
std::string expectNoCreaseLeak(ShadowSettings::Raster raster, ShadowSettings::ConservativeRaster conservative) {
    const int w = 128, h = 96;
    std::string used;
    const bool marked = atlasIsMarked(raster);
    std::vector<glm::vec3> suns{kRedWallSun};
    std::vector<ShadowSettings::Filter> filters{ShadowSettings::Filter::Off};
    if (marked) {
        suns.push_back(kCeilingSun);
        filters = {ShadowSettings::Filter::Off, ShadowSettings::Filter::Pcf3x3, ShadowSettings::Filter::Pcf5x5,
                   ShadowSettings::Filter::Poisson};
    }
    for (glm::vec3 sun : suns)
        for (bool zeroBias : {true, false})
            for (auto f : filters) {
                const Scene s = cornerScene(sun);
                const glm::dvec3 toLight = -glm::normalize(glm::dvec3(s.directionalLights[0].direction));
                const double ambient = double(s.ambient.x) * test::srgb8Stored(0.6);
                RenderSettings settings;
                settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
                settings.autoExposure = false;           // and 0 EV
                settings.shadows.raster = raster;
                settings.shadows.conservativeRaster = conservative;
                settings.shadows.size = 128;
                settings.shadows.cascades = 1;
                settings.shadows.filter = f;
                if (zeroBias) settings.shadows.depthBias = settings.shadows.slopeBias = settings.shadows.normalBias = 0.0f;
                settings.ao.enabled = false;  // the floor's ambient must be the constant: this is about the sun's shadow
                settings.width = w;
                settings.height = h;
                settings.keepHdr = true;
                Renderer r(s);
                r.render(settings);
                const ImageF hdr = r.readHdr();
                const std::string pass = conservativeRasterUsed(r);
                EXPECT_TRUE(used.empty() || used == pass) << used << " then " << pass;
                used = pass;
                FrameData frame = makeFrameData(s, settings, 0.0f);
                const double texel = fitShadowFrustum(frame, s.directionalLights[0].direction).cascades[0].texelWorld;
                const double radius = f == ShadowSettings::Filter::Off ? 1.0 : f == ShadowSettings::Filter::Pcf3x3 ? 2.0
                                      : f == ShadowSettings::Filter::Pcf5x5 ? 3.0 : 3.6;
                // The other edges' margins: the filter's reach (plus the normal offset's shift) in the
                // light's plane, as a height on the wall (the wall's top) and as z (its ends). A floor
                // step of length d moves its light-plane point by at least d * toLight.y.
                const double reach = (radius + 1.5) * texel;
                const double heightMargin = reach / -toLight.x;
                const double zMargin = reach * std::sqrt(1.0 + toLight.z * toLight.z / (toLight.x * toLight.x)) / toLight.y;
                int checked = 0, nearCrease = 0, leaks = 0;
                double worst = 0.0;
                std::string first;
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        Ray ray = pixelRay(s, w, h, x, y);
                        glm::dvec3 p;
                        if (!hitY(ray, 0.0, p) || p.x < 0.0 || p.x > 2.0 || std::abs(p.z) > 1.0) continue;
                        // Up the light ray to the wall's plane x = 0: the height and z where it crosses.
                        const double t = p.x / -toLight.x;
                        const double height = t * toLight.y, zWall = p.z + t * toLight.z;
                        if (height > 2.0 - heightMargin || std::abs(zWall) > 1.0 - zMargin) continue;
                        ++checked;
                        if (p.x < 2.0 * texel) ++nearCrease;
                        const double got = hdr.rgba[(size_t(y) * w + x) * 4];
                        const double err = std::abs(got - ambient) / ambient;
                        worst = std::max(worst, err);
                        if (err > 2e-3 && leaks++ == 0) {
                            char where[256];
                            std::snprintf(where, sizeof where, "first at pixel (%d, %d), floor x = %.4f m (%.2f texels from the crease): %.4g, ambient %.4g",
                                          x, y, p.x, p.x / texel, got, ambient);
                            first = where;
                        }
                    }
                const std::string what = std::string(sun == kRedWallSun ? "red-wall sun" : "ceiling sun") + ", " +
                                         (zeroBias ? "biases 0" : "default biases") + ", filter " +
                                         ShadowSettings::filterName(f) + ", raster " + ShadowSettings::rasterName(raster) +
                                         ", " + pass + " conservative raster";
                EXPECT_GT(checked, 300) << what;
                EXPECT_GT(nearCrease, 10) << what;
                EXPECT_EQ(leaks, 0) << "lit pixels in the wall's shadow, " << what << " (worst relative " << worst << "), "
                                    << first;
            }
    return used;
}

}  // namespace

// No light leaks along a closed concave crease (issues #16, #37): every floor pixel whose point the
// wall hides from the sun, up to the crease itself, is ambient only (2e-3 relative), with every bias 0
// and with the defaults, under both suns. Only the shadow's other edges (the wall's top and ends) keep
// a margin of the filter's reach plus 1.5 texels; the crease gets none. Coarse 128-texel maps make
// the old leaks a few pixels wide here: texels past the wall's silhouette that held no caster (every
// filter), and, with a filter on, taps past the crease on the grown edges of the floor and the wall,
// where the floor's plane runs on in front of the wall (a dotted line on the Cornell box's ceiling
// crease under the default 3x3 PCF), and with the filter off, a lookup within a few hundredths of a
// texel of the crease whose own texel lies past it. Every filter under both suns with the
// conservative raster; with split (only the faces away from the light grown), the filter off under
// the red-wall sun: its plainly drawn faces are not marked (atlasIsMarked), so its filters still let
// light onto the crease. Each with the conservative raster auto picks on this GPU (printed).
TEST(ShadowRender, ConcaveCornerDoesNotLeakAlongTheCrease) {
    for (auto raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split}) {
        const std::string used = expectNoCreaseLeak(raster, ShadowSettings::ConservativeRaster::Auto);
        std::printf("%s raster, --shadow-conservative auto: %s conservative raster\n", ShadowSettings::rasterName(raster),
                    used.c_str());
        EXPECT_NE(used, "none");
    }
}

// The same crease with each conservative raster forced: the geometry shader runs on every GPU; the
// hardware one (GL_NV_conservative_raster) where the GPU has it, and is skipped with the reason
// elsewhere (llvmpipe).
TEST(ShadowRender, ConcaveCornerDoesNotLeakWithTheGeometryShaderRaster) {
    for (auto raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split})
        EXPECT_EQ(expectNoCreaseLeak(raster, ShadowSettings::ConservativeRaster::GeometryShader), "geometry shader");
}

TEST(ShadowRender, ConcaveCornerDoesNotLeakWithTheHardwareConservativeRaster) {
    const ConservativeRasterSupport support = queryConservativeRasterSupport();
    if (!support.hardware) GTEST_SKIP() << "no hardware conservative raster on this GPU: " << support.reason;
    for (auto raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split})
        EXPECT_EQ(expectNoCreaseLeak(raster, ShadowSettings::ConservativeRaster::Hardware), "hardware");
}

// --shadow-redraw-budget: the camera jumps, the near cascades' new squares wait for the budget and
// keep serving from their previous squares (drawn for the old camera, far from the new view), so
// most of their slices' pixels lie outside them. Each ground pixel must then be shaded from the
// first cascade, from its depth split on, whose square (previous or new) holds it: exactly lit or
// exactly shadowed by the analytic occluder (as checkShadowEdge), the margin from that cascade's
// texel. Once the camera stays, the squares catch up within the budget, and the image equals the
// one drawn without a budget.
TEST(ShadowRedrawBudget, LaggingCascadesMissesShadeFromTheNextCascadeAndConverge) {
    const int w = 96, h = 64;
    Scene s = shadowScene(glm::vec3(-0.3f, -1.0f, -0.2f), true);
    RenderSettings settings;
    settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
    settings.autoExposure = false;       // and 0 EV
    settings.width = w;
    settings.height = h;
    settings.keepHdr = true;
    settings.shadows.size = 256;
    settings.shadows.cascades = 4;
    settings.shadows.filter = ShadowSettings::Filter::Pcf3x3;
    settings.shadows.raster = ShadowSettings::Raster::Plain;
    settings.shadows.scroll = false;  // a moved square lags too (no scroll to take it)
    settings.shadows.redrawBudget = 1;
    Camera seen = s.camera;  // close over the occluder: its shadow in the near cascades' slices
    seen.position = glm::vec3(0.6f, 1.9f, 1.9f);
    seen.target = glm::vec3(0.0f, 0.0f, 0.3f);
    s.camera.position = glm::vec3(-8.0f, 3.0f, -8.5f);  // first: over the ground's far corner
    s.camera.target = glm::vec3(-8.5f, 0.0f, -4.5f);
    Renderer r(s);
    r.render(settings);
    const ShadowFrustum before = fitShadowFrustum(makeFrameData(s, settings, 0.0f), s.directionalLights[0].direction);
    s.camera = seen;  // then: the occluder in view
    r.resetShadowCacheStats();
    r.render(settings);
    const ImageF hdr = r.readHdr();
    const FrameData frame = makeFrameData(s, settings, 0.0f);
    const ShadowFrustum wanted = fitShadowFrustum(frame, s.directionalLights[0].direction);
    // What the lighting is given: the last cascade drawn whole, every other whose tile held another
    // square still on that square.
    ShadowFrustum served = wanted;
    size_t lagging = 0;
    for (size_t c = 0; c + 1 < served.cascades.size(); ++c)
        for (const ShadowCascade& old : before.cascades)
            if (old.tile == wanted.cascades[c].tile && old.worldToClip != wanted.cascades[c].worldToClip) {
                served.cascades[c].worldToClip = old.worldToClip;
                served.cascades[c].texelWorld = old.texelWorld;
                ++lagging;
            }
    ASSERT_GE(lagging, 1u) << "the jump moved no square";
    EXPECT_EQ(r.shadowCacheStats().lagging, lagging);
    EXPECT_EQ(r.shadowCacheStats().mostBudgetUnitsInAFrame, 1u);

    const glm::dvec3 toLight = -glm::normalize(glm::dvec3(s.directionalLights[0].direction));
    const double tanTheta = std::sqrt(std::max(1.0 - toLight.y * toLight.y, 0.0)) / toLight.y;
    int lit = 0, shadowed = 0, fellThrough = 0, fellThroughShadowed = 0;
    double worst = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::dvec3 p;
            if (!visibleGroundPoint(s, w, h, x, y, p)) continue;
            const double depth = -(glm::dmat4(frame.view) * glm::dvec4(p, 1.0)).z;
            size_t split = 0;
            while (split + 1 < served.cascades.size() && depth > served.cascades[split].splitFar) ++split;
            // The shader's choice: from the split on, the first square holding the point (well inside:
            // the filter's texels and the normal offset stay in it).
            size_t c = split;
            for (; c < served.cascades.size(); ++c) {
                const glm::dvec4 q = glm::dmat4(served.cascades[c].worldToClip) * glm::dvec4(p, 1.0);
                const double inset = 2.0 * 4.0 / double(settings.shadows.size);
                if (std::abs(q.x) < 1.0 - inset && std::abs(q.y) < 1.0 - inset) break;
                const bool onTheEdge = std::abs(q.x) < 1.0 + inset && std::abs(q.y) < 1.0 + inset;
                if (onTheEdge) c = served.cascades.size();  // the edge's texels: either choice, not checked
            }
            if (c >= served.cascades.size()) continue;
            const double texel = served.cascades[c].texelWorld;
            const double margin = (2.0 + 1.5) * texel / toLight.y + settings.shadows.normalBias * texel * tanTheta;
            const double d = squareDistance(p + toLight * (1.0 / toLight.y));
            if (std::abs(d) < margin) continue;
            const glm::dvec3 expected = lambertRadiance(s, d > 0.0 ? toLight.y : 0.0);
            for (int ch = 0; ch < 3; ++ch) {
                const double got = hdr.rgba[(size_t(y) * w + x) * 4 + ch];
                worst = std::max(worst, std::abs(got - expected[ch]) / std::max(expected[ch], 1e-3));
            }
            (d > 0.0 ? lit : shadowed)++;
            if (c != split) {
                ++fellThrough;
                fellThroughShadowed += d > 0.0 ? 0 : 1;
            }
        }
    std::printf("redraw budget: %zu of %zu cascades lagging; %d lit and %d shadowed ground pixels checked, %d (%d shadowed) "
                "outside their split's square and shaded from a later cascade; worst relative error %.2e\n",
                lagging, served.cascades.size(), lit, shadowed, fellThrough, fellThroughShadowed, worst);
    EXPECT_GT(lit, 500);
    EXPECT_GT(shadowed, 30);
    EXPECT_GT(fellThrough, 200) << "the lagging squares still held most pixels: the fallback was not exercised";
    EXPECT_GT(fellThroughShadowed, 10) << "no shadowed pixel was served by a later cascade";
    EXPECT_LT(worst, 2e-3);

    // The camera stays: at one quarter a frame, each lagging square is done in 4 frames.
    for (size_t i = 0; i < 4 * lagging; ++i) r.render(settings);
    EXPECT_EQ(r.shadowCacheStats().completed, lagging);
    r.render(settings);
    const ImageF converged = r.readHdr();
    RenderSettings unbudgeted = settings;
    unbudgeted.shadows.redrawBudget = 0;
    Renderer fresh(s);
    fresh.render(unbudgeted);
    const ImageF reference = fresh.readHdr();
    ASSERT_EQ(converged.rgba.size(), reference.rgba.size());
    size_t differing = 0;
    for (size_t i = 0; i < converged.rgba.size(); ++i) differing += converged.rgba[i] != reference.rgba[i] ? 1 : 0;
    EXPECT_EQ(differing, 0u) << "the converged image differs from the unbudgeted one in " << differing << " values";
}

namespace {
// A depth as the conservative raster marks it (shaders/common/shadow_caster_depth.glsl's
// shadowDepthMarked): its lowest bit 0 where a face towards the light covers the texel's centre, else
// 1, the float rounded up to have it.
float markedDepth(float depth, bool frontAtCentre) {
    uint32_t bits;
    std::memcpy(&bits, &depth, sizeof bits);
    if ((bits & 1u) != (frontAtCentre ? 0u : 1u)) ++bits;
    std::memcpy(&depth, &bits, sizeof bits);
    return depth;
}
bool frontAtCentre(float depth) {
    uint32_t bits;
    std::memcpy(&bits, &depth, sizeof bits);
    return (bits & 1u) == 0u;
}

// shaders/common/shadow.glsl's shadowFilter in double precision: every texel compare with its texel
// clamped into the tile, weights, and the silent texels (no caster; in a `marked` atlas, one without a
// face towards the light at its centre that does not occlude) left out and the others' weights
// renormalised, as documented there. The per-pixel Poisson rotation's noise is computed in float, as
// the shader does (pixel coordinates below 8 keep it within a few float ulps of the shader's).
double cpuShadowFilter(const std::vector<float>& atlas, int width, int mode, glm::dvec2 pos, glm::ivec2 tileMin,
                       glm::ivec2 tileMax, double z, glm::dvec2 grad, double bias, bool marked, glm::vec2 pixel) {
    const double kSilent = -1.0;
    auto compare = [&](glm::ivec2 t) {
        const glm::ivec2 tc = glm::clamp(t, tileMin, tileMax);
        const float stored = atlas[size_t(tc.y) * size_t(width) + size_t(tc.x)];
        if (stored >= 1.0f) return kSilent;
        const double expected = z + glm::dot(grad, glm::dvec2(tc) + 0.5 - pos) - bias;
        if (expected > double(stored)) return 0.0;
        return marked && !frontAtCentre(stored) ? kSilent : 1.0;
    };
    double sum = 0.0, weights = 0.0;
    auto add = [&](double w, double c) {
        if (c == kSilent) return;
        sum += w * c;
        weights += w;
    };
    // The filter off: the own texel, or where it is silent the bilinear 2x2 around the lookup.
    auto single = [&] {
        const double own = compare(glm::ivec2(glm::floor(pos)));
        if (own != kSilent) return own;
        const glm::dvec2 p = pos - 0.5;
        const glm::ivec2 t(glm::floor(p));
        const glm::dvec2 f = p - glm::floor(p);
        sum = weights = 0.0;
        for (int q = 0; q < 4; ++q) {
            const glm::ivec2 o(q & 1, q >> 1);
            add((o.x ? f.x : 1.0 - f.x) * (o.y ? f.y : 1.0 - f.y), compare(t + o));
        }
        return weights > 0.0 ? sum / weights : 1.0;
    };
    if (mode == int(ShadowSettings::Filter::Off)) return single();
    if (mode == int(ShadowSettings::Filter::Poisson)) {
        static const double disc[16][2] = {
            {-0.94201624, -0.39906216}, {0.94558609, -0.76890725}, {-0.094184101, -0.92938870},
            {0.34495938, 0.29387760},   {-0.91588581, 0.45771432}, {-0.81544232, -0.87912464},
            {-0.38277543, 0.27676845},  {0.97484398, 0.75648379},  {0.44323325, -0.97511554},
            {0.53742981, -0.47373420},  {-0.26496911, -0.41893023}, {0.79197514, 0.19090188},
            {-0.24188840, 0.99706507},  {-0.81409955, 0.91437590}, {0.19984126, 0.78641367},
            {0.14383161, -0.14100790}};
        const float inner = pixel.x * 0.06711056f + pixel.y * 0.00583715f;
        const float noise = 52.9829189f * (inner - std::floor(inner));
        const double angle = 6.28318531 * double(noise - std::floor(noise));
        const double c = std::cos(angle), s = std::sin(angle);
        for (const auto& d : disc) {
            const glm::dvec2 p = pos - 0.5 + glm::dvec2(c * d[0] - s * d[1], s * d[0] + c * d[1]) * 2.0;
            const glm::ivec2 t(glm::floor(p));
            const glm::dvec2 f = p - glm::floor(p);
            for (int q = 0; q < 4; ++q) {
                const glm::ivec2 o(q & 1, q >> 1);
                add((o.x ? f.x : 1.0 - f.x) * (o.y ? f.y : 1.0 - f.y), compare(t + o));
            }
        }
    } else {
        const int r = mode == int(ShadowSettings::Filter::Pcf5x5) ? 2 : 1;
        const glm::dvec2 p = pos - 0.5;
        const glm::dvec2 f = p - glm::floor(p);
        for (int j = -r; j <= r + 1; ++j)
            for (int i = -r; i <= r + 1; ++i) {
                const double wx = i == -r ? 1.0 - f.x : (i == r + 1 ? f.x : 1.0);
                const double wy = j == -r ? 1.0 - f.y : (j == r + 1 ? f.y : 1.0);
                add(wx * wy, compare(glm::ivec2(glm::floor(p)) + glm::ivec2(i, j)));
            }
    }
    return weights > 0.0 ? sum / weights : single();
}
}  // namespace

// The shadow filter (read four texels at a time with textureGather inside the tile, one by one at its
// edge) against the double-precision reference above, for every filter, in a marked atlas and not:
// receivers all over a tile of an atlas of random depths (a fifth of its texels with no caster, a
// third of the others without a face towards the light at their centre), the tile's edges and
// corners included, sloped receivers. Depths sit on a 1/64 grid (the mark moves them by one ulp) and
// receivers between its steps, so no compare lies within float rounding of its threshold.
TEST(ShadowFilter, GatheredTapsMatchTheCpuReferenceForEveryFilter) {
    const int width = 64, height = 48;
    const glm::ivec2 tileMin(16, 8), tileMax(47, 39);  // a 32x32 tile away from the atlas's edges
    std::vector<float> atlas(size_t(width) * height);
    uint32_t state = 12345u;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return double(state >> 8) / double(1u << 24);
    };
    for (float& d : atlas) {
        d = next() < 0.2 ? 1.0f : float(std::floor(next() * 60.0) / 64.0 + 1.0 / 128.0);
        if (d < 1.0f) d = markedDepth(d, next() >= 1.0 / 3.0);
    }
    gl::Texture map = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, width, height, 1, "test.shadowAtlas");
    glTextureSubImage2D(map.id(), 0, 0, 0, width, height, GL_DEPTH_COMPONENT, GL_FLOAT, atlas.data());
    glBindTextureUnit(9, map.id());

    std::vector<glm::vec4> inputs;
    for (int k = 0; k < 1500; ++k) {
        // Positions over the tile and a texel past it (taps clamp at its edge), a third of them
        // within 3 texels of an edge or a corner.
        glm::dvec2 pos(tileMin.x + next() * 32.0, tileMin.y + next() * 32.0);
        if (k % 3 == 0) pos.x = next() < 0.5 ? tileMin.x + next() * 3.0 : tileMax.x + 1.0 - next() * 3.0;
        if (k % 6 == 0) pos.y = next() < 0.5 ? tileMin.y + next() * 3.0 : tileMax.y + 1.0 - next() * 3.0;
        const double z = std::floor(next() * 62.0) / 64.0;  // a step below the depths around it
        inputs.emplace_back(float(pos.x), float(pos.y), float(z), float(k));
    }
    const std::string globals = "layout(binding = 9) uniform sampler2D uMap;\n";
    for (bool marked : {false, true})
        for (int mode = 0; mode < 4; ++mode) {
            // grad up to 1/1024 per texel: 5 texels of reach move the receiver 0.005, under the depths'
            // 1/128 spacing from it; bias 0.001.
            const std::string body = "vec2 grad = vec2(sin(x.w * 1.7), cos(x.w * 2.3)) / 1024.0;\n"
                                     "return vec4(shadowFilter(uMap, " + std::to_string(mode) +
                                     ", x.xy, ivec2(16, 8), ivec2(47, 39), x.z, grad, 0.001, " + (marked ? "true" : "false") +
                                     ", vec2(mod(x.w, 7.0), mod(x.w, 5.0))));";
            const auto out = runGlsl({"common/shadow.glsl"}, body, inputs, globals);
            double worst = 0.0;
            int partial = 0, changedByMarks = 0;
            for (size_t i = 0; i < inputs.size(); ++i) {
                const glm::vec4 x = inputs[i];
                const glm::dvec2 grad(std::sin(double(x.w) * 1.7), std::cos(double(x.w) * 2.3));
                const glm::vec2 pixel(std::fmod(x.w, 7.0f), std::fmod(x.w, 5.0f));
                const double ref = cpuShadowFilter(atlas, width, mode, glm::dvec2(x.x, x.y), tileMin, tileMax, x.z,
                                                   grad / 1024.0, 0.001, marked, pixel);
                worst = std::max(worst, std::abs(double(out[i].x) - ref));
                partial += ref > 0.01 && ref < 0.99;
                const double without = cpuShadowFilter(atlas, width, mode, glm::dvec2(x.x, x.y), tileMin, tileMax, x.z,
                                                       grad / 1024.0, 0.001, false, pixel);
                changedByMarks += std::abs(ref - without) > 1e-3;
            }
            const std::string what = std::string("filter ") + ShadowSettings::filterName(ShadowSettings::Filter(mode)) +
                                     (marked ? ", marked atlas" : "");
            // Poisson's taps turn with the per-pixel noise, whose float rounding (a fused multiply-add or
            // not) moves them by ~1e-5 texels: its bound allows that, not a wrong texel or weight (~0.05).
            EXPECT_LT(worst, mode == int(ShadowSettings::Filter::Poisson) ? 5e-4 : 2e-5) << what;
            if (mode != 0) EXPECT_GT(partial, 300) << what << ": too few receivers in penumbra";
            if (marked) EXPECT_GT(changedByMarks, mode == 0 ? 20 : 100) << what << ": too few receivers see a marked texel";
        }
    glBindTextureUnit(9, 0);
}
