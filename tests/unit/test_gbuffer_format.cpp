// G-buffer layouts without GL: names and parsing, the defines that select them, and what the frame
// graph allocates for each (no position target when positions are rebuilt from depth; the bytes per
// pixel the README table states).
#include <gtest/gtest.h>

#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/frame_graph.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/scene/primitives.hpp"

using namespace lp;

TEST(GBufferFormat, NamesRoundTripAndUnknownNamesAreRejected) {
    for (GBufferNormalFormat f : allGBufferFormats()) EXPECT_EQ(parseGBufferFormat(gbufferFormatName(f)), f);
    for (GBufferPositionMode m : allGBufferPositionModes()) EXPECT_EQ(parseGBufferPosition(gbufferPositionName(m)), m);
    EXPECT_FALSE(parseGBufferFormat("oct12"));
    EXPECT_FALSE(parseGBufferPosition("reversed"));
    EXPECT_EQ(allGBufferFormats().size(), 7u);
    EXPECT_EQ(allGBufferPositionModes().size(), 3u);
}

TEST(GBufferFormat, EveryLayoutCompilesWithItsOwnDefines) {
    std::set<std::vector<std::string>> seen;
    for (GBufferNormalFormat f : allGBufferFormats())
        for (GBufferPositionMode m : allGBufferPositionModes()) seen.insert(gbufferDefines({f, m}));
    EXPECT_EQ(seen.size(), 21u);
}

// Table of the README (depth 4 + normal + diffuse 4 + specular + position): unpacked/stored 48 bytes,
// oct16/depth 18 bytes.
TEST(GBufferFormat, BytesPerPixel) {
    EXPECT_EQ(gbufferBytesPerPixel({}), 48);
    EXPECT_EQ(gbufferBytesPerPixel({GBufferNormalFormat::SeedPacked, GBufferPositionMode::Stored}), 36);
    EXPECT_EQ(gbufferBytesPerPixel({GBufferNormalFormat::TwoAngle, GBufferPositionMode::Depth}), 24);
    EXPECT_EQ(gbufferBytesPerPixel({GBufferNormalFormat::Oct16, GBufferPositionMode::Depth}), 18);
    EXPECT_EQ(gbufferBytesPerPixel({GBufferNormalFormat::Oct32, GBufferPositionMode::ReversedZ}), 20);
}

namespace {
Scene sphereScene() {
    Scene s;
    ModelInstance m;
    m.name = "sphere";
    m.primitive = "sphere";
    m.mesh = makeSphere(0.5f, 16, 8);
    s.models.push_back(std::move(m));
    DirectionalLight sun;
    s.directionalLights.push_back(sun);
    PointLight p;
    p.position = {0.0f, 1.0f, 0.0f};
    s.pointLights.push_back(p);
    s.camera.position = {0.0f, 0.5f, 3.0f};
    return s;
}
}  // namespace

// Rebuilt positions: no gbuffer.position resource in the compiled graph (the toon and every light
// pass still run); the live G-buffer textures add up to gbufferBytesPerPixel, for all 21 layouts.
TEST(GBufferFormat, RebuiltPositionsAllocateNoPositionTarget) {
    const Scene scene = sphereScene();
    for (GBufferNormalFormat f : allGBufferFormats())
        for (GBufferPositionMode m : allGBufferPositionModes()) {
            RenderSettings settings;
            settings.aa.method = AntiAliasing::Off;  // one sample a pixel, as the references
            settings.autoExposure = false;       // and 0 EV
            settings.width = 64;
            settings.height = 48;
            settings.gbuffer = {f, m};
            settings.post.toon = true;
            FrameData frame = makeFrameData(scene, settings, 0.0f);
            fg::FrameGraph g;
            PassStates passes;
            buildFrameGraph(g, passes, frame);
            g.compile();
            bool hasPosition = false;
            size_t bytes = 0;
            for (const auto& r : g.resources()) {
                if (r.name == "gbuffer.position") hasPosition = true;
                if (r.name.rfind("gbuffer.", 0) == 0 && r.live) bytes += r.desc.bytes();
            }
            const std::string name = std::string(gbufferFormatName(f)) + "/" + gbufferPositionName(m);
            EXPECT_EQ(hasPosition, m == GBufferPositionMode::Stored) << name;
            EXPECT_EQ(bytes, size_t(gbufferBytesPerPixel({f, m})) * 64u * 48u) << name;
            for (const char* pass : {"global_lights", "local_lights", "toon", "sky"}) EXPECT_TRUE(g.isLive(pass)) << name << " " << pass;
        }
}

// The base colour's 8-bit storage is sRGB, as its textures are, in every layout and both G-buffer
// modes: the live gbuffer.diffuse (kd) is SRGB8_A8, and gbuffer.specular (F0) SRGB8_A8 in the seed
// formats (8-bit colour) or RGBA16F (11 significant bits) in the others: the two storages
// GBufferFormats.EverySrgbBaseColourCodeRoundTripsInEveryLayoutAndMode renders every code through.
TEST(GBufferFormat, BaseColourIsSrgbOrHalfFloatInEveryLayoutAndMode) {
    const Scene scene = sphereScene();
    for (GBufferNormalFormat f : allGBufferFormats())
        for (GBufferPositionMode m : allGBufferPositionModes())
            for (GBufferMode mode : allGBufferModes()) {
                RenderSettings settings;
                settings.width = 64;
                settings.height = 48;
                settings.gbuffer = {f, m, mode};
                FrameData frame = makeFrameData(scene, settings, 0.0f);
                fg::FrameGraph g;
                PassStates passes;
                buildFrameGraph(g, passes, frame);
                g.compile();
                const std::string name =
                    std::string(gbufferFormatName(f)) + "/" + gbufferPositionName(m) + " " + gbufferModeName(mode);
                int checked = 0;
                for (const auto& r : g.resources()) {
                    if (!r.live) continue;
                    if (r.name == "gbuffer.diffuse") {
                        EXPECT_EQ(r.desc.format, GLenum(GL_SRGB8_ALPHA8)) << name;
                        ++checked;
                    }
                    if (r.name == "gbuffer.specular") {
                        EXPECT_EQ(r.desc.format, shininessInNormalTarget(f) ? GLenum(GL_SRGB8_ALPHA8) : GLenum(GL_RGBA16F))
                            << name;
                        ++checked;
                    }
                }
                EXPECT_EQ(checked, 2) << name;
                EXPECT_EQ(g.isLive("gbuffer_resolve"), mode == GBufferMode::Visibility) << name;
            }
}

// --light-range-scale: every light's range is scaled (shading, scissor, volumes and tiles agree).
TEST(GBufferFormat, LightRangeScaleScalesEveryRange) {
    const Scene scene = sphereScene();
    LocalLightSettings s;
    const float full = localLightsForFrame(scene, s, 0.0f)[0].range;
    s.rangeScale = 0.25f;
    EXPECT_FLOAT_EQ(localLightsForFrame(scene, s, 0.0f)[0].range, 0.25f * full);
}
