// KHR_materials_transmission + KHR_materials_volume on the raster paths (passes/transparent_pass,
// shaders/forward.frag LP_FORWARD_TRANSMISSION): physics, not pixels. A far camera with a narrow
// field of view makes the view rays nearly parallel; the backdrop is flat-lit (its radiance is its
// colour) and nothing else lights the glass (no lights, no ambient, a black environment), so what the
// glass shows is the transmitted term alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/renderer.hpp"
#include "passes/transparent_pass.hpp"
#include "tests/gl/render_fixture.hpp"
#include "gl_fixture.hpp"

using namespace lp;
using lp::test::renderHdr;

namespace {

constexpr int kWidth = 128, kHeight = 96;
constexpr float kCameraDistance = 100.0f, kFovDegrees = 1.5f;

struct FrameWay {
    RenderPath path;
    GBufferMode mode;
};
const FrameWay kEveryWay[] = {{RenderPath::Deferred, GBufferMode::Classic},
                              {RenderPath::Deferred, GBufferMode::Visibility},
                              {RenderPath::ForwardPlus, GBufferMode::Classic}};
std::string wayName(FrameWay w) {
    return w.path == RenderPath::ForwardPlus ? renderPathName(w.path)
                                             : std::string(renderPathName(w.path)) + ", " + gbufferModeName(w.mode) + " G-buffer";
}

RenderSettings settings(FrameWay w) {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;
    s.autoExposure = false;
    s.width = kWidth;
    s.height = kHeight;
    s.keepHdr = true;
    s.renderPath = w.path;
    s.gbuffer.mode = w.mode;
    s.environment = test::smallIblBake(16);
    return s;
}

ModelInstance model(const std::string& primitive, MeshData mesh, const glm::mat4& transform, glm::vec3 colour, bool flat) {
    ModelInstance m;
    m.name = primitive;
    m.primitive = primitive;
    m.mesh = std::move(mesh);
    for (Material& mat : m.mesh.materials) {
        mat.diffuse = colour;
        mat.specular = glm::vec3(0.04f);
        mat.metallic = 0.0f;
        mat.roughness = 0.0f;
        mat.shininess = shininessFromRoughness(0.0f);
        mat.flat = flat;
    }
    m.transform = transform;
    return m;
}

// A flat-lit quad of w x h in the plane z = `z`, facing +Z, centred at (x, 0).
ModelInstance backdrop(float x, float z, float w, float h, glm::vec3 colour) {
    glm::mat4 t = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z));
    t = glm::rotate(t, glm::radians(90.0f), glm::vec3(1, 0, 0));
    t = glm::scale(t, glm::vec3(w, 1.0f, h));
    return model("plane", makePlane(1.0f), t, colour, true);
}

// A glass slab: the unit cube scaled to w x h x `thickness` (its own z), turned `degrees` about +Y, at
// the origin; its material: transmission 1, ior 1.5, smooth, volume thickness 1 in model units (the
// model's scale makes it `thickness`), or 0 (thin-walled).
ModelInstance slab(float thickness, float degrees, bool thinWalled, float w = 1.2f, float h = 1.0f) {
    glm::mat4 t = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0));
    t = glm::scale(t, glm::vec3(w, h, thickness));
    ModelInstance m = model("cube", makeCube(1.0f), t, glm::vec3(1.0f), false);
    for (Material& mat : m.mesh.materials) {
        mat.transmission = 1.0f;
        mat.ior = 1.5f;
        mat.thickness = thinWalled ? 0.0f : 1.0f;
    }
    return m;
}

// Nothing lights the glass but what it transmits: no lights, no ambient, a black environment.
Scene darkScene() {
    Scene s;
    s.camera.position = {0.0f, 0.0f, kCameraDistance};
    s.camera.target = {0.0f, 0.0f, 0.0f};
    s.camera.fovYDegrees = kFovDegrees;
    s.camera.nearPlane = kCameraDistance - 5.0f;
    s.camera.farPlane = kCameraDistance + 5.0f;
    s.ambient = glm::vec3(0.0f);
    s.environment.color = glm::vec3(0.0f);
    return s;
}

glm::vec3 pixel(const ImageF& img, int x, int y) {
    const size_t i = (size_t(y) * size_t(img.width) + size_t(x)) * 4;
    return {img.rgba[i], img.rgba[i + 1], img.rgba[i + 2]};
}

// Where along row y, between x0 and x1, the red channel first rises through `level`: the sub-pixel
// position (pixel centres at x + 0.5), linearly between the two pixels it lies between; NaN if never.
double risingEdge(const ImageF& img, int y, int x0, int x1, float level) {
    for (int x = x0; x + 1 <= x1; ++x) {
        const float a = pixel(img, x, y).x, b = pixel(img, x + 1, y).x;
        if (a < level && b >= level) return x + 0.5 + double(level - a) / double(b - a);
    }
    return std::nan("");
}

// Metres on the plane z = `z` per pixel.
double metresPerPixel(float z) {
    const double height = 2.0 * double(kCameraDistance - z) * std::tan(glm::radians(double(kFovDegrees)) / 2.0);
    return height / double(kHeight);
}

std::string decision(const Scene& scene, const RenderSettings& s, const std::string& pass) {
    Renderer r(scene);
    r.render(s, 0.0f, false);
    for (const auto& d : r.graph().explain())
        if (d.name == pass) return d.runs ? "runs" : d.reason;
    return "absent";
}

}  // namespace

// A slab of IOR 1.5, t = 0.5 thick, turned 40 degrees to the view, shifts a vertical edge of the wall
// behind it by Snell's lateral offset t sin(theta - theta_t) / cos(theta_t) (0.140 m, 5.1 pixels here)
// within 0.75 pixel, towards +x (the refracted ray bends towards the slab's inner normal, -x here), in
// every render path. A thin-walled slab (thickness 0) leaves the edge where it is, within 0.1 pixel.
TEST(Transmission, SlabShiftsTheBackgroundBySnellsLateralOffset) {
    const float t = 0.5f, degrees = 40.0f, wallZ = -1.0f;
    const double theta = glm::radians(double(degrees)), thetaT = std::asin(std::sin(theta) / 1.5);
    const double offset = t * std::sin(theta - thetaT) / std::cos(thetaT);
    Scene base = darkScene();
    base.models.push_back(backdrop(-1.5f, wallZ, 3.0f, 3.0f, glm::vec3(0.0f)));  // black left of x = 0
    base.models.push_back(backdrop(1.5f, wallZ, 3.0f, 3.0f, glm::vec3(1.0f)));   // white right of it
    for (FrameWay way : kEveryWay) {
        SCOPED_TRACE(wayName(way));
        const ImageF bare = renderHdr(base, settings(way));
        Scene thick = base, thin = base;
        thick.models.push_back(slab(t, degrees, false));
        thin.models.push_back(slab(t, degrees, true));
        const ImageF shifted = renderHdr(thick, settings(way)), unshifted = renderHdr(thin, settings(way));
        const int y = kHeight / 2;
        // Half the white level seen through the glass, right of the edge: 1 - F at 40 degrees.
        const float white = pixel(shifted, kWidth / 2 + 12, y).x;
        ASSERT_GT(white, 0.9f) << "the white wall seen through the slab";
        // Within the slab's front face (its outline is +-16 pixels about the centre; its left side face,
        // seen edge-on left of that, reads the backdrop 1.2 m across its width).
        const int x0 = kWidth / 2 - 12, x1 = kWidth / 2 + 14;
        const double edgeBare = risingEdge(bare, y, x0, x1, 0.5f);
        const double edgeThick = risingEdge(shifted, y, x0, x1, 0.5f * white);
        const double edgeThin = risingEdge(unshifted, y, x0, x1, 0.5f * white);
        ASSERT_FALSE(std::isnan(edgeBare) || std::isnan(edgeThick) || std::isnan(edgeThin));
        EXPECT_NEAR(edgeBare, kWidth / 2.0, 0.25) << "the wall's edge at x = 0 is the image's centre";
        // The exit point lies about t / 2 behind the slab's centre, the wall 1 m: the exit's pixel
        // offset is the wall's times (D - wallZ) / (D + t / 2), under 1% off.
        const double expected = offset / metresPerPixel(wallZ);
        ASSERT_GT(expected, 4.0) << "the offset is several pixels: the test can tell";
        EXPECT_NEAR(edgeThick - edgeBare, expected, 0.75) << "Snell's lateral offset " << offset << " m";
        EXPECT_NEAR(edgeThin - edgeBare, 0.0, 0.1) << "thin-walled: no offset";
    }
}

// Beer-Lambert: a slab 0.3 thick facing the camera with attenuationColor c at attenuationDistance 0.2
// passes (1 - F0) c^(0.3 / 0.2) of a white wall, per channel, within 1%, in every render path (the
// G-buffer does not hold the slab: the wall behind is what the copy holds). A metal slab transmits
// nothing.
TEST(Transmission, BeerLambertThroughAKnownThickness) {
    const glm::vec3 c{0.5f, 0.8f, 0.25f};
    Scene s = darkScene();
    s.models.push_back(backdrop(0.0f, -1.0f, 4.0f, 4.0f, glm::vec3(1.0f)));
    ModelInstance glass = slab(0.3f, 0.0f, false);
    glass.mesh.materials[0].attenuationColor = c;
    glass.mesh.materials[0].attenuationDistance = 0.2f;
    s.models.push_back(glass);
    Scene metal = s;
    metal.models[1].mesh.materials[0].metallic = 1.0f;
    for (FrameWay way : kEveryWay) {
        SCOPED_TRACE(wayName(way));
        const ImageF img = renderHdr(s, settings(way));
        const glm::vec3 got = pixel(img, kWidth / 2, kHeight / 2);
        for (int k = 0; k < 3; ++k) {
            const double expected = 0.96 * std::pow(double(c[k]), 0.3 / 0.2);
            EXPECT_NEAR(got[k], expected, 0.01 * expected + 1e-3) << "channel " << k;
        }
        const glm::vec3 m = pixel(renderHdr(metal, settings(way)), kWidth / 2, kHeight / 2);
        EXPECT_LT(std::max({m.x, m.y, m.z}), 1e-3f) << "metals do not transmit";
    }
}

// Energy: a slab of transmission 1 before a uniform backdrop passes (1 - F) of it, F = F0 at normal
// incidence: never more than the backdrop, for a smooth and a rough slab (the rough one reads a
// blurred level of the copy, the same for a uniform backdrop); half of it at transmission 0.5 (the
// rest is the diffuse share, unlit here).
TEST(Transmission, SlabPassesOneMinusFresnelOfAUniformBackdrop) {
    const glm::vec3 backdropColour{0.8f, 0.5f, 0.3f};
    for (float roughness : {0.0f, 0.5f})
        for (float transmission : {1.0f, 0.5f}) {
            Scene s = darkScene();
            s.models.push_back(backdrop(0.0f, -1.0f, 4.0f, 4.0f, backdropColour));
            ModelInstance glass = slab(0.2f, 0.0f, false);
            glass.mesh.materials[0].roughness = roughness;
            glass.mesh.materials[0].shininess = shininessFromRoughness(roughness);
            glass.mesh.materials[0].transmission = transmission;
            s.models.push_back(glass);
            SCOPED_TRACE("roughness " + std::to_string(roughness) + ", transmission " + std::to_string(transmission));
            const ImageF img = renderHdr(s, settings(kEveryWay[0]));
            const glm::vec3 got = pixel(img, kWidth / 2, kHeight / 2);
            for (int k = 0; k < 3; ++k) {
                const double expected = transmission * 0.96 * backdropColour[k];
                EXPECT_NEAR(got[k], expected, 0.01 * expected) << "channel " << k;
                EXPECT_LE(got[k], backdropColour[k]) << "no more than the backdrop";
            }
        }
}

// A scene without a transmissive material skips the background copy, saying why; adding one that
// the opaque frame hides entirely (inside an opaque box) runs the copy and compiles the transparent
// pass's transmission variant, and the frame with a blended quad stays bit-identical: the variant
// shades the other blended materials as before.
TEST(Transmission, PassIsSkippedAndFrameUnchangedWithoutTransmission) {
    Scene s = darkScene();
    s.ambient = glm::vec3(0.1f);
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -0.4f, -1.0f));
    s.directionalLights.push_back(sun);
    s.models.push_back(backdrop(0.0f, -1.0f, 4.0f, 4.0f, glm::vec3(0.3f, 0.6f, 0.9f)));
    ModelInstance quad = backdrop(0.0f, 0.5f, 0.6f, 0.6f, glm::vec3(0.9f, 0.3f, 0.1f));
    quad.mesh.materials[0].flat = false;
    quad.mesh.materials[0].opacity = 0.5f;
    quad.mesh.materials[0].alphaMode = AlphaMode::Blend;
    s.models.push_back(quad);
    ModelInstance box = model("cube", makeCube(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.0f, 0.0f)),
                              glm::vec3(0.5f), false);
    s.models.push_back(box);
    Scene hidden = s;
    ModelInstance inside = slab(0.2f, 0.0f, false, 0.3f, 0.3f);
    inside.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.2f, 0.0f, 0.0f)) * inside.transform;
    hidden.models.push_back(inside);
    ASSERT_FALSE(sceneHasTransmission(s));
    ASSERT_TRUE(sceneHasTransmission(hidden));
    for (FrameWay way : kEveryWay) {
        SCOPED_TRACE(wayName(way));
        EXPECT_EQ(decision(s, settings(way), "transmission_background"),
                  "skipped: no material of the scene is transmissive (KHR_materials_transmission, MTL illum 4/6/7)");
        EXPECT_EQ(decision(hidden, settings(way), "transmission_background"), "runs");
        EXPECT_EQ(decision(hidden, settings(way), "transparent"), "runs");
        const ImageF a = renderHdr(s, settings(way)), b = renderHdr(hidden, settings(way));
        EXPECT_TRUE(test::imagesNear(a, b, 0.0f, "a hidden transmissive box changed the frame"));
    }
}

// The bundled scene loads its glTF's transmissive materials and renders finite in every path.
TEST(Transmission, BundledSceneRendersFinite) {
    const Scene scene = loadScene(test::repoPath("scenes/transmission.json"));
    ASSERT_TRUE(sceneHasTransmission(scene));
    for (FrameWay way : kEveryWay) {
        SCOPED_TRACE(wayName(way));
        RenderSettings s = settings(way);
        s.width = 64;
        s.height = 48;
        const ImageF img = renderHdr(scene, s);
        for (float v : img.rgba) ASSERT_TRUE(std::isfinite(v));
    }
}

// The path tracer refracts too: through a slab facing the camera before a uniform flat-lit backdrop,
// each ray crosses two boundaries (1 - F0 each, F0 = 0.04 at normal incidence) and 0.3 of the volume,
// Beer-Lambert c^(0.3 / 0.2), plus the light reflected back and forth inside (F0^2 of it, under 0.2%):
// within 1.5% per channel (5 standard errors), from 64 samples through each pixel's centre averaged over
// 16 x 12 pixels. A
// thin-walled box (thickness 0) lets the rays through unbent, (1 - F0) at each of its two walls, with no
// absorption.
TEST(Transmission, PathTracerRefractsThroughAnAbsorbingSlab) {
    const glm::vec3 c{0.5f, 0.8f, 0.25f};
    Scene s = darkScene();
    s.models.push_back(backdrop(0.0f, -1.0f, 4.0f, 4.0f, glm::vec3(1.0f)));
    ModelInstance glass = slab(0.3f, 0.0f, false, 3.0f, 2.0f);
    glass.mesh.materials[0].attenuationColor = c;
    glass.mesh.materials[0].attenuationDistance = 0.2f;
    s.models.push_back(glass);
    Scene thin = s;
    thin.models[1].mesh.materials[0].thickness = 0.0f;
    RenderSettings traced = settings(kEveryWay[0]);
    traced.width = 32;
    traced.height = 24;
    traced.renderPath = RenderPath::PathTraced;
    traced.pathTrace.samples = 64;
    traced.pathTrace.pixelCentre = true;
    for (bool thinWalled : {false, true}) {
        SCOPED_TRACE(thinWalled ? "thin-walled" : "a volume 0.3 thick");
        const ImageF img = renderHdr(thinWalled ? thin : s, traced);
        glm::dvec3 mean(0.0);
        for (int y = 6; y < 18; ++y)
            for (int x = 8; x < 24; ++x) mean += glm::dvec3(pixel(img, x, y));
        mean /= 192.0;
        for (int k = 0; k < 3; ++k) {
            const double expected = 0.96 * 0.96 * (thinWalled ? 1.0 : std::pow(double(c[k]), 0.3 / 0.2));
            EXPECT_NEAR(mean[k], expected, 0.015 * expected) << "channel " << k;
        }
    }
}

// The tracer's refraction moves the background edge by Snell's lateral offset too (the ray leaves a
// flat slab parallel to how it came in): the slab of SlabShiftsTheBackgroundBySnellsLateralOffset.
TEST(Transmission, PathTracerShiftsTheBackgroundBySnellsLateralOffset) {
    const float t = 0.5f, degrees = 40.0f, wallZ = -1.0f;
    const double theta = glm::radians(double(degrees)), thetaT = std::asin(std::sin(theta) / 1.5);
    const double offset = t * std::sin(theta - thetaT) / std::cos(thetaT);
    Scene s = darkScene();
    s.models.push_back(backdrop(-1.5f, wallZ, 3.0f, 3.0f, glm::vec3(0.0f)));
    s.models.push_back(backdrop(1.5f, wallZ, 3.0f, 3.0f, glm::vec3(1.0f)));
    const Scene bare = s;
    s.models.push_back(slab(t, degrees, false));
    RenderSettings traced = settings(kEveryWay[0]);
    traced.renderPath = RenderPath::PathTraced;
    traced.pathTrace.samples = 4;
    traced.pathTrace.pixelCentre = true;
    const ImageF before = renderHdr(bare, traced), after = renderHdr(s, traced);
    const int y = kHeight / 2, x0 = kWidth / 2 - 12, x1 = kWidth / 2 + 14;
    const float white = pixel(after, kWidth / 2 + 12, y).x;
    ASSERT_GT(white, 0.8f);
    const double edgeBare = risingEdge(before, y, x0, x1, 0.5f);
    const double edgeThick = risingEdge(after, y, x0, x1, 0.5f * white);
    ASSERT_FALSE(std::isnan(edgeBare) || std::isnan(edgeThick));
    EXPECT_NEAR(edgeThick - edgeBare, offset / metresPerPixel(wallZ), 1.0) << "Snell's lateral offset " << offset << " m";
}
