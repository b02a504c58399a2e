// Light extraction from an environment map (engine/render/ibl_lights.hpp): a synthetic map with a
// 2-texel lamp gives one light in the lamp's direction with the lamp's excess irradiance, the residual
// plus the light conserve the map's integral, and maps without a lamp (uniform, a smooth sky) lose nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/render/ibl_lights.hpp"
#include "engine/render/ibl_sh.hpp"

using namespace lp;

namespace {
constexpr double kPi = 3.14159265358979323846;

ImageF uniformMap(int w, int h, glm::vec3 c) {
    ImageF m;
    m.width = w;
    m.height = h;
    for (int i = 0; i < w * h; ++i) m.rgba.insert(m.rgba.end(), {c.x, c.y, c.z, 1.0f});
    return m;
}

void setTexel(ImageF& m, int x, int y, glm::vec3 c) {
    float* p = &m.rgba[(size_t(y) * size_t(m.width) + size_t(x)) * 4];
    p[0] = c.x;
    p[1] = c.y;
    p[2] = c.z;
}

double texelSolidAngle(const ImageF& m, int y) {
    return (2.0 * kPi / m.width) * (kPi / m.height) * std::sin((y + 0.5) / m.height * kPi);
}

glm::dvec3 integral(const ImageF& m) {  // sum of L dOmega
    glm::dvec3 s(0.0);
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const float* p = &m.rgba[(size_t(y) * size_t(m.width) + size_t(x)) * 4];
            s += glm::dvec3(p[0], p[1], p[2]) * texelSolidAngle(m, y);
        }
    return s;
}

// A sky like bench/mitsuba/make_maps.py's: 1 at the zenith to 0.3 at the horizon, 0.15 below.
ImageF smoothSky(int w, int h) {
    ImageF m = uniformMap(w, h, glm::vec3(0.0f));
    for (int y = 0; y < h; ++y) {
        const double up = std::cos((y + 0.5) / h * kPi);
        const float v = up > 0.0 ? float(0.3 + 0.7 * up) : 0.15f;
        for (int x = 0; x < w; ++x) setTexel(m, x, y, glm::vec3(v, v * 0.9f, v * 0.8f));
    }
    return m;
}
}  // namespace

// Uniform background 0.5 + a lamp of 2 adjacent texels (radiance 50,000, slightly coloured): one light,
// towards the texels' centroid (rotation applied), E = sum (L - 0.5) dOmega, and the residual is the
// background again; residual + light = original to double rounding.
TEST(IblLights, TwoTexelLampIsExtractedWithItsIrradianceAndDirection) {
    ImageF map = uniformMap(128, 64, glm::vec3(0.5f));
    const glm::vec3 lamp(50000.0f, 40000.0f, 30000.0f);
    const int x0 = 40, y = 20;
    setTexel(map, x0, y, lamp);
    setTexel(map, x0 + 1, y, lamp);
    const ImageF original = map;
    const double rotation = 30.0;
    const LightExtraction e = extractEnvironmentLights(map, rotation, 4, 100.0);
    ASSERT_EQ(e.lights.size(), 1u);
    EXPECT_NEAR(e.medianLuminance, 0.5, 1e-6);
    const EnvironmentLight& l = e.lights[0];
    EXPECT_EQ(l.texels, 2);
    const double dOmega = texelSolidAngle(map, y);
    const glm::dvec3 expectedE = (glm::dvec3(lamp) - 0.5) * (2.0 * dOmega);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.irradiance[c], expectedE[c], 1e-5 * expectedE[c]);
    EXPECT_NEAR(l.solidAngle, 2.0 * dOmega, 1e-6 * dOmega);
    EXPECT_NEAR(2.0 * kPi * (1.0 - std::cos(double(l.angularRadius))), 2.0 * dOmega, 1e-6 * dOmega);
    // Centroid of the two texels: u at the boundary between them.
    const glm::dvec3 expectedDir =
        rotateY(equirectDirection((x0 + 1.0) / map.width, (y + 0.5) / map.height), rotation * kPi / 180.0);
    EXPECT_GT(glm::dot(glm::dvec3(l.direction), expectedDir), std::cos(1e-4));
    // Residual: the lamp texels are background now; nothing else moved.
    for (int x : {x0, x0 + 1}) {
        const float* p = &map.rgba[(size_t(y) * size_t(map.width) + size_t(x)) * 4];
        EXPECT_EQ(p[0], 0.5f);
        EXPECT_EQ(p[2], 0.5f);
    }
    const glm::dvec3 before = integral(original), after = integral(map) + glm::dvec3(l.irradiance);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 1e-6 * before[c]);
    EXPECT_FALSE(describeExtraction(e, 4).empty());
}

// Energy with several lamps on a smooth sky, more lamps than asked for: the brightest are taken,
// the rest stay in the map, and the residual's integral plus the lights' is still the original's.
TEST(IblLights, EnergyIsConservedAndOnlyTheBrightestAreTaken) {
    ImageF map = smoothSky(256, 128);
    setTexel(map, 10, 30, glm::vec3(20000.0f));     // dimmest
    setTexel(map, 100, 40, glm::vec3(60000.0f));    // brightest, 2x2 with the wrap below
    setTexel(map, 101, 40, glm::vec3(60000.0f));
    setTexel(map, 100, 41, glm::vec3(60000.0f));
    setTexel(map, 255, 50, glm::vec3(40000.0f));    // across the seam: one region with x = 0
    setTexel(map, 0, 50, glm::vec3(40000.0f));
    const ImageF original = map;
    const LightExtraction e = extractEnvironmentLights(map, 0.0, 2, 100.0);
    EXPECT_EQ(e.regions, 3);
    ASSERT_EQ(e.lights.size(), 2u);
    EXPECT_EQ(e.leftInMap, 1);
    EXPECT_EQ(e.lights[0].texels, 3);
    EXPECT_EQ(e.lights[1].texels, 2);  // the seam did not split it
    EXPECT_GT(e.lights[0].irradiance.x, e.lights[1].irradiance.x);
    glm::dvec3 lights(0.0);
    for (const EnvironmentLight& l : e.lights) lights += glm::dvec3(l.irradiance);
    const glm::dvec3 before = integral(original), after = integral(map) + lights;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 1e-6 * before[c]);
    // The dimmest lamp stays in the map.
    EXPECT_EQ(map.rgba[(size_t(30) * 256 + 10) * 4], 20000.0f);
}

// No lamp: a uniform (furnace) map, a smooth sky and a black map give nothing and stay bit-identical.
TEST(IblLights, NothingIsExtractedWithoutALamp) {
    for (const ImageF& source : {uniformMap(64, 32, glm::vec3(1.0f)), smoothSky(128, 64), uniformMap(16, 8, glm::vec3(0.0f))}) {
        ImageF map = source;
        const LightExtraction e = extractEnvironmentLights(map, 10.0, 4, 100.0);
        EXPECT_TRUE(e.lights.empty());
        EXPECT_EQ(e.regions, 0);
        EXPECT_EQ(map.rgba, source.rgba);
        ASSERT_EQ(describeExtraction(e, 4).size(), 1u);
        EXPECT_NE(describeExtraction(e, 4)[0].find("no light extracted"), std::string::npos);
    }
}

// A bright region wider than the cap (an overcast patch, 1/8 of the sphere) is left to the prefilter;
// with extraction off (0 lights) even a lamp stays.
TEST(IblLights, WideRegionsAndExtractionOffLeaveTheMap) {
    ImageF map = uniformMap(128, 64, glm::vec3(0.1f));
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) setTexel(map, x, y, glm::vec3(100.0f));
    ImageF before = map;
    LightExtraction e = extractEnvironmentLights(map, 0.0, 4, 100.0);
    EXPECT_TRUE(e.lights.empty());
    EXPECT_EQ(e.tooLarge, 1);
    EXPECT_EQ(map.rgba, before.rgba);
    ImageF lamp = uniformMap(128, 64, glm::vec3(0.1f));
    setTexel(lamp, 5, 5, glm::vec3(5000.0f));
    before = lamp;
    e = extractEnvironmentLights(lamp, 0.0, 0, 100.0);
    EXPECT_TRUE(e.lights.empty());
    EXPECT_EQ(lamp.rgba, before.rgba);
}

// The bundled sky (hdr/sky.hdr, Preetham with a sun of about 34,000) yields its sun: above the horizon,
// carrying most of the map's energy (the sky alone is dim), within the solid-angle cap.
TEST(IblLights, BundledSkyGivesItsSun) {
    ImageF map = loadHdrImage(std::filesystem::path(LIGHTPASS_SOURCE_DIR) / "hdr/sky.hdr");
    const glm::dvec3 before = integral(map);
    const LightExtraction e = extractEnvironmentLights(map, 0.0, 4, 100.0);
    ASSERT_GE(e.lights.size(), 1u);
    EXPECT_GT(e.lights[0].direction.y, 0.0f);
    EXPECT_LT(e.lights[0].solidAngle, kMaxLightSolidAngleFraction * 4.0 * kPi);
    glm::dvec3 lights(0.0);
    for (const EnvironmentLight& l : e.lights) lights += glm::dvec3(l.irradiance);
    EXPECT_GT(lightLuminance(lights), 0.3 * lightLuminance(before));
    const glm::dvec3 after = integral(map) + lights;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 1e-6 * before[c]);
}

// The one equirectangular convention (engine/render/ibl_sh.hpp equirectDirection, the shaders'
// common/ibl.glsl likewise), by its directions written out: the centre column looks down -Z, u = 0.75
// is +X, 0.25 is -X, the edges +Z, the top row +Y. Seen from inside, the map reads as the flat image:
// for a viewer looking at any column (up +Y), the column to its right (larger u) lies on its right
// (forward x up), never mirrored. A positive rotation turns the map right-handed about +Y: +90
// degrees brings the centre column to -X.
TEST(EquirectConvention, CentreLooksDownMinusZAndReadsUnmirroredFromInside) {
    struct Case {
        double u, v;
        glm::dvec3 direction;
    };
    for (const Case& c : {Case{0.5, 0.5, {0, 0, -1}}, Case{0.75, 0.5, {1, 0, 0}}, Case{0.25, 0.5, {-1, 0, 0}},
                          Case{0.0, 0.5, {0, 0, 1}}, Case{1.0, 0.5, {0, 0, 1}}, Case{0.3, 0.0, {0, 1, 0}},
                          Case{0.8, 1.0, {0, -1, 0}}, Case{0.625, 0.25, {0.5, std::sqrt(0.5), -0.5}}}) {
        const glm::dvec3 d = equirectDirection(c.u, c.v);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], c.direction[k], 1e-12) << "u " << c.u << " v " << c.v;
    }
    for (int i = 0; i < 64; ++i) {
        const double u = (i + 0.5) / 64.0;
        const glm::dvec3 forward = equirectDirection(u, 0.5);
        const glm::dvec3 right = glm::cross(forward, glm::dvec3(0, 1, 0));
        EXPECT_GT(glm::dot(equirectDirection(u + 0.01, 0.5), right), 0.0) << "u " << u;
        EXPECT_LT(glm::dot(equirectDirection(u - 0.01, 0.5), right), 0.0) << "u " << u;
        EXPECT_GT(equirectDirection(u, 0.4).y, 0.0) << "u " << u;  // up the image is up
    }
    const glm::dvec3 turned = rotateY(equirectDirection(0.5, 0.5), kPi / 2.0);
    EXPECT_NEAR(turned.x, -1.0, 1e-12);
    EXPECT_NEAR(turned.z, 0.0, 1e-12);
}

// An asymmetric map: a lamp of 2 x 2 texels centred on (u, v) = (0.625, 0.25) of a 128 x 64 map, which
// is world (0.5, 0.707, -0.5): up, ahead and to the right of a viewer looking down -Z. The extracted
// light points there (within the 2 x 2 block's centroid error, 1 degree), and with the map rotated by
// +90 degrees to rotateY of it, (-0.5, 0.707, -0.5); the SH irradiance is larger facing the lamp than
// facing its mirror image (x negated), so no path mirrors it.
TEST(EquirectConvention, AsymmetricLampLandsAtItsWorldDirection) {
    const glm::dvec3 expected(0.5, std::sqrt(0.5), -0.5);
    for (double rotation : {0.0, 90.0}) {
        ImageF map = uniformMap(128, 64, glm::vec3(0.5f));
        for (int y : {15, 16})
            for (int x : {79, 80}) setTexel(map, x, y, glm::vec3(50000.0f));
        const ShCoefficients sh = projectEquirectSh(map, rotation);
        const LightExtraction e = extractEnvironmentLights(map, rotation, 4, 100.0);
        ASSERT_EQ(e.lights.size(), 1u);
        const glm::dvec3 want = rotation == 0.0 ? expected : glm::dvec3(-0.5, std::sqrt(0.5), -0.5);
        EXPECT_GT(glm::dot(glm::dvec3(e.lights[0].direction), want), std::cos(kPi / 180.0)) << "rotation " << rotation;
        const glm::dvec3 mirror(-want.x, want.y, want.z);
        EXPECT_GT(lightLuminance(shIrradiance(sh, want)), 1.5 * lightLuminance(shIrradiance(sh, mirror)))
            << "rotation " << rotation;
    }
}
