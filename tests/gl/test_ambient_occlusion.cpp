// Ambient occlusion (GTAO) on the GL driver: the slice integral and the specular occlusion against
// double-precision references, the per-texel pattern, open planes (AO 1, uniform), lone spheres in a
// white furnace (nothing occludes them: radiance 1), a 90-degree corner against the analytic
// cosine-weighted visibility and the Cornell box's back wall (no streaks), half against full size,
// and that only indirect light is darkened.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>
#include <string>


#include <glm/gtc/matrix_transform.hpp>

#include "engine/io/image_io.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "tests/gl/render_fixture.hpp"

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

// The 8x8 pattern holds each of its 64 indices once per tile and repeats every 8 texels; its
// (rotation, step offset) pairs put one pair in each of the 8 x 8 strata of [0,1)^2 (the Hammersley
// set), so no rotation range goes with one offset range; and the blur's period weights give each of
// the 8 phases weight 1 about any centre.
TEST(ShaderAmbientOcclusion, PatternCoversSixtyFourStratifiedPairs) {
    std::vector<glm::vec4> in;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) in.push_back(glm::vec4(float(x), float(y), 0.0f, 0.0f));
    auto out = runGlsl({"common/ambient_occlusion.glsl"},
                       "int k = aoPatternIndex(ivec2(x.xy));\n"
                       "return vec4(float(k), aoSliceRotation(k), aoStepOffset(k), float(LP_AO_PATTERN_PERIOD));",
                       in);
    ASSERT_EQ(out[0].w, 8.0f);
    std::set<int> tile;
    std::set<std::pair<int, int>> strata;
    for (size_t i = 0; i < in.size(); ++i) {
        const int x = int(in[i].x), y = int(in[i].y);
        const int k = int(out[i].x);
        EXPECT_EQ(out[i].x, out[size_t((y & 7) * 16 + (x & 7))].x) << x << "," << y;
        EXPECT_NEAR(out[i].y, (k + 0.5) / 64.0, 1e-6);
        if (x < 8 && y < 8) {
            tile.insert(k);
            strata.insert({int(out[i].y * 8.0), int(out[i].z * 8.0)});
            EXPECT_GT(out[i].z, 0.0f);
            EXPECT_LT(out[i].z, 1.0f);
        }
    }
    EXPECT_EQ(tile.size(), 64u);
    EXPECT_EQ(*tile.begin(), 0);
    EXPECT_EQ(*tile.rbegin(), 63);
    EXPECT_EQ(strata.size(), 64u);

    std::vector<glm::vec4> taps;
    for (int k = -6; k <= 6; ++k) taps.push_back(glm::vec4(float(k), 0.0f, 0.0f, 0.0f));
    auto w = runGlsl({"common/ambient_occlusion.glsl"}, "return vec4(aoPeriodWeight(int(x.x)));", taps);
    double phase[8] = {};
    for (size_t i = 0; i < taps.size(); ++i) phase[(int(taps[i].x) + 16) % 8] += w[i].x;
    for (double p : phase) EXPECT_EQ(p, 1.0);
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

namespace {
// Where the ray of pixel (x, y) meets the plane through the origin with normal n, within `extent`
// metres of the origin (in front of the camera), or false.
bool planePoint(const Scene& s, int w, int h, int x, int y, glm::dvec3 n, double extent, glm::dvec3& hit) {
    glm::dvec3 o, d;
    pixelRay(s, w, h, x, y, o, d);
    const double dn = glm::dot(d, n);
    if (std::abs(dn) < 1e-9) return false;
    const double t = -glm::dot(o, n) / dn;
    hit = o + t * d;
    return t > 0.0 && glm::length(hit) < extent;
}

// Mean, standard deviation and minimum of the AO over the pixels `inside` selects.
struct AoStats {
    double mean = 0.0, std = 0.0, min = 1.0;
    int n = 0;
};
template <class Inside>
AoStats aoStats(const AoImage& img, Inside inside) {
    AoStats st;
    double sum = 0.0, sum2 = 0.0;
    for (int y = 0; y < img.h; ++y)
        for (int x = 0; x < img.w; ++x) {
            if (!inside(x, y)) continue;
            const double v = img.at(x, y);
            sum += v;
            sum2 += v * v;
            st.min = std::min(st.min, v);
            ++st.n;
        }
    if (st.n > 0) {
        st.mean = sum / st.n;
        st.std = std::sqrt(std::max(0.0, sum2 / st.n - st.mean * st.mean));
    }
    return st;
}
}  // namespace

// Open walls occlude nothing and read uniform: a 20 m wall facing the camera squarely and one turned
// 60 degrees away, nothing else in the scene, at full and half size. Over the wall's pixels: mean
// >= 0.995, every pixel >= 0.98, standard deviation < 0.005 (no pattern, no streaks).
TEST(AmbientOcclusion, OpenWallsAreUniform) {
    for (double turn : {0.0, 60.0}) {
        Scene s;
        const glm::mat4 t = glm::rotate(glm::mat4(1.0f), float(turn * kPi / 180.0), glm::vec3(0.0f, 1.0f, 0.0f)) *
                            glm::rotate(glm::mat4(1.0f), float(kPi / 2.0), glm::vec3(1.0f, 0.0f, 0.0f)) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(20.0f));
        s.models.push_back(planeModel("wall", t, glm::vec3(0.5f)));
        s.ambient = glm::vec3(0.2f);
        s.camera.position = {0.0f, 0.3f, 4.0f};
        s.camera.target = {0.0f, 0.0f, 0.0f};
        s.camera.fovYDegrees = 60.0f;
        s.camera.nearPlane = 0.1f;
        s.camera.farPlane = 60.0f;
        const glm::dvec3 n(std::sin(turn * kPi / 180.0), 0.0, std::cos(turn * kPi / 180.0));
        for (AoResolution res : {AoResolution::Full, AoResolution::Half}) {
            SCOPED_TRACE(std::string(aoResolutionName(res)) + ", wall turned " + std::to_string(int(turn)) + " deg");
            const AoImage img = renderAoView(s, 96, 64, aoAt(res));
            glm::dvec3 p;
            const AoStats st = aoStats(img, [&](int x, int y) { return planePoint(s, 96, 64, x, y, n, 9.0, p); });
            EXPECT_GT(st.n, 96 * 64 / 3);
            EXPECT_GE(st.mean, 0.995);
            EXPECT_GE(st.min, 0.98);
            EXPECT_LT(st.std, 0.005);
        }
    }
}

// White furnace with AO on: white Lambertian spheres (albedo 1, specular 0) of radius 0.5 made of 64 x
// 32, 24 x 12 and 12 x 6 facets with interpolated normals, on and off the view axis and at three
// depths, each further than the AO radius (1 m) from the others, in a uniform environment of radiance
// 1 (IBL on, no lights, ambient 0). A convex object occludes nothing of itself, so every pixel reads 1:
// each sphere's mean within 1% (bound 0.5%), and every pixel of the image, rims included, within 2%
// (IBL alone: 0.5%; the coarse spheres' interpolated normals face away from the eye at their
// silhouettes, where samples of the sphere itself used to read as horizons: rims up to 30% dark).
// AO at its defaults (half size) and at full size.
TEST(AmbientOcclusion, WhiteFurnaceSpheresStayUnoccluded) {
    const test::WhiteFurnaceMap map("ao-furnace");
    struct Ball {
        glm::vec3 centre;
        int segments;
    };
    const Ball balls[] = {{{-2.6f, 1.3f, 0.0f}, 64}, {{0.0f, 1.3f, 0.0f}, 12}, {{2.6f, 1.3f, 0.0f}, 24},
                          {{-2.6f, -1.3f, 0.0f}, 24}, {{0.0f, -1.3f, -1.5f}, 64}, {{2.6f, -1.3f, 1.0f}, 12}};
    Scene s;
    for (const Ball& b : balls) {
        ModelInstance m;
        m.name = "sphere" + std::to_string(s.models.size());
        m.primitive = "sphere";
        m.mesh = makeSphere(0.5f, b.segments, b.segments / 2);
        for (auto& mat : m.mesh.materials) {
            mat.diffuse = glm::vec3(1.0f);
            mat.specular = glm::vec3(0.0f);
            mat.shininess = 1.0f;
        }
        m.transform = glm::translate(glm::mat4(1.0f), b.centre);
        s.models.push_back(std::move(m));
    }
    s.ambient = glm::vec3(0.0f);
    s.environment.map = map.path;
    s.camera.position = {0.0f, 0.0f, 6.0f};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    const int w = 240, h = 160;
    for (AoResolution res : {AoResolution::Half, AoResolution::Full}) {
        SCOPED_TRACE(aoResolutionName(res));
        RenderSettings settings;
        settings.width = w;
        settings.height = h;
        settings.environment = test::smallIblBake(64);
        settings.environment.ibl = true;
        settings.ao = aoAt(res);
        settings.disabledPasses.insert("global_lights");  // no lights, ambient 0: it adds nothing
        Renderer r(s);
        settings.keepHdr = true;
        settings.post.bloom = false;
        r.render(settings);
        ASSERT_TRUE(r.graph().isLive("ao"));
        ASSERT_TRUE(r.graph().isLive("ibl"));
        const ImageF hdr = r.readHdr();
        double worst = 0.0;
        for (int i = 0; i < w * h; ++i)
            for (int c = 0; c < 3; ++c) {
                const double v = hdr.rgba[size_t(i) * 4 + c];
                worst = std::max(worst, std::abs(v - 1.0));
                EXPECT_NEAR(v, 1.0, 0.02) << "pixel " << i % w << "," << i / w;
            }
        for (const Ball& b : balls) {
            double sum = 0.0;
            int n = 0;
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    glm::dvec3 o, d;
                    pixelRay(s, w, h, x, y, o, d);
                    const glm::dvec3 oc = o - glm::dvec3(b.centre);
                    const double bq = glm::dot(oc, d);
                    if (bq * bq - (glm::dot(oc, oc) - 0.25) <= 0.0) continue;
                    sum += hdr.rgba[(size_t(y) * w + x) * 4];
                    ++n;
                }
            EXPECT_GT(n, 200);
            EXPECT_NEAR(sum / n, 1.0, 0.005) << b.segments << "-segment sphere at " << b.centre.x << "," << b.centre.y;
            std::cout << "furnace " << aoResolutionName(res) << " sphere " << b.segments << ": mean " << sum / n << "\n";
        }
        std::cout << "furnace " << aoResolutionName(res) << " worst pixel |v - 1| " << worst << "\n";
    }
}

// A 90-degree crease: on the floor at distance d from the wall the cosine-weighted visibility of
// occluders within the radius r is 1 - (acos(a) - a sqrt(1 - a^2)) / pi, a = d / r. GTAO fades
// samples out between 0.6 r and r, so its value lies between the visibilities with cut-offs r and
// 0.6 r; bound 0.06 beyond them (the slices and steps spread over the 8x8 pattern, the filters
// spanning a range of d, 8-bit output). At 4 directions x 8 steps at full size, and at the defaults
// (2 x 8, half size). The corner darkens: below 0.75 on average for d in [0.03, 0.2] m (analytic:
// 0.57-0.68 at the rows there, 0.12-0.17 m). Along a row of the floor, d is constant: its AO must be too (standard deviation < 0.01
// over the middle half of the row: no streaks across the crease). Either G-buffer mode.
TEST(AmbientOcclusion, CornerMatchesAnalyticVisibility) {
    const Scene s = cornerScene(true);
    const int w = 128, h = 128;
    AoSettings dense = aoAt(AoResolution::Full);
    dense.directions = 4;
    dense.steps = 8;
    for (const AoSettings& settings : {dense, AoSettings{}}) {
        const double r = settings.radius;
        for (GBufferMode mode : allGBufferModes()) {
            SCOPED_TRACE(std::string(gbufferModeName(mode)) + " G-buffer, " + aoResolutionName(settings.resolution) +
                         ", " + std::to_string(settings.directions) + " x " + std::to_string(settings.steps));
            const AoImage img = renderAoView(s, w, h, settings, mode);
            int checked = 0, near = 0;
            double nearSum = 0.0;
            const int x = w / 2;
            for (int y = 0; y < h; ++y) {
                glm::dvec3 p;
                bool inside = true;  // two rows either side on the floor too (the filters reject the wall's taps)
                for (int dy = -2; dy <= 2 && inside; ++dy) inside = floorPoint(s, w, h, x, y + dy, p);
                if (!inside || !floorPoint(s, w, h, x, y, p)) continue;
                const double d = p.z;
                if (d < 0.03 || d > 0.45) continue;
                const double lo = cornerVisibility(d, r), hi = cornerVisibility(d, 0.6 * r);
                const double got = img.at(x, y);
                EXPECT_GE(got, lo - 0.06) << "d " << d << " expected in [" << lo << ", " << hi << "]";
                EXPECT_LE(got, hi + 0.06) << "d " << d << " expected in [" << lo << ", " << hi << "]";
                ++checked;
                if (d <= 0.2) {
                    nearSum += got;
                    ++near;
                }
                const AoStats row = aoStats(img, [&](int px, int py) { return py == y && px >= w / 4 && px < 3 * w / 4; });
                EXPECT_LT(row.std, 0.01) << "row " << y << " (d " << d << ")";
            }
            EXPECT_GE(checked, 5);
            ASSERT_GE(near, 2);
            EXPECT_LT(nearSum / near, 0.75);
            std::cout << "corner " << aoResolutionName(settings.resolution) << " " << settings.directions << "x"
                      << settings.steps << ": mean AO for d in [0.03, 0.2] m " << nearSum / near << " over " << near
                      << " rows\n";
            // Far from the crease (beyond the radius) the floor is open again.
            glm::dvec3 p;
            ASSERT_TRUE(floorPoint(s, w, h, x, h - 3, p));
            ASSERT_GT(p.z, 1.2 * r);
            EXPECT_GE(img.at(x, h - 3), 0.97);
        }
    }
}

// The Cornell box's back wall (scenes/cornell.json, IBL on, AO at its defaults), the region 0.13-0.42
// m across and 0.38-0.46 m up: at least 0.09 m from the ceiling and the side walls, above the blocks
// and the spheres. Its AO changes only as smoothly as the walls around it make it: the converged
// estimate (16 directions x 32 steps at full size) has a standard deviation of 0.0075 there and
// 0.0013 about a quadratic fit in the pixel coordinates. Bounds: standard deviation < 0.01, and about
// the quadratic fit (what streaks and blotches add) < 0.005; the former 4x4 pattern with 4 steps gave
// 0.018 and 0.016.
TEST(AmbientOcclusion, CornellBackWallHasNoStreaks) {
    const Scene scene = loadScene(test::repoPath("scenes/cornell.json"));
    const int w = 160, h = 160;
    Renderer r(scene);
    RenderSettings settings;
    settings.width = w;
    settings.height = h;
    settings.view = DebugView::Ao;
    settings.environment = test::smallIblBake(16);
    settings.environment.ibl = true;
    r.render(settings);
    ASSERT_TRUE(r.graph().isLive("ao"));
    const Image8 img = r.readDisplay();
    std::vector<double> v, xs, ys;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::dvec3 o, d;
            pixelRay(scene, w, h, x, y, o, d);
            const glm::dvec3 hit = o + d * ((0.5592 - o.z) / d.z);
            if (hit.x < 0.13 || hit.x > 0.42 || hit.y < 0.38 || hit.y > 0.46) continue;
            v.push_back(img.rgba[(size_t(y) * w + x) * 4] / 255.0);
            xs.push_back(x);
            ys.push_back(y);
        }
    ASSERT_GT(v.size(), 400u);
    double mean = 0.0;
    for (double a : v) mean += a / double(v.size());
    double var = 0.0;
    for (double a : v) var += (a - mean) * (a - mean) / double(v.size());
    // Least squares fit of 1, x, y, x^2, y^2, xy (normal equations, Gaussian elimination).
    const int k = 6;
    double A[k][k + 1] = {};
    for (size_t i = 0; i < v.size(); ++i) {
        const double x = (xs[i] - w / 2.0) / w, y = (ys[i] - h / 2.0) / h;
        const double f[k] = {1.0, x, y, x * x, y * y, x * y};
        for (int a = 0; a < k; ++a) {
            for (int b = 0; b < k; ++b) A[a][b] += f[a] * f[b];
            A[a][k] += f[a] * v[i];
        }
    }
    for (int c = 0; c < k; ++c)
        for (int row = 0; row < k; ++row)
            if (row != c) {
                const double m = A[row][c] / A[c][c];
                for (int col = c; col <= k; ++col) A[row][col] -= m * A[c][col];
            }
    double resid = 0.0;
    for (size_t i = 0; i < v.size(); ++i) {
        const double x = (xs[i] - w / 2.0) / w, y = (ys[i] - h / 2.0) / h;
        const double f[k] = {1.0, x, y, x * x, y * y, x * y};
        double fit = 0.0;
        for (int a = 0; a < k; ++a) fit += f[a] * A[a][k] / A[a][a];
        resid += (v[i] - fit) * (v[i] - fit) / double(v.size());
    }
    std::cout << "Cornell back wall: " << v.size() << " pixels, mean " << mean << " std " << std::sqrt(var)
              << " about a quadratic " << std::sqrt(resid) << "\n";
    EXPECT_LT(std::sqrt(var), 0.01);
    EXPECT_LT(std::sqrt(resid), 0.005);
    EXPECT_LT(mean, 0.5) << "the box's walls occlude most of the back wall's hemisphere";
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
    settings.post.bloom = false;
    settings.post.toon = false;
    return test::renderHdr(s, settings);
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
