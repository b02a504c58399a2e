// CPU side of image-based lighting: SH irradiance against a brute-force integral for every
// HDR map in the shared assets, the bundled sky, the tone-map names and the IBL pass in the graph.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/io/image_io.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/ibl_sh.hpp"
#include "engine/render/ibl_environment.hpp"
#include "engine/core/error.hpp"

using namespace lp;

namespace {
constexpr double kPi = 3.14159265358979323846;

// The largest |order-2 SH approximation of max(cos, 0) - max(cos, 0)| over the angle: the kernel
// error that bounds E_sh - E for any non-negative radiance (about 0.094, at 90 degrees).
double kernelErrorMax() {
    double worst = 0.0;
    for (int i = 0; i <= 100000; ++i) {
        const double c = -1.0 + 2.0 * i / 100000.0;
        const double approx = 0.25 + 0.5 * c + 0.3125 * (1.5 * c * c - 0.5);
        worst = std::max(worst, std::abs(approx - std::max(c, 0.0)));
    }
    return worst;
}

std::string sourcePath(const std::string& relative) {
    return (std::filesystem::path(LIGHTPASS_SOURCE_DIR) / relative).string();
}
}  // namespace

// For every .hdr/.exr under the shared assets (skipped when absent), at 64 normals (a Fibonacci
// sphere), SH irradiance vs the brute-force double integral over the hemisphere (same texels).
// Bound (exact by the SH addition theorem): |E_sh(n) - E(n)| <= k * sum(L dOmega) per channel,
// k = max kernel error (0.094), times 1.0001 for the rounded SH constants. Clamping negative SH
// irradiance (sun-dominated maps ring below 0 on the far side, Filament #744) only moves E_sh
// towards E >= 0, so the bound holds after the clamp. The mean error is also recorded.
TEST(IblSh, IrradianceMatchesBruteForceForEveryAssetMap) {
    const std::filesystem::path root = LIGHTPASS_SHARED_ASSETS;
    if (!std::filesystem::exists(root)) GTEST_SKIP() << root << " absent";
    const double k = kernelErrorMax();
    EXPECT_NEAR(k, 0.0938, 0.001);
    int maps = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        const auto ext = entry.path().extension();
        if (ext != ".hdr" && ext != ".exr") continue;
        ImageF map = loadHdrImage(entry.path());
        ++maps;
        const ShCoefficients sh = projectEquirectSh(map, 30.0);
        glm::dvec3 total(0.0);  // sum of L dOmega
        for (int y = 0; y < map.height; ++y) {
            const double dOmega = (2.0 * kPi / map.width) * (kPi / map.height) * std::sin((y + 0.5) / map.height * kPi);
            for (int x = 0; x < map.width; ++x) {
                const float* p = &map.rgba[(size_t(y) * size_t(map.width) + size_t(x)) * 4];
                total += glm::dvec3(p[0], p[1], p[2]) * dOmega;
            }
        }
        double meanRel = 0.0;
        for (int i = 0; i < 64; ++i) {
            const double z = 1.0 - (i + 0.5) / 32.0, phi = i * 2.399963229728653, r = std::sqrt(1.0 - z * z);
            const glm::dvec3 n(r * std::cos(phi), z, r * std::sin(phi));
            const glm::dvec3 e = bruteForceIrradiance(map, 30.0, n), esh = shIrradiance(sh, n);
            for (int c = 0; c < 3; ++c) {
                EXPECT_LE(std::abs(esh[c] - e[c]), 1.0001 * k * total[c] + 1e-9) << entry.path() << " normal " << i;
                EXPECT_GE(esh[c], 0.0);
            }
            meanRel += std::abs(esh.y - e.y) / std::max(total.y / kPi, 1e-12);
        }
        RecordProperty(entry.path().filename().string(), std::to_string(meanRel / 64.0));
    }
    if (maps == 0) GTEST_SKIP() << "no maps under " << root;
}

// A uniform map of radiance 1: E = pi at every normal, by SH and by brute force. Bound: relative
// 5e-4 (the quadrature over 64 rows: the midpoint rule's (pi / 64)^2 / 24 = 1e-4 on sin(theta),
// the band-2 terms it leaves, texels the hemisphere's edge cuts).
TEST(IblSh, UniformMapGivesPi) {
    ImageF map;
    map.width = 128;
    map.height = 64;
    map.rgba.assign(size_t(128 * 64 * 4), 1.0f);
    const ShCoefficients sh = projectEquirectSh(map, 0.0);
    for (glm::dvec3 n : {glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::normalize(glm::dvec3(1, -2, 3))}) {
        EXPECT_NEAR(shIrradiance(sh, n).x, kPi, 5e-4 * kPi);
        EXPECT_NEAR(bruteForceIrradiance(map, 0.0, n).x, kPi, 5e-4 * kPi);
    }
}

// The bundled sky (scripts/make_sky.py): 1024 x 512, finite, non-negative; the .hdr (RGBE, 8-bit
// mantissa) and .exr (half) agree within 1% of each texel's largest component (+1e-4); the sun
// disk's irradiance (texels within 1 degree of the sun, cosine-weighted towards it, minus the sky
// there) is the generator's 4 W/m^2 within 2%.
TEST(IblSky, BundledSkyFilesAgreeAndCarryTheSun) {
    ImageF exr = loadHdrImage(sourcePath("hdr/sky.exr"));
    ImageF hdr = loadHdrImage(sourcePath("hdr/sky.hdr"));
    ASSERT_EQ(exr.width, 1024);
    ASSERT_EQ(exr.height, 512);
    ASSERT_EQ(hdr.width, 1024);
    ASSERT_EQ(hdr.height, 512);
    for (size_t i = 0; i < exr.rgba.size(); i += 4) {
        const float m = std::max({exr.rgba[i], exr.rgba[i + 1], exr.rgba[i + 2]});
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(exr.rgba[i + size_t(c)]));
            ASSERT_GE(exr.rgba[i + size_t(c)], 0.0f);
            ASSERT_NEAR(hdr.rgba[i + size_t(c)], exr.rgba[i + size_t(c)], 0.01 * m + 1e-4) << "texel " << i / 4;
        }
    }
    const glm::dvec3 sun = glm::normalize(glm::dvec3(0.25, 0.45, -1.0));
    double sunE = 0.0, skyNear = 0.0, nearOmega = 0.0;
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 1024; ++x) {
            const glm::dvec3 d = equirectDirection((x + 0.5) / 1024, (y + 0.5) / 512);
            const double c = glm::dot(d, sun);
            if (c < std::cos(1.0 * kPi / 180.0)) continue;
            const double dOmega = (2.0 * kPi / 1024) * (kPi / 512) * std::sin((y + 0.5) / 512 * kPi);
            const float* p = &exr.rgba[(size_t(y) * 1024 + size_t(x)) * 4];
            const double lum = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sunE += lum * c * dOmega;
            if (lum < 100.0) {  // texels the sun does not touch: the sky around it
                skyNear += lum * c * dOmega;
                nearOmega += dOmega;
            }
        }
    EXPECT_GT(nearOmega, 0.0);
    // The sun colour (1, 0.95, 0.85) has luminance 0.9626; subtract the sky under the sun texels.
    EXPECT_NEAR(sunE - skyNear, 4.0 * 0.9626, 0.02 * 4.0);
}

TEST(IblSettings, ToneMapNamesRoundTrip) {
    for (ToneMapOperator op : allToneMapOperators()) EXPECT_EQ(parseToneMap(toneMapName(op)), op);
    EXPECT_EQ(allToneMapOperators().size(), 5u);
    EXPECT_EQ(parseToneMap("aces-legacy"), ToneMapOperator::AcesLegacy);
    EXPECT_FALSE(parseToneMap("filmic").has_value());
    for (const char* v : {"environment", "irradiance", "prefiltered", "dfg"}) EXPECT_TRUE(parseView(v).has_value()) << v;
}

// The IBL pass is in the graph (after global_lights, before sky) only with --ibl and a map, and
// the environment views read only the G-buffer.
TEST(IblGraph, IblPassOnlyWithSwitchAndMap) {
    Scene scene;
    ModelInstance m;
    m.name = "box";
    m.mesh.boundsMin = glm::vec3(-1);
    m.mesh.boundsMax = glm::vec3(1);
    scene.models.push_back(m);
    auto build = [&](bool ibl, DebugView view) {
        RenderSettings settings;
        settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
        settings.autoExposure = false;       // and 0 EV
        settings.width = 64;
        settings.height = 48;
        settings.view = view;
        settings.environment.ibl = ibl;  // overrides the scene
        FrameData frame = makeFrameData(scene, settings, 0.0f);
        fg::FrameGraph g;
        PassStates passes;
        buildFrameGraph(g, passes, frame);
        g.compile();
        return g;
    };
    EXPECT_FALSE(build(true, DebugView::Final).hasPass("ibl"));  // no map
    scene.environment.map = "sky.exr";                           // never opened: the graph is only described
    EXPECT_FALSE(build(false, DebugView::Final).hasPass("ibl"));
    fg::FrameGraph g = build(true, DebugView::Final);
    ASSERT_TRUE(g.isLive("ibl"));
    auto order = g.executionOrder();
    auto pos = [&](const std::string& n) { return std::find(order.begin(), order.end(), n) - order.begin(); };
    EXPECT_LT(pos("global_lights"), pos("ibl"));
    EXPECT_LT(pos("ibl"), pos("sky"));
    EXPECT_LT(pos("ibl_bake"), pos("ibl"));  // nothing baked yet in a fresh state: the bake runs first
    for (DebugView v : {DebugView::Environment, DebugView::Irradiance, DebugView::Prefiltered, DebugView::Dfg})
        EXPECT_EQ(build(true, v).executionOrder(), (std::vector<std::string>{"ibl_bake", "gbuffer", "debug_view"}))
            << viewName(v);
}

// Settings that are each in range but do not fit together name the flags that hold them
// (`--env-size 4` alone used to say "specular size 256 must be ... [4, cube size 4]").
TEST(EnvironmentSettingsErrors, NameTheFlags) {
    auto errorOf = [](const EnvironmentSettings& s) -> std::string {
        try {
            validateEnvironmentSettings(s);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EnvironmentSettings s;
    EXPECT_EQ(errorOf(s), "");
    s.cubeSize = 4;
    EXPECT_EQ(errorOf(s), "environment settings: --ibl-specular-size 256 must be a power of two in [4, --env-size 4]");
    s = EnvironmentSettings{};
    s.specularSize = 4;
    EXPECT_EQ(errorOf(s), "environment settings: --ibl-specular-levels 6 must be in [1, 3] for --ibl-specular-size 4");
    s = EnvironmentSettings{};
    s.cubeSize = 100;
    EXPECT_EQ(errorOf(s), "environment settings: --env-size 100 must be a power of two in [4, 4096]");
}
