// The environment a model or scene is lit by (no GL): a bare --model gets the bundled studio map with
// IBL on and its key and fill light only on frames without IBL; --env FILE|none replaces any scene's
// environment; the viewer's picker turns IBL on; the bundled studio map is small, neutral and lit
// from above; the graph of each case has the passes that light it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "app/cli.hpp"
#include "app/environment_pick.hpp"
#include "engine/core/error.hpp"
#include "engine/render/ibl_lights.hpp"
#include "engine/render/ibl_sh.hpp"
#include "frame/frame_builder.hpp"
#include "engine/scene/scene_loader.hpp"

using namespace lp;

namespace {

const std::filesystem::path kSource = LIGHTPASS_SOURCE_DIR;

const Scene& bareModel() {  // models/pbr_spheres.glb: ten spheres, no KHR_lights_punctual
    static const Scene scene = sceneForModel(kSource / "models/pbr_spheres.glb");
    return scene;
}

// Candidate passes that run in the graph of `scene` under `settings`, and why the others do not.
struct Passes {
    std::set<std::string> runs;
    std::map<std::string, std::string> skipped;
};
Passes passes(const Scene& scene, const RenderSettings& settings) {
    FrameData frame = makeFrameData(scene, settings, 0.0f);
    fg::FrameGraph graph;
    PassStates states;
    buildFrameGraph(graph, states, frame);
    graph.compile();
    Passes p;
    for (const fg::PassDecision& d : graph.explain()) {
        if (d.runs) p.runs.insert(d.name);
        else p.skipped[d.name] = d.reason;
    }
    return p;
}

RenderSettings small() {
    RenderSettings s;
    s.width = 160;
    s.height = 90;
    return s;
}

}  // namespace

// A model without lights of its own: the studio map with IBL on, no directional light and no ambient
// of its own (the map is its light), and a key (casting shadows) and a fill for frames without IBL.
TEST(ModelEnvironment, BareModelIsLitByTheBundledStudio) {
    const Scene& s = bareModel();
    EXPECT_EQ(s.environment.map, studioEnvironmentPath());
    EXPECT_TRUE(std::filesystem::is_regular_file(s.environment.map)) << s.environment.map;
    EXPECT_TRUE(s.environment.ibl);
    EXPECT_TRUE(s.directionalLights.empty());
    EXPECT_EQ(s.ambient, glm::vec3(0.0f));
    ASSERT_TRUE(s.lightsWithoutIbl.has_value());
    ASSERT_EQ(s.lightsWithoutIbl->directionalLights.size(), 2u);
    EXPECT_TRUE(s.lightsWithoutIbl->directionalLights[0].castsShadows);
    EXPECT_GT(s.lightsWithoutIbl->ambient.x, 0.0f);
}

// A glTF with KHR_lights_punctual keeps its own lights and gets no environment.
TEST(ModelEnvironment, ModelWithItsOwnLightsGetsNoEnvironment) {
    const Scene s = sceneForModel(kSource / "tests/data/gltf/lights.gltf");
    EXPECT_TRUE(s.environment.map.empty());
    EXPECT_FALSE(s.environment.ibl);
    EXPECT_FALSE(s.lightsWithoutIbl.has_value());
    EXPECT_FALSE(s.pointLights.empty() && s.directionalLights.empty());
}

// The lights a frame shades with: the map while IBL lights it, the key and fill when it does not
// (IBL switched off, or no map), and a scene without lightsWithoutIbl keeps its own either way.
TEST(ModelEnvironment, KeyAndFillOnlyOnFramesWithoutIbl) {
    Scene s = bareModel();
    RenderSettings on = small();
    FrameData f = makeFrameData(s, on, 0.0f);
    EXPECT_TRUE(iblLightsFrame(s, on));
    EXPECT_TRUE(frameDirectionalLights(f).empty());
    EXPECT_EQ(frameAmbient(f), glm::vec3(0.0f));

    RenderSettings off = small();
    off.environment.ibl = false;  // --brdf-only
    f = makeFrameData(s, off, 0.0f);
    EXPECT_EQ(frameDirectionalLights(f).size(), 2u);
    EXPECT_EQ(frameAmbient(f), s.lightsWithoutIbl->ambient);

    replaceEnvironment(s, {});  // --env none
    f = makeFrameData(s, on, 0.0f);
    EXPECT_FALSE(iblLightsFrame(s, on));
    EXPECT_EQ(frameDirectionalLights(f).size(), 2u);

    Scene cornell = loadScene(kSource / "scenes/cornell.json");
    replaceEnvironment(cornell, {});
    f = makeFrameData(cornell, on, 0.0f);
    EXPECT_EQ(frameDirectionalLights(f).size(), cornell.directionalLights.size());
    EXPECT_EQ(frameAmbient(f), cornell.ambient);
}

// A scene's constant ambient stands in for indirect light: a frame that IBL lights adds none (the
// environment's irradiance is that light), the same scene without IBL keeps it.
TEST(ModelEnvironment, ConstantAmbientOnlyOnFramesWithoutIbl) {
    const Scene cornell = loadScene(kSource / "scenes/cornell.json");
    ASSERT_FALSE(cornell.environment.map.empty());
    ASSERT_GT(cornell.ambient.x, 0.0f);
    RenderSettings ibl = small();
    ibl.environment.ibl = true;
    FrameData f = makeFrameData(cornell, ibl, 0.0f);
    EXPECT_EQ(frameAmbient(f), glm::vec3(0.0f));
    RenderSettings analytic = small();
    analytic.environment.ibl = false;
    f = makeFrameData(cornell, analytic, 0.0f);
    EXPECT_EQ(frameAmbient(f), cornell.ambient);
}

// The graph: a bare model runs the bake, the IBL and the sky and no shadow map (no sun); --env none
// swaps in the sun's shadow map and drops IBL; --brdf-only keeps the sky, drops IBL, adds the sun.
TEST(ModelEnvironment, GraphLightsTheModelEitherWay) {
    Scene s = bareModel();
    Passes p = passes(s, small());
    for (const char* pass : {"ibl_bake", "ibl", "sky", "global_lights"}) EXPECT_TRUE(p.runs.count(pass)) << pass;
    EXPECT_EQ(p.skipped["shadow_map"], "skipped: no directional light casts shadows");

    RenderSettings off = small();
    off.environment.ibl = false;
    p = passes(s, off);
    EXPECT_TRUE(p.runs.count("shadow_map_0"));
    EXPECT_TRUE(p.runs.count("sky"));
    EXPECT_FALSE(p.runs.count("ibl"));

    replaceEnvironment(s, {});
    p = passes(s, small());
    EXPECT_TRUE(p.runs.count("shadow_map_0"));
    EXPECT_EQ(p.skipped["ibl"], "skipped: scene has no environment map");
}

// --env: none removes map and IBL; a file replaces the map, turns IBL on, at intensity 1 and rotation
// 0; a missing file and a non-HDR name are one-line errors naming the flag and the file.
TEST(ModelEnvironment, EnvFlagReplacesAnyScenesEnvironment) {
    const std::string cornell = (kSource / "scenes/cornell.json").string();
    const std::string studio = (kSource / "hdr/studio.exr").string();
    app::Options o = app::parseArgs({"render", "--scene", cornell, "--out", "x.png", "--env", "none"});
    ASSERT_TRUE(o.environment.has_value());
    EXPECT_TRUE(o.environment->empty());
    Scene s = app::sceneFromOptions(o);
    EXPECT_TRUE(s.environment.map.empty());
    EXPECT_FALSE(s.environment.ibl);

    o = app::parseArgs({"render", "--scene", cornell, "--out", "x.png", "--env", studio});
    EXPECT_EQ(*o.environment, studio);
    s = app::sceneFromOptions(o);
    EXPECT_EQ(s.environment.map, studio);
    EXPECT_TRUE(s.environment.ibl);
    EXPECT_EQ(s.environment.intensity, 1.0f);
    EXPECT_EQ(s.environment.rotationDegrees, 0.0f);
    EXPECT_FALSE(s.directionalLights.empty()) << "the scene keeps its own lights";

    o = app::parseArgs({"render", "--model", (kSource / "models/pbr_spheres.glb").string(), "--out", "x.png", "--env",
                        (kSource / "hdr/sky.hdr").string()});
    s = app::sceneFromOptions(o);
    EXPECT_EQ(s.environment.map, kSource / "hdr/sky.hdr");
    EXPECT_TRUE(s.environment.ibl);

    auto errorOf = [&](const std::string& env) {
        try {
            app::parseArgs({"render", "--scene", cornell, "--out", "x.png", "--env", env});
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(errorOf("/nonexistent/map.exr"), "--env /nonexistent/map.exr: file not found");
    EXPECT_EQ(errorOf("picture.png"), "--env picture.png: expected an .hdr or .exr map, or none");
}

// The viewer's picker: a map turns IBL on (the scene's switch, and the knob where it was off);
// "plain colour" leaves IBL as it was; a failed map puts everything back.
TEST(ModelEnvironment, PickingAMapTurnsIblOn) {
    Scene s = loadScene(kSource / "scenes/cornell.json");  // its sky map, IBL off
    ASSERT_FALSE(s.environment.ibl);
    const std::filesystem::path sky = s.environment.map;
    RenderSettings settings;
    app::EnvironmentBefore before = app::pickEnvironment(s, settings, kSource / "hdr/studio.exr");
    EXPECT_TRUE(s.environment.ibl);
    EXPECT_FALSE(settings.environment.ibl.has_value()) << "an unset knob follows the scene";
    EXPECT_TRUE(iblLightsFrame(s, settings));
    app::restoreEnvironment(s, settings, before);
    EXPECT_EQ(s.environment.map, sky);
    EXPECT_FALSE(s.environment.ibl);

    settings.environment.ibl = false;  // switched off in the panel
    app::pickEnvironment(s, settings, kSource / "hdr/studio.exr");
    EXPECT_EQ(settings.environment.ibl, std::optional<bool>(true));

    Scene m = bareModel();
    RenderSettings mine;
    app::pickEnvironment(m, mine, {});  // plain colour
    EXPECT_TRUE(m.environment.map.empty());
    EXPECT_FALSE(iblLightsFrame(m, mine));
    EXPECT_EQ(frameDirectionalLights(makeFrameData(m, mine, 0.0f)).size(), 2u) << "the key and fill take over";
}

// hdr/studio.exr (scripts/make_studio.py): small, grey (R = G = B everywhere), lit from above (a
// surface facing up receives about 3, as from the key light without an environment; facing down,
// the floor's light, well under half of that), and its softboxes are too wide for light extraction,
// so the whole map lights through the cube and the SH.
TEST(ModelEnvironment, BundledStudioIsSmallNeutralAndLitFromAbove) {
    const std::filesystem::path file = studioEnvironmentPath();
    EXPECT_LT(std::filesystem::file_size(file), 300u * 1024u);
    ImageF map = loadHdrImage(file);
    EXPECT_EQ(map.width, 2 * map.height);
    for (size_t i = 0; i < map.rgba.size(); i += 4) {
        ASSERT_EQ(map.rgba[i], map.rgba[i + 1]) << "texel " << i / 4;
        ASSERT_EQ(map.rgba[i], map.rgba[i + 2]) << "texel " << i / 4;
        ASSERT_GT(map.rgba[i], 0.0f) << "texel " << i / 4;
    }
    const double up = bruteForceIrradiance(map, 0.0, {0, 1, 0}).x, down = bruteForceIrradiance(map, 0.0, {0, -1, 0}).x;
    EXPECT_GT(up, 2.5);
    EXPECT_LT(up, 3.5);
    EXPECT_GT(down, 0.1 * up);
    EXPECT_LT(down, 0.4 * up);
    // The key is in front of the model, above and to the camera's left (-X): the side facing it gets
    // more light than the side facing away.
    EXPECT_GT(bruteForceIrradiance(map, 0.0, {-1, 0, 0}).x, bruteForceIrradiance(map, 0.0, {1, 0, 0}).x);
    EXPECT_GT(bruteForceIrradiance(map, 0.0, {0, 0, 1}).x, bruteForceIrradiance(map, 0.0, {0, 0, -1}).x);
    const LightExtraction e = extractEnvironmentLights(map, 0.0, EnvironmentSettings{}.extractLights,
                                                       EnvironmentSettings{}.extractThreshold);
    EXPECT_TRUE(e.lights.empty());
}

// A turning sun ("turn"): every pass reads the direction at the frame's time, and a still sun's
// frame keeps the file's direction bit for bit.
TEST(ModelEnvironment, FramesShadeATurningSunAtTheirTime) {
    Scene s;
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.turnSpeed = 0.25f;
    s.directionalLights = {sun, sun};
    s.directionalLights[1].turnSpeed = 0.0f;
    const RenderSettings settings = small();
    for (float t : {0.0f, 1.0f, 7.5f}) {
        const std::vector<DirectionalLight> suns = frameDirectionalLights(makeFrameData(s, settings, t));
        ASSERT_EQ(suns.size(), 2u);
        EXPECT_NEAR(glm::length(suns[0].direction - sun.directionAt(t)), 0.0f, 1e-6f) << "t = " << t;
        EXPECT_NEAR(glm::dot(suns[0].direction, glm::vec3(0, 1, 0)), sun.direction.y, 1e-6f) << "the height stays";
        EXPECT_EQ(suns[0].turnSpeed, 0.0f) << "the frame's copy is the still direction at t";
        EXPECT_EQ(suns[1].direction, sun.direction) << "t = " << t;
    }
    // Half a radian about +Y moves the direction by the chord 2 h sin(0.25), h its horizontal length.
    const float h = glm::length(glm::vec2(sun.direction.x, sun.direction.z));
    EXPECT_NEAR(glm::length(frameDirectionalLights(makeFrameData(s, settings, 2.0f))[0].direction - sun.direction),
                2.0f * h * std::sin(0.25f), 1e-5f);
}
