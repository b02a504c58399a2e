// The path tracer (passes/path_trace_pass, shaders/path_trace.comp) against analytic answers, and
// against the raster frame where both model the same light. Small images: seconds on llvmpipe.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/io/image_io.hpp"
#include "engine/render/gltf_brdf.hpp"
#include "engine/scene/primitives.hpp"
#include "frame/renderer.hpp"
#include "tests/gl/gl_fixture.hpp"
#include "engine/scene/animation.hpp"
#include "tests/gl/render_fixture.hpp"

using namespace lp;

namespace {

ModelInstance model(const std::string& name, MeshData mesh, const glm::mat4& transform, glm::vec3 albedo, glm::vec3 ks) {
    ModelInstance m;
    m.name = name;
    m.primitive = name;
    m.mesh = std::move(mesh);
    for (auto& mat : m.mesh.materials) {
        mat.diffuse = albedo;
        mat.specular = ks;  // Ks 0: Lambertian (docs/brdf.md)
        mat.shininess = 32.0f;
    }
    m.transform = transform;
    return m;
}

// The camera straight down at the origin from `height`.
Camera topDown(float height, float fov) {
    Camera c;
    c.position = glm::vec3(0.0f, height, 0.0f);
    c.target = glm::vec3(0.0f);
    c.up = glm::vec3(0.0f, 0.0f, -1.0f);
    c.fovYDegrees = fov;
    c.nearPlane = 0.05f;
    c.farPlane = 100.0f;
    return c;
}

RenderSettings tracerSettings(int size, int samples) {
    RenderSettings s;
    s.renderPath = RenderPath::PathTraced;
    s.width = s.height = size;
    s.keepHdr = true;
    s.autoExposure = false;
    s.aa.method = AntiAliasing::Off;
    s.aa.dither = false;
    s.pathTrace.samples = samples;
    return s;
}

// A white furnace: everything white and Lambertian (albedo 1) under a uniform white environment.
Scene furnaceScene(bool withCube) {
    Scene s;
    s.environment.color = glm::vec3(1.0f);
    s.environment.intensity = 1.0f;
    s.ambient = glm::vec3(0.0f);
    if (withCube) {
        s.models.push_back(model("plane", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)), glm::vec3(1.0f),
                                 glm::vec3(0.0f)));
        s.models.push_back(model("cube", makeCube(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f)),
                                 glm::vec3(1.0f), glm::vec3(0.0f)));
    } else {
        s.models.push_back(model("cube", makeCube(1.0f), glm::rotate(glm::mat4(1.0f), 0.6f, glm::vec3(1.0f, 1.0f, 0.0f)),
                                 glm::vec3(1.0f), glm::vec3(0.0f)));
    }
    s.camera = topDown(4.0f, 50.0f);
    return s;
}

float channel(const ImageF& img, int x, int y, int c) { return img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4 + size_t(c)]; }

// Where a pixel-centre ray of the top-down camera's square image meets the ground (it always looks down).
glm::dvec3 groundPoint(const Scene& s, int size, int x, int y) { return *test::planePoint(s.camera, size, size, x, y); }

// A plane (its materials as the caller set them) under one sun of irradiance 2 and nothing else,
// traced through pixel centres with one sample from (0, 2, 4) at 32 x 24: every pixel on the plane
// within 2e-3 relative of `brdfCosine(V, L)` (the reference BRDF times N.L, N = +Y) times the
// irradiance, and at least a third of the image compared.
void expectSunlitPlaneMatches(ModelInstance plane, const std::function<glm::dvec3(glm::dvec3 V, glm::dvec3 L)>& brdfCosine) {
    Scene s;
    s.environment.color = glm::vec3(0.0f);
    s.ambient = glm::vec3(0.0f);
    s.models.push_back(std::move(plane));
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    sun.intensity = 2.0f;
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 2.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.fovYDegrees = 50.0f;
    const int w = 32, h = 24;
    RenderSettings traced = tracerSettings(w, 1);
    traced.height = h;
    traced.pathTrace.pixelCentre = true;
    Renderer r(s);
    r.render(traced);
    const ImageF hdr = r.readHdr();
    const glm::dvec3 eye(s.camera.position), toSun = -glm::normalize(glm::dvec3(sun.direction));
    int compared = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::optional<glm::dvec3> hit = test::planePoint(s.camera, w, h, x, y);
            if (!hit) continue;
            const glm::dvec3 p = *hit;
            if (std::abs(p.x) > 9.0 || std::abs(p.z) > 9.0) continue;
            const glm::dvec3 want = brdfCosine(glm::normalize(eye - p), toSun) * double(sun.intensity);
            ++compared;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(channel(hdr, x, y, c), want[c], 2e-3 * want[c] + 1e-5) << "pixel " << x << "," << y << " channel " << c;
        }
    EXPECT_GT(compared, w * h / 3);
}

TEST(PathTracer, WhiteConvexObjectInAWhiteFurnaceIsOne) {
    // A convex object: a ray leaving it never meets it again, so each sample is exactly 1 (cosine
    // sampling of albedo 1 weighs 1): any error is the estimator's, not noise.
    const Scene s = furnaceScene(false);
    Renderer r(s);
    const RenderSettings settings = tracerSettings(24, 8);
    r.render(settings);
    const ImageF hdr = r.readHdr();
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(channel(hdr, x, y, c), 1.0f, 1e-3f) << "pixel " << x << "," << y;
    const PathTraceNoise& noise = r.pathTraceNoise();
    EXPECT_EQ(noise.samples, 8);
    EXPECT_LT(noise.meanRelativeStandardError, 1e-3);  // no noise at all
}

TEST(PathTracer, FurnaceWithInterreflectionIsOneWithinTheStatedNoiseAndDirectLightIsNot) {
    // A cube on a plane, all albedo 1: under the uniform environment the full transport is exactly 1
    // everywhere (L = 1 solves the rendering equation); direct light alone loses what bounces between
    // the cube and the plane, and only there: the cube's top sees the sky alone.
    const Scene s = furnaceScene(true);
    const int size = 24;
    RenderSettings full = tracerSettings(size, 64);
    full.pathTrace.bounces = 64;
    Renderer r(s);
    r.render(full);
    const ImageF traced = r.readHdr();
    const double rse = r.pathTraceNoise().meanRelativeStandardError;
    EXPECT_GT(rse, 0.0);
    RenderSettings direct = full;
    direct.pathTrace.directOnly = true;
    r.render(direct);
    const ImageF directOnly = r.readHdr();
    double sum = 0.0;
    int pixels = 0, darkerDirect = 0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const double v = channel(traced, x, y, 1);
            // A pixel's own error: loose (pixels beside the cube vary most); the image mean below is
            // held to the stated noise.
            EXPECT_NEAR(v, 1.0, 0.25) << "pixel " << x << "," << y;
            sum += v;
            ++pixels;
            const double d = channel(directOnly, x, y, 1);
            EXPECT_LE(d, 1.0 + 1e-3) << "pixel " << x << "," << y;
            darkerDirect += d < 0.97 ? 1 : 0;
        }
    }
    // The image's mean: within 4 standard errors of it (pixels are independent).
    EXPECT_NEAR(sum / pixels, 1.0, 4.0 * rse / std::sqrt(double(pixels)) + 1e-3);
    EXPECT_GT(darkerDirect, size * size / 8) << "direct light alone misses the interreflection beside the cube";
    // The cube's top face (the centre of the view) sees only the sky: direct is the whole light.
    for (int y = size / 2 - 2; y < size / 2 + 2; ++y)
        for (int x = size / 2 - 2; x < size / 2 + 2; ++x)
            EXPECT_NEAR(channel(directOnly, x, y, 1), 1.0f, 1e-3f) << "pixel " << x << "," << y;
}

TEST(PathTracer, SunOnALambertianPlaneIsAlbedoOverPiTimesIrradianceTimesCosine) {
    for (double thetaDegrees : {0.0, 35.0, 70.0}) {
        SCOPED_TRACE(thetaDegrees);
        Scene s;
        s.environment.color = glm::vec3(0.0f);
        const glm::vec3 albedo(0.5f, 0.25f, 0.8f);
        s.models.push_back(model("plane", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)), albedo, glm::vec3(0.0f)));
        const double theta = glm::radians(thetaDegrees);
        DirectionalLight sun;
        sun.direction = glm::vec3(-std::sin(theta), -std::cos(theta), 0.0);
        sun.intensity = 3.0f;
        sun.color = glm::vec3(1.0f, 0.9f, 0.5f);
        s.directionalLights.push_back(sun);
        s.camera = topDown(3.0f, 60.0f);
        Renderer r(s);
        r.render(tracerSettings(16, 4));
        const ImageF hdr = r.readHdr();
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double e = albedo[c] / M_PI * sun.intensity * sun.color[c] * std::cos(theta);
                    ASSERT_NEAR(channel(hdr, x, y, c), e, 1e-3 * e + 1e-6) << "pixel " << x << "," << y << " channel " << c;
                }
    }
}

TEST(PathTracer, PointLightOverAPlaneFollowsLightpasssRangedInverseSquare) {
    Scene s;
    s.environment.color = glm::vec3(0.0f);
    const float albedo = 0.7f;
    s.models.push_back(model("plane", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)), glm::vec3(albedo),
                             glm::vec3(0.0f)));
    PointLight light;
    light.position = glm::vec3(0.3f, 1.0f, -0.2f);
    light.intensity = 5.0f;
    light.range = 2.5f;  // the window reaches into the view: the falloff is lightpass's, not 1/d^2 alone
    s.pointLights.push_back(light);
    s.camera = topDown(3.0f, 80.0f);
    s.camera.position.x = 0.01f;  // off the light's own vertical
    const int size = 20;
    RenderSettings settings = tracerSettings(size, 1);
    settings.pathTrace.pixelCentre = true;
    Renderer r(s);
    r.render(settings);
    const ImageF hdr = r.readHdr();
    int lit = 0, dark = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 p = groundPoint(s, size, x, y);
            const glm::dvec3 toLight = glm::dvec3(light.position) - p;
            const double d = glm::length(toLight), cosine = toLight.y / d;
            const double window = std::pow(std::clamp(1.0 - std::pow(d / light.range, 4.0), 0.0, 1.0), 2.0);
            const double dMin = std::min(0.01 * light.range, 0.01);
            const double e = albedo / M_PI * light.intensity / std::max(d * d, dMin * dMin) * window * cosine;
            EXPECT_NEAR(channel(hdr, x, y, 0), e, 2e-3 * e + 1e-5) << "pixel " << x << "," << y << " at " << d << " m";
            lit += e > 0.0 ? 1 : 0;
            dark += e == 0.0 ? 1 : 0;
        }
    EXPECT_GT(lit, size * size / 4);
    EXPECT_GT(dark, 0);  // pixels past the range: exactly 0
}

TEST(PathTracer, MatchesTheRasterFrameOnASunlitGlossyPlane) {
    // One plane (no shadow to disagree on) with a GGX dielectric: the tracer's sun term is the raster's
    // own BRDF function; the raster stores kd in 8-bit sRGB, hence 1%.
    Scene s;
    s.environment.color = glm::vec3(0.0f);
    s.ambient = glm::vec3(0.0f);
    s.models.push_back(model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)),
                             glm::vec3(0.6f, 0.4f, 0.3f), glm::vec3(0.04f)));
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    sun.intensity = 2.0f;
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 2.0f, 4.0f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.fovYDegrees = 50.0f;
    const int w = 48, h = 32;
    RenderSettings raster;
    raster.width = w;
    raster.height = h;
    raster.keepHdr = true;
    raster.autoExposure = false;
    raster.aa.method = AntiAliasing::Off;
    raster.aa.dither = false;
    RenderSettings traced = raster;
    traced.renderPath = RenderPath::PathTraced;
    traced.pathTrace.samples = 2;
    traced.pathTrace.pixelCentre = true;  // the raster's one sample a pixel
    Renderer r(s);
    r.render(raster);
    const ImageF a = r.readHdr();
    const Image8 aDisplay = r.readDisplay();
    r.render(traced);
    const ImageF b = r.readHdr();
    const Image8 bDisplay = r.readDisplay();
    int compared = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (channel(a, x, y, 1) <= 0.0f) continue;  // the background: black in both
            ++compared;
            for (int c = 0; c < 3; ++c) {
                const float ra = channel(a, x, y, c), rb = channel(b, x, y, c);
                EXPECT_NEAR(rb, ra, 0.01f * ra + 1e-4f) << "pixel " << x << "," << y << " channel " << c;
                const int da = aDisplay.rgba[(size_t(y) * w + x) * 4 + c], db = bDisplay.rgba[(size_t(y) * w + x) * 4 + c];
                EXPECT_LE(std::abs(da - db), 2) << "display pixel " << x << "," << y << " channel " << c;
            }
        }
    EXPECT_GT(compared, w * h / 3);
}

// KHR_materials_specular in the tracer's material (F0 = min(0.04 c, 1) s and f90 = s given, the diffuse
// weighted by 1 - max3(F)): a sunlit plane, one pixel-centre sample, no environment (nothing but the
// sun reaches it), against the reference gltfBrdf at every pixel, for weights 0.5, 0 and 1 with coloured
// F0s. Bound: 2e-3 relative (float evaluation).
TEST(PathTracer, SpecularExtensionMatchesTheReferenceOnASunlitPlane) {
    struct Case {
        double s;
        glm::dvec3 colour;
    };
    for (const Case& k : {Case{0.5, {1.0, 0.5, 0.2}}, Case{0.0, {1.0, 1.0, 1.0}}, Case{1.0, {10.0, 5.0, 2.0}}}) {
        SCOPED_TRACE("specular " + std::to_string(k.s));
        GltfBrdfMaterial ref{{0.6, 0.4, 0.3}, 0.0, 0.5};
        ref.specular = k.s;
        ref.specularColor = k.colour;
        ModelInstance plane = model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)),
                                    glm::vec3(ref.baseColor), glm::vec3(0.0f));
        for (auto& mat : plane.mesh.materials) {
            mat.specular = glm::vec3(gltfDielectricF0(1.5) * k.colour);  // the loader's: F0_ior x colour
            mat.dielectricF90 = float(k.s);
            mat.metallic = 0.0f;
            mat.roughness = float(ref.roughness);
            mat.shininess = shininessFromRoughness(mat.roughness);
        }
        expectSunlitPlaneMatches(std::move(plane), [&](glm::dvec3 V, glm::dvec3 L) {
            return gltfBrdf(ref, glm::dvec3(0, 1, 0), V, L) * L.y;
        });
    }
}

// KHR_materials_clearcoat in the tracer: the base under 1 - w and the coat's lobe on the interpolated
// normal. A sunlit plane as above, against gltfCoatedBrdfCosine at every pixel for a full smooth coat
// and a half rough one over a dielectric. Bound: 2e-3 relative.
TEST(PathTracer, ClearcoatMatchesTheReferenceOnASunlitPlane) {
    for (const glm::dvec2 coat : {glm::dvec2(1.0, 0.3), glm::dvec2(0.5, 0.7)}) {
        SCOPED_TRACE("clearcoat " + std::to_string(coat.x) + " roughness " + std::to_string(coat.y));
        GltfBrdfMaterial ref{{0.6, 0.4, 0.3}, 0.0, 0.5};
        ref.clearcoat = coat.x;
        ref.clearcoatRoughness = coat.y;
        ModelInstance plane = model("plane", makePlane(1.0f, 4), glm::scale(glm::mat4(1.0f), glm::vec3(20.0f)),
                                    glm::vec3(ref.baseColor), glm::vec3(0.0f));
        for (auto& mat : plane.mesh.materials) {
            mat.specular = glm::vec3(float(gltfDielectricF0(1.5)));
            mat.metallic = 0.0f;
            mat.roughness = float(ref.roughness);
            mat.shininess = shininessFromRoughness(mat.roughness);
            mat.clearcoat = float(coat.x);
            mat.clearcoatRoughness = float(coat.y);
        }
        expectSunlitPlaneMatches(std::move(plane), [&](glm::dvec3 V, glm::dvec3 L) {
            const glm::dvec3 N(0, 1, 0);
            return gltfCoatedBrdfCosine(ref, N, N, V, L);
        });
    }
}

// The coat's sampled lobe in a white furnace: a Lambertian white plane (albedo 1, F0 0; a ray leaving it
// never meets it again) under a full coat of roughness 0.3 reflects (1 - w) + w A_coat(N.V), A_coat the
// coat lobe's integrated D Vis N.L (below 1: the layering adds no energy). Seen from 3 m above at 70
// degrees of field of view, N.V from 1 to 0.6: each pixel's mean of 64 samples against that at its own
// N.V within 3% (its noise), the image's mean within 0.3% and below 1 (without the coat, or with the coat
// lobe left out, the mean is 1 or 4% low).
TEST(PathTracer, ClearcoatInAWhiteFurnaceReflectsTheLayeringsEnergy) {
    Scene s;
    s.environment.color = glm::vec3(1.0f);
    s.environment.intensity = 1.0f;
    s.ambient = glm::vec3(0.0f);
    s.models.push_back(model("plane", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(40.0f)), glm::vec3(1.0f),
                             glm::vec3(0.0f)));
    for (auto& mat : s.models[0].mesh.materials) {
        mat.clearcoat = 1.0f;
        mat.clearcoatRoughness = 0.3f;
    }
    s.camera = topDown(3.0f, 70.0f);
    GltfBrdfMaterial coat;
    coat.clearcoatRoughness = 0.3;
    const double alpha = 0.09, a2 = alpha * alpha;
    auto energy = [&](double nv) {  // (1 - w) + w A_coat, A_coat by GGX half-vector sampling
        const glm::dvec3 N(0, 0, 1), V(std::sqrt(std::max(1.0 - nv * nv, 0.0)), 0.0, nv);
        double sum = 0.0;
        const int n = 96;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double u = (i + 0.5) / n, phi = (j + 0.5) / n * 2.0 * 3.14159265358979323846;
                const double ct = std::sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u)), st = std::sqrt(std::max(1.0 - ct * ct, 0.0));
                const glm::dvec3 H(st * std::cos(phi), st * std::sin(phi), ct);
                const double vh = glm::dot(V, H);
                const glm::dvec3 L = 2.0 * vh * H - V;
                if (vh <= 0.0 || L.z <= 0.0) continue;
                sum += gltfClearcoatLobe(coat, N, V, L) * L.z * 4.0 * vh / (gltfGgxDistribution(ct, alpha) * ct);
            }
        const double w = gltfClearcoatWeight(1.0, N, V);
        return (1.0 - w) + w * sum / (n * n);
    };
    const int size = 16;
    Renderer r(s);
    r.render(tracerSettings(size, 64));
    const ImageF hdr = r.readHdr();
    const glm::dvec3 eye(s.camera.position);
    double worst = 0.0, sumGot = 0.0, sumWant = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const double nv = glm::normalize(eye - groundPoint(s, size, x, y)).y;
            const double want = energy(nv);
            const float got = channel(hdr, x, y, 1);
            EXPECT_NEAR(got, want, 0.03 * want) << "pixel " << x << "," << y << " N.V " << nv;
            EXPECT_LT(want, 1.0) << "N.V " << nv << ": the layering's energy";
            worst = std::max(worst, std::abs(got - want) / want);
            sumGot += got;
            sumWant += want;
        }
    // The image's mean (the noise averaged out) within 0.3% of the layering's, and below 1.
    EXPECT_NEAR(sumGot / sumWant, 1.0, 0.003);
    EXPECT_LT(sumGot / (size * size), 1.0);
    RecordProperty("worst_relative_error", std::to_string(worst));
    RecordProperty("mean_over_layering", std::to_string(sumGot / sumWant));
}

TEST(PathTracer, GraphRunsThePathTracerInsteadOfTheRasterPasses) {
    const Scene s = furnaceScene(false);
    Renderer r(s);
    r.render(tracerSettings(8, 1));
    EXPECT_TRUE(r.graph().isLive("path_trace"));
    EXPECT_TRUE(r.graph().isLive("tonemap"));
    EXPECT_FALSE(r.graph().isLive("gbuffer"));
    EXPECT_FALSE(r.graph().isLive("global_lights"));
}

// A small bright lamp in a dim map (64 x 32, one texel of 2000 at row 9, rest 0.05), turned 30
// degrees, over a white Lambertian plane, direct light: the plane's radiance is albedo / π times the
// cosine-weighted integral of the map over the upper hemisphere, the map filtered bilinearly as the
// tracer's sampler does (REPEAT across u, CLAMP_TO_EDGE along v); the turn about +Y changes nothing
// on a horizontal plane, but a frame mismatch between the two strategies' densities would bias it.
// Importance sampling must give it within its stated noise at 64 samples; the BRDF's samples alone
// mostly miss the lamp (about one ray in 700), so their pixels scatter widely. (A sample's own relative
// spread is about 1.7 here: the cells are uniform while the filtered lamp is a tent across them.)
TEST(PathTracer, SmallLampInAMapConvergesWithEnvironmentSamplingAndAgreesWithTheIntegral) {
    const int mw = 64, mh = 32, lx = 40, ly = 9;
    const float lamp = 2000.0f, rest = 0.05f;
    ImageF map;
    map.width = mw;
    map.height = mh;
    map.rgba.assign(size_t(mw) * size_t(mh) * 4, rest);
    for (size_t i = 3; i < map.rgba.size(); i += 4) map.rgba[i] = 1.0f;
    for (int c = 0; c < 3; ++c) map.rgba[(size_t(ly) * mw + size_t(lx)) * 4 + size_t(c)] = lamp;
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("lightpass-test-" + std::to_string(::getpid()) + "-lamp.exr");
    writeExr(file, map);
    auto texel = [&](int x, int y) {
        x = ((x % mw) + mw) % mw;
        y = std::clamp(y, 0, mh - 1);
        return double(map.rgba[(size_t(y) * mw + size_t(x)) * 4]);
    };
    // ∫ L cos θ dω over θ < 90°, dω = 2π² sin θ du dv, midpoint rule on a grid 64x finer than the map.
    const int nu = mw * 64, nv = mh * 32;  // v in [0, 0.5)
    double integral = 0.0;
    for (int j = 0; j < nv; ++j) {
        const double v = (j + 0.5) / (2.0 * nv), theta = v * M_PI;
        const double t = v * mh - 0.5, fy = t - std::floor(t);
        const int y0 = int(std::floor(t));
        double row = 0.0;
        for (int i = 0; i < nu; ++i) {
            const double sx = (i + 0.5) / nu * mw - 0.5, fx = sx - std::floor(sx);
            const int x0 = int(std::floor(sx));
            row += (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
                   fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
        }
        integral += row * std::cos(theta) * 2.0 * M_PI * M_PI * std::sin(theta) / (double(nu) * 2.0 * nv);
    }
    const double expected = integral / M_PI;  // albedo 1

    Scene s;
    s.models.push_back(model("plane", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)), glm::vec3(1.0f),
                             glm::vec3(0.0f)));
    s.environment.map = file;
    s.environment.intensity = 1.0f;
    s.environment.rotationDegrees = 30.0f;
    s.ambient = glm::vec3(0.0f);
    s.camera = topDown(4.0f, 50.0f);
    const int size = 24;
    RenderSettings settings = tracerSettings(size, 64);
    settings.pathTrace.directOnly = true;
    // Per pixel (green channel) the error relative to the integral: its mean and RMS; returns the
    // tracer's stated noise.
    auto relativeErrors = [&](bool importance, double& mean, double& rms) {
        RenderSettings run = settings;
        run.pathTrace.environmentSampling = importance;
        Renderer r(s);
        r.render(run);
        const ImageF img = r.readHdr();
        double sum = 0.0, sq = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const double e = channel(img, x, y, 1) / expected - 1.0;
                sum += e;
                sq += e * e;
            }
        mean = sum / (size * size);
        rms = std::sqrt(sq / (size * size));
        return r.pathTraceNoise().meanRelativeStandardError;
    };
    double mean = 0.0, rms = 0.0, brdfMean = 0.0, brdfRms = 0.0;
    const double rse = relativeErrors(true, mean, rms);
    relativeErrors(false, brdfMean, brdfRms);
    std::filesystem::remove(file);
    // The image's mean within 4 standard errors of the integral (pixels are independent), each
    // pixel's spread about its stated noise; the HDR target's half floats add < 1e-3.
    EXPECT_NEAR(mean, 0.0, 4.0 * rse / size + 2e-3) << "expected radiance " << expected;
    EXPECT_LT(rms, 2.0 * rse + 2e-3);
    EXPECT_LT(rse, 0.3) << "64 samples, nearly all towards the lamp";
    EXPECT_GT(brdfRms, 5.0 * rms) << "the BRDF's samples alone: relative RMS error " << brdfRms << " against " << rms;
}

// The maps at the hit: a 1 m card 0.5 m over a white ground, both Lambertian, under a sun straight
// down (E = 1), seen from above. The card's base-colour map is opaque grey (sRGB 188: linear 0.5029)
// where u < 0.5 and alpha 0 where u >= 0.5, alphaMode MASK: the grey half shows 0.5029 / π; through
// the cut half the camera ray and the sun's shadow ray both pass, so the ground there shows 1 / π.
TEST(PathTracer, BaseColourMapIsSampledAndMaskCutsCameraAndShadowRays) {
    Image8 img;
    img.width = img.height = 8;
    img.rgba.assign(8 * 8 * 4, 0);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            uint8_t* t = &img.rgba[size_t(y * 8 + x) * 4];
            t[0] = t[1] = t[2] = 188;
            t[3] = x < 4 ? 255 : 0;
        }
    TextureRef map;
    map.encoded = std::make_shared<const std::string>(encodePng(img));
    map.key = "test#card";
    Scene s;
    s.environment.color = glm::vec3(0.0f);
    s.ambient = glm::vec3(0.0f);
    s.models.push_back(model("ground", makePlane(1.0f), glm::scale(glm::mat4(1.0f), glm::vec3(6.0f)), glm::vec3(1.0f),
                             glm::vec3(0.0f)));
    ModelInstance card = model("card", makePlane(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f)),
                               glm::vec3(1.0f), glm::vec3(0.0f));
    for (auto& mat : card.mesh.materials) {
        mat.diffuseMap = map;
        mat.alphaMode = AlphaMode::Mask;
        mat.alphaCutoff = 0.5f;
    }
    s.models.push_back(std::move(card));
    DirectionalLight sun;
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    sun.intensity = 1.0f;
    sun.color = glm::vec3(1.0f);
    s.directionalLights.push_back(sun);
    s.camera = topDown(4.0f, 40.0f);
    const int size = 32;
    RenderSettings settings = tracerSettings(size, 1);
    settings.pathTrace.directOnly = true;
    settings.pathTrace.pixelCentre = true;
    Renderer r(s);
    r.render(settings);
    const ImageF hdr = r.readHdr();
    const double grey = std::pow((188.0 / 255.0 + 0.055) / 1.055, 2.4) / M_PI, ground = 1.0 / M_PI;
    int onCard = 0, throughCut = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 p = *test::planePoint(s.camera, size, size, x, y, 0.5);  // where it crosses the card's height
            if (std::fabs(p.z) > 0.45 || std::fabs(p.x) > 0.45 || std::fabs(p.x) < 0.1) continue;
            const bool opaque = p.x < 0.0;  // u = x + 0.5 on the card
            const double expected = opaque ? grey : ground;
            ASSERT_NEAR(channel(hdr, x, y, 1), expected, 2e-3 * expected)
                << "pixel " << x << "," << y << (opaque ? " (the card's grey half)" : " (the ground through the cut half)");
            ++(opaque ? onCard : throughCut);
        }
    EXPECT_GT(onCard, 20);
    EXPECT_GT(throughCut, 20);
}

}  // namespace

// An animated glTF is traced where its clip puts it at the frame's time: a white card sliding 1 m a
// second along +x under a sun straight down, seen from above through pixel centres (each pixel is on
// the card or not), lights exactly the pixels whose ground point its posed footprint covers, first
// at t = 0 and then, in the same renderer, at t = 1 (the tracer poses and uploads the scene again).
TEST(PathTracer, AnimatedModelIsTracedInItsPoseAtTheFramesTime) {
    Scene s;
    s.environment.color = glm::vec3(0.0f);
    ModelInstance card = model("plane", makePlane(1.0f), glm::mat4(1.0f), glm::vec3(0.6f), glm::vec3(0.0f));
    auto animation = std::make_shared<NodeAnimation>();
    animation->nodes.push_back(AnimatedNode{});
    animation->order = {0};
    animation->restLocal = card.mesh.vertices;
    animation->ranges.push_back({0, 0, uint32_t(card.mesh.vertices.size()), 0, false});
    AnimationSampler sampler;
    sampler.times = {0.0f, 2.0f};
    sampler.values = {glm::vec4(0.0f), glm::vec4(2.0f, 0.0f, 0.0f, 0.0f)};
    AnimationClip clip;
    clip.samplers.push_back(sampler);
    clip.channels.push_back({0, AnimationPath::Translation, 0});
    clip.duration = 2.0f;
    animation->clips.push_back(clip);
    card.animation = animation;
    card.playingClips = {0};
    s.models.push_back(card);
    DirectionalLight sun;
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    sun.intensity = 2.0f;
    s.directionalLights.push_back(sun);
    s.camera = topDown(3.0f, 60.0f);
    const int size = 24;
    RenderSettings settings = tracerSettings(size, 2);
    settings.pathTrace.pixelCentre = true;
    settings.pathTrace.bounces = 1;
    Renderer r(s);
    const double lit = 0.6 / M_PI * 2.0;
    for (float t : {0.0f, 1.0f}) {
        SCOPED_TRACE(t);
        r.render(settings, t);
        const ImageF hdr = r.readHdr();
        int litPixels = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 p = groundPoint(s, size, x, y);
                const double cx = p.x - t;                                     // the card's centre is at x = t
                const bool onCard = std::abs(cx) < 0.5 && std::abs(p.z) < 0.5;
                const bool nearEdge = std::abs(std::abs(cx) - 0.5) < 1e-3 || std::abs(std::abs(p.z) - 0.5) < 1e-3;
                if (nearEdge) continue;
                litPixels += onCard;
                ASSERT_NEAR(channel(hdr, x, y, 0), onCard ? lit : 0.0, 1e-3) << "pixel " << x << "," << y << " ground " << p.x << "," << p.z;
            }
        EXPECT_GT(litPixels, 20);
    }
}
