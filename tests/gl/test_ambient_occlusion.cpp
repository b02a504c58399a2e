// Ambient occlusion (GTAO) on the GL driver: the slice integral and the specular occlusion against
// double-precision references, an open plane (AO 1), a 90-degree corner against the analytic
// cosine-weighted visibility, half against full size, and that only indirect light is darkened.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;
using lp::test::runGlsl;

namespace {

constexpr double kPi = 3.14159265358979323846;

// integral over [h0, h1] of cos(t - n) |sin t| dt by the midpoint rule (the slice's visible arc).
double sliceArcReference(double h0, double h1, double n) {
    const int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double t = h0 + (h1 - h0) * (i + 0.5) / steps;
        sum += std::cos(t - n) * std::abs(std::sin(t));
    }
    return sum * (h1 - h0) / steps;
}

double specularOcclusionReference(double nv, double ao, double alpha) {
    return std::clamp(std::pow(nv + ao, std::exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

ModelInstance planeModel(const std::string& name, const glm::mat4& transform, glm::vec3 kd) {
    ModelInstance m;
    m.name = name;
    m.primitive = "plane";
    m.mesh = makePlane(1.0f, 4);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = kd;
        mat.specular = glm::vec3(0.0f);
        mat.shininess = 1.0f;
    }
    m.transform = transform;
    return m;
}

// A 20 m floor at y = 0 and, with `wall`, a 20 m wall in the plane z = 0 facing +z standing on it:
// a 90-degree concave crease along the x axis.
Scene cornerScene(bool wall) {
    Scene s;
    s.models.push_back(planeModel("floor", glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)), glm::vec3(0.5f)));
    if (wall) {
        glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 10.0f, 0.0f)) *
                      glm::rotate(glm::mat4(1.0f), float(kPi / 2.0), glm::vec3(1.0f, 0.0f, 0.0f)) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(20.0f));
        s.models.push_back(planeModel("wall", t, glm::vec3(0.5f)));
    }
    s.ambient = glm::vec3(0.2f);
    s.camera.position = {0.0f, 1.2f, 2.5f};
    s.camera.target = {0.0f, 0.25f, 0.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.fovYDegrees = 60.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 50.0f;
    return s;
}

// The world ray through the centre of pixel (x, y) (row 0 = top).
void pixelRay(const Scene& s, int w, int h, int x, int y, glm::dvec3& origin, glm::dvec3& dir) {
    glm::dmat4 inv = glm::inverse(glm::dmat4(s.camera.projection(float(w) / float(h))) * glm::dmat4(s.camera.view()));
    double nx = (x + 0.5) / w * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / h * 2.0;
    glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
    origin = glm::dvec3(a) / a.w;
    dir = glm::normalize(glm::dvec3(b) / b.w - origin);
}

// Where pixel (x, y) sees the floor in front of the wall (z > 0), or false.
bool floorPoint(const Scene& s, int w, int h, int x, int y, glm::dvec3& hit) {
    glm::dvec3 o, d;
    pixelRay(s, w, h, x, y, o, d);
    if (d.y >= -1e-9) return false;
    hit = o + d * (-o.y / d.y);
    return hit.z > 0.0 && std::abs(hit.x) < 9.0;
}

// Cosine-weighted visibility at a floor point a distance d in front of an unbounded wall, counting
// only occluders nearer than r: the cosine-weighted hemisphere projects to the unit disk uniformly,
// and the directions that reach the wall within r are the segment z < -d / r of that disk.
double cornerVisibility(double d, double r) {
    const double a = std::min(d / r, 1.0);
    return 1.0 - (std::acos(a) - a * std::sqrt(1.0 - a * a)) / kPi;
}

struct AoImage {
    int w = 0, h = 0;
    std::vector<double> ao;  // row 0 = top
    double at(int x, int y) const { return ao[size_t(y) * w + x]; }
};

AoImage renderAoView(const Scene& s, int w, int h, const AoSettings& ao, GBufferMode mode = GBufferMode::Auto) {
    Renderer r(s);
    RenderSettings settings;
    settings.gbuffer.mode = mode;
    settings.width = w;
    settings.height = h;
    settings.view = DebugView::Ao;
    settings.ao = ao;
    r.render(settings);
    EXPECT_TRUE(r.graph().isLive("ao"));
    EXPECT_TRUE(r.graph().isLive("ao_denoise"));
    EXPECT_FALSE(r.graph().isLive("global_lights"));
    const Image8 img = r.readDisplay();
    AoImage out{w, h, {}};
    for (int i = 0; i < w * h; ++i) out.ao.push_back(img.rgba[size_t(i) * 4] / 255.0);
    return out;
}

AoSettings aoAt(AoResolution resolution) {
    AoSettings a;
    a.resolution = resolution;
    return a;
}

}  // namespace

// Bound: |GLSL - double| <= 2e-5 (float trigonometry). The closed form of one side's arc, the
// clamping into the normal's hemisphere, and an unoccluded slice at n = 0 giving exactly 1.
TEST(ShaderAmbientOcclusion, SliceVisibilityMatchesNumericalIntegral) {
    std::vector<glm::vec4> in;
    for (double n : {-1.2, -0.5, 0.0, 0.3, 1.0, 1.5})
        for (double h0 : {-3.0, -1.4, -0.7, -0.1, 0.0})
            for (double h1 : {0.0, 0.2, 0.9, 1.6, 3.0})
                for (double len : {1.0, 0.6}) in.push_back(glm::vec4(float(h0), float(h1), float(n), float(len)));
    auto out = runGlsl({"common/ambient_occlusion.glsl"},
                       "return vec4(gtaoSliceVisibility(x.x, x.y, x.z, x.w), gtaoArc(x.y, x.z), gtaoArc(x.x, x.z), 0.0);",
                       in);
    for (size_t i = 0; i < in.size(); ++i) {
        const double h0 = in[i].x, h1 = in[i].y, n = in[i].z, len = in[i].w;
        const double c0 = n + std::max(h0 - n, -kPi / 2), c1 = n + std::min(h1 - n, kPi / 2);
        const double ref = len * (sliceArcReference(c0, 0.0, n) * (c0 <= 0.0 ? 1.0 : -1.0) +
                                  sliceArcReference(0.0, c1, n) * (c1 >= 0.0 ? 1.0 : -1.0));
        EXPECT_NEAR(out[i].x, ref, 2e-5) << "h0 " << h0 << " h1 " << h1 << " n " << n;
        EXPECT_NEAR(out[i].y, sliceArcReference(0.0, h1, n), 2e-5);
        EXPECT_NEAR(out[i].z, sliceArcReference(h0, 0.0, n), 2e-5);
    }
    auto open = runGlsl({"common/ambient_occlusion.glsl"},
                        "return vec4(gtaoSliceVisibility(-LP_AO_HALF_PI, LP_AO_HALF_PI, 0.0, 1.0));",
                        {glm::vec4(0.0f)});
    EXPECT_NEAR(open[0].x, 1.0, 1e-6);
}

// The slice integral averaged over slices spread uniformly in azimuth about V is 1 for an unoccluded
// point, for any normal facing the eye (the parameterisation covers the cosine-weighted hemisphere
// exactly), through the shader's own slice direction and normal projection. Screen angles spread
// uniformly would be off by up to 2% here.
TEST(ShaderAmbientOcclusion, UnoccludedHemisphereAveragesToOne) {
    const std::string body = R"(
        vec3 V = normalize(vec3(0.3, -0.2, 1.0));
        vec3 N = normalize(x.xyz);
        float sum = 0.0;
        const int slices = 256;
        for (int i = 0; i < slices; ++i) {
            vec3 w = gtaoSliceDirection(V, (float(i) + 0.5) * LP_AO_PI / float(slices));
            float n, len;
            gtaoProjectNormal(N, V, w, n, len);
            sum += gtaoSliceVisibility(-LP_AO_PI, LP_AO_PI, n, len);
        }
        return vec4(sum / float(slices));)";
    std::vector<glm::vec4> normals = {glm::vec4(0.3f, -0.2f, 1.0f, 0.0f), glm::vec4(0.0f, 1.0f, 0.4f, 0.0f),
                                      glm::vec4(-0.8f, 0.1f, 0.3f, 0.0f), glm::vec4(0.5f, 0.5f, 0.2f, 0.0f)};
    auto out = runGlsl({"common/ambient_occlusion.glsl"}, body, normals);
    for (size_t i = 0; i < normals.size(); ++i) EXPECT_NEAR(out[i].x, 1.0, 2e-3) << "normal " << i;
}

// The screen direction of a slice is the direction in which the projection of P + t w moves: check
// against a finite difference of the projection, and that w is perpendicular to V and unit.
TEST(ShaderAmbientOcclusion, SliceDirectionProjectsOntoTheScreenLine) {
    const std::string body = R"(
        vec3 P = vec3(x.x, x.y, -x.z);
        vec3 V = normalize(-P);
        vec3 w = gtaoSliceDirection(V, x.w);
        vec2 d = gtaoScreenDirection(P, w);
        float t = 1e-3;
        vec2 a = P.xy / -P.z, b = (P + t * w).xy / -(P + t * w).z;
        vec2 fd = normalize(b - a);
        return vec4(dot(d, fd), dot(w, V), length(w), 0.0);)";
    std::vector<glm::vec4> in;
    for (float psi : {0.1f, 0.9f, 1.7f, 2.6f, 3.1f})
        for (glm::vec3 p : {glm::vec3(0.0f, 0.0f, 2.0f), glm::vec3(1.5f, -0.7f, 3.0f), glm::vec3(-2.0f, 1.0f, 1.0f)})
            in.push_back(glm::vec4(p, psi));
    auto out = runGlsl({"common/ambient_occlusion.glsl"}, body, in);
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_NEAR(out[i].x, 1.0, 1e-3) << i;
        EXPECT_NEAR(out[i].y, 0.0, 1e-5) << i;
        EXPECT_NEAR(out[i].z, 1.0, 1e-5) << i;
    }
}

// Lagarde's specular occlusion against its formula in double; 1 without occlusion, 0 under full
// occlusion, never above the AO's reach of 1 and non-decreasing in the AO.
TEST(ShaderAmbientOcclusion, SpecularOcclusionMatchesReference) {
    std::vector<glm::vec4> in;
    for (double nv : {0.0, 0.1, 0.5, 0.9, 1.0})
        for (double alpha : {0.0, 0.05, 0.25, 0.6, 1.0})
            for (int a = 0; a <= 20; ++a) in.push_back(glm::vec4(float(nv), float(a / 20.0), float(alpha), 0.0f));
    auto out = runGlsl({"common/ambient_occlusion.glsl"}, "return vec4(specularOcclusion(x.x, x.y, x.z));", in);
    for (size_t i = 0; i < in.size(); ++i) {
        EXPECT_NEAR(out[i].x, specularOcclusionReference(in[i].x, in[i].y, in[i].z), 2e-5);
        EXPECT_GE(out[i].x, 0.0f);
        EXPECT_LE(out[i].x, 1.0f);
        if (in[i].y == 1.0f) EXPECT_NEAR(out[i].x, 1.0, 1e-6);
        if (in[i].y == 0.0f) EXPECT_NEAR(out[i].x, 0.0, 1e-6);
        if (i > 0 && in[i].y > 0.0f) EXPECT_GE(out[i].x, out[i - 1].x - 1e-6);
    }
}

// The 4x4 rotation pattern holds each of its 16 values once per tile (so the denoise's 4x4 box
// averages 16 distinct rotations) and repeats every 4 pixels.
TEST(ShaderAmbientOcclusion, TileNoiseIsAPermutationOfSixteen) {
    std::vector<glm::vec4> in;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) in.push_back(glm::vec4(float(x), float(y), 0.0f, 0.0f));
    auto out = runGlsl({"common/ambient_occlusion.glsl"}, "return vec4(aoTileNoise(ivec2(x.xy)));", in);
    std::set<int> tile;
    for (size_t i = 0; i < in.size(); ++i) {
        const int x = int(in[i].x), y = int(in[i].y);
        const int k = int(std::lround(out[i].x * 16.0 - 0.5));
        EXPECT_NEAR(out[i].x, (k + 0.5) / 16.0, 1e-6);
        if (x < 4 && y < 4) tile.insert(k);
        EXPECT_EQ(out[i].x, out[size_t((y & 3) * 8 + (x & 3))].x);
    }
    EXPECT_EQ(tile.size(), 16u);
    EXPECT_EQ(*tile.begin(), 0);
    EXPECT_EQ(*tile.rbegin(), 15);
}

// An open plane occludes nothing: AO 1 on it within 0.01 (8-bit output, samples rounded to pixel
// centres), at full and half size, from either G-buffer mode's positions and normals.
TEST(AmbientOcclusion, OpenPlaneIsUnoccluded) {
    const Scene s = cornerScene(false);
    for (GBufferMode mode : allGBufferModes())
        for (AoResolution res : {AoResolution::Full, AoResolution::Half}) {
            SCOPED_TRACE(std::string(aoResolutionName(res)) + ", " + gbufferModeName(mode) + " G-buffer");
            const AoImage img = renderAoView(s, 96, 64, aoAt(res), mode);
            double worst = 1.0, sum = 0.0;
            int n = 0;
            for (int y = 0; y < img.h; ++y)
                for (int x = 0; x < img.w; ++x) {
                    glm::dvec3 p;
                    if (!floorPoint(s, img.w, img.h, x, y, p)) continue;
                    worst = std::min(worst, img.at(x, y));
                    sum += img.at(x, y);
                    ++n;
                }
            EXPECT_GT(n, img.w * img.h / 4);
            EXPECT_GE(sum / n, 0.995);
            EXPECT_GE(worst, 0.99);
        }
}

// A 90-degree crease: on the floor at distance d from the wall the cosine-weighted visibility of
// occluders within the radius r is 1 - (acos(a) - a sqrt(1 - a^2)) / pi, a = d / r. GTAO fades
// samples out between 0.6 r and r, so its value lies between the visibilities with cut-offs r and
// 0.6 r; bound 0.06 beyond them (16 rotations x 4 directions x 8 steps, the 4x4 denoise box spanning
// a range of d, 8-bit output). Either G-buffer mode.
TEST(AmbientOcclusion, CornerMatchesAnalyticVisibility) {
    const Scene s = cornerScene(true);
    const int w = 128, h = 128;
    AoSettings settings = aoAt(AoResolution::Full);
    settings.directions = 4;
    settings.steps = 8;
    const double r = settings.radius;
    for (GBufferMode mode : allGBufferModes()) {
        SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer");
        const AoImage img = renderAoView(s, w, h, settings, mode);
        int checked = 0;
        const int x = w / 2;
        for (int y = 0; y < h; ++y) {
            glm::dvec3 p;
            bool inside = true;  // the denoise's 4x4 box stays on the floor
            for (int dy = -2; dy <= 2 && inside; ++dy)
                for (int dx = -2; dx <= 2 && inside; ++dx) inside = floorPoint(s, w, h, x + dx, y + dy, p);
            if (!inside || !floorPoint(s, w, h, x, y, p)) continue;
            const double d = p.z;
            if (d < 0.03 || d > 0.45) continue;
            const double lo = cornerVisibility(d, r), hi = cornerVisibility(d, 0.6 * r);
            const double got = img.at(x, y);
            EXPECT_GE(got, lo - 0.06) << "d " << d << " expected in [" << lo << ", " << hi << "]";
            EXPECT_LE(got, hi + 0.06) << "d " << d << " expected in [" << lo << ", " << hi << "]";
            ++checked;
        }
        EXPECT_GE(checked, 5);
        // Far from the crease (beyond the radius) the floor is open again.
        glm::dvec3 p;
        ASSERT_TRUE(floorPoint(s, w, h, x, h - 3, p));
        ASSERT_GT(p.z, 1.2 * r);
        EXPECT_GE(img.at(x, h - 3), 0.97);
    }
}

// Half size with the depth-aware upsample against full size on the corner: mean difference <= 0.03,
// and no pixel on the wall or floor further than 0.15 away (edges of the 2x2 footprint).
TEST(AmbientOcclusion, HalfResolutionFollowsFullResolution) {
    const Scene s = cornerScene(true);
    const AoImage full = renderAoView(s, 96, 96, aoAt(AoResolution::Full));
    const AoImage half = renderAoView(s, 96, 96, aoAt(AoResolution::Half));
    double sum = 0.0, worst = 0.0;
    for (size_t i = 0; i < full.ao.size(); ++i) {
        const double d = std::abs(full.ao[i] - half.ao[i]);
        sum += d;
        worst = std::max(worst, d);
    }
    EXPECT_LE(sum / double(full.ao.size()), 0.03);
    EXPECT_LE(worst, 0.15);
}

namespace {
ImageF renderHdr(const Scene& s, RenderSettings settings) {
    Renderer r(s);
    settings.keepHdr = true;
    settings.post.bloom = false;
    settings.post.toon = false;
    r.render(settings);
    return r.readHdr();
}
}  // namespace

// AO darkens only indirect light: with IBL off and ambient 0 the image is identical with the AO
// pass forced on (--all-passes adds it), and with ambient on, AO on is never brighter than AO off
// and darker by at most the ambient term kd x ambient.
TEST(AmbientOcclusion, DirectLightIsUntouched) {
    Scene s = cornerScene(true);
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
    sun.color = glm::vec3(1.0f);
    sun.intensity = 2.0f;
    s.directionalLights.push_back(sun);
    RenderSettings base;
    base.width = 64;
    base.height = 64;
    base.shadows.enabled = false;
    base.environment.ibl = false;

    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);  // --all-passes adds IBL from the colour: black, no light
    RenderSettings on = base;
    on.allPasses = true;  // adds the AO pass although nothing indirect is lit
    RenderSettings off = on;
    off.ao.enabled = false;
    {
        Renderer r(s);
        RenderSettings check = on;
        r.render(check);
        EXPECT_TRUE(r.graph().isLive("ao"));
    }
    const ImageF a = renderHdr(s, on), b = renderHdr(s, off);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    for (size_t i = 0; i < a.rgba.size(); ++i) ASSERT_EQ(a.rgba[i], b.rgba[i]) << "value " << i;

    s.ambient = glm::vec3(0.2f);
    RenderSettings ambientOn = base, ambientOff = base;
    ambientOff.ao.enabled = false;
    const ImageF c = renderHdr(s, ambientOn), d = renderHdr(s, ambientOff);
    const double ambientTerm = 0.2 * 0.5;  // ambient x kd
    double darkest = 0.0;
    for (size_t i = 0; i < c.rgba.size(); i += 4)
        for (int k = 0; k < 3; ++k) {
            const double diff = double(c.rgba[i + k]) - double(d.rgba[i + k]);
            EXPECT_LE(diff, 1e-3 * std::max(1.0, double(d.rgba[i + k]))) << "AO brightened pixel " << i / 4;
            EXPECT_GE(diff, -ambientTerm - 1e-3) << "AO darkened more than the ambient at pixel " << i / 4;
            darkest = std::min(darkest, diff);
        }
    EXPECT_LT(darkest, -0.02) << "the crease must darken the ambient";
}

// The stock scenes with IBL on and AO at both sizes: every HDR value finite, never brighter than
// without AO (AO only multiplies indirect terms by [0, 1]).
TEST(AmbientOcclusion, StockScenesStayFiniteAndOnlyDarken) {
    for (const char* name : {"cornell", "ibl-spheres", "unlit"}) {
        SCOPED_TRACE(name);
        const Scene scene = loadScene(test::repoPath(std::string("scenes/") + name + ".json"));
        RenderSettings base;
        base.width = 48;
        base.height = 32;
        base.environment = test::smallIblBake(64);
        base.environment.ibl = true;
        base.localLights.enabled = false;
        RenderSettings off = base;
        off.ao.enabled = false;
        const ImageF ref = renderHdr(scene, off);
        for (AoResolution res : {AoResolution::Full, AoResolution::Half}) {
            RenderSettings on = base;
            on.ao.resolution = res;
            const ImageF img = renderHdr(scene, on);
            ASSERT_EQ(img.rgba.size(), ref.rgba.size());
            for (size_t i = 0; i < img.rgba.size(); ++i) {
                ASSERT_TRUE(std::isfinite(img.rgba[i])) << "value " << i;
                EXPECT_LE(img.rgba[i], ref.rgba[i] * (1.0f + 2e-3f) + 1e-4f) << "value " << i;
            }
        }
    }
}
