// --shadow-cache: a kept cascade tile is exactly what a redraw would write; a scrolled one
// (--shadow-scroll) is within kShadowScrollDepthTolerance of it but for a few texels at silhouettes. The same frames are
// drawn by one ShadowMapPass kept across them (cache on) and by a fresh one with the cache off; their
// cascade tiles must agree bit for bit while the camera moves, the sun turns or a caster moves, and
// the cache must have kept some tiles and redrawn others (or the comparison proves nothing).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/spin.hpp"
#include "frame/frame_builder.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

using namespace lp;

namespace {

// A 12 m floor with boxes and spheres spread over it under a tilted sun; the camera looks along
// the row from one end, so the near cascades cover part of it and the far ones the rest.
Scene castersOnAFloor() {
    Scene s;
    ModelInstance floor;
    floor.name = "floor";
    floor.mesh = makePlane(12.0f, 4);
    s.models.push_back(std::move(floor));
    std::mt19937 rng(77);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int i = 0; i < 10; ++i) {
        ModelInstance m;
        m.name = "caster" + std::to_string(i);
        m.mesh = i % 2 == 0 ? makeSphere(0.3f + 0.05f * float(i % 3), 12, 8) : makeCube(0.6f);
        m.transform = glm::translate(glm::mat4(1.0f), glm::vec3(4.0f * unit(rng), 0.5f + 0.3f * unit(rng), 5.0f * unit(rng))) *
                      glm::rotate(glm::mat4(1.0f), 3.0f * unit(rng), glm::normalize(glm::vec3(unit(rng), 1.0f, unit(rng))));
        s.models.push_back(std::move(m));
    }
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    s.directionalLights.push_back(sun);
    s.camera.position = glm::vec3(0.0f, 1.6f, 6.0f);
    s.camera.target = glm::vec3(0.0f, 0.6f, 0.0f);
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 40.0f;
    return s;
}

RenderSettings smallCascades(ShadowSettings::Raster raster) {
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.shadows.size = 256;
    s.shadows.cascades = 4;
    s.shadows.raster = raster;
    // Resized squares drawn whole at once: each frame's tiles compare bit for bit with a fresh
    // redraw of the same frusta (--shadow-redraw-budget's lag is tested on its own).
    s.shadows.redrawBudget = 0;
    return s;
}

// The cascade tiles of light 0's atlas, tile by tile (the atlas's unused tile left out).
struct Tiles {
    std::vector<std::vector<float>> depth;
};

// Draws one frame's shadow passes with `state` and cuts the cascade tiles out of the atlas.
Tiles drawTiles(const Scene& scene, const SceneGpu& gpu, const RenderSettings& settings, ShadowMapPass& state,
                fg::TexturePool& pool, std::vector<std::string>* notes = nullptr, float time = 0.0f) {
    const test::ShadowAtlasFrame atlas = test::drawShadowAtlas(scene, gpu, settings, state, pool, time);
    if (notes) *notes = atlas.notes;
    const ShadowFrustum& fr = atlas.frustum;
    const size_t side = size_t(fr.tileSize), width = side * size_t(fr.columns);
    Tiles t;
    for (size_t c = 0; c < fr.cascades.size(); ++c) {
        const size_t at = size_t(fr.cascades[c].tile);
        const size_t x0 = (at % size_t(fr.columns)) * side, y0 = (at / size_t(fr.columns)) * side;
        std::vector<float> tile;
        tile.reserve(side * side);
        for (size_t y = 0; y < side; ++y)
            tile.insert(tile.end(), atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0),
                        atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0 + side));
        t.depth.push_back(std::move(tile));
    }
    return t;
}

// The same frame drawn from scratch: a fresh pass state, the cache off.
Tiles redrawnTiles(const Scene& scene, const SceneGpu& gpu, RenderSettings settings, float time = 0.0f) {
    settings.shadows.cache = false;
    ShadowMapPass fresh;
    fg::TexturePool pool;
    return drawTiles(scene, gpu, settings, fresh, pool, nullptr, time);
}

void expectSameTiles(const Tiles& kept, const Tiles& redrawn, const std::string& what) {
    ASSERT_EQ(kept.depth.size(), redrawn.depth.size()) << what;
    for (size_t c = 0; c < kept.depth.size(); ++c) {
        ASSERT_EQ(kept.depth[c].size(), redrawn.depth[c].size());
        size_t differing = 0, casters = 0;
        for (size_t i = 0; i < kept.depth[c].size(); ++i) {
            differing += std::memcmp(&kept.depth[c][i], &redrawn.depth[c][i], sizeof(float)) != 0 ? 1 : 0;
            casters += redrawn.depth[c][i] < 1.0f ? 1 : 0;
        }
        EXPECT_EQ(differing, 0u) << what << ": cascade " << c << " differs from a full redraw in " << differing << " texels";
        EXPECT_GT(casters, 0u) << what << ": cascade " << c << " holds no caster (the comparison would prove little)";
    }
}

size_t countNotes(const std::vector<std::string>& notes, const std::string& text) {
    size_t n = 0;
    for (const std::string& note : notes) n += note.find(text) != std::string::npos ? 1 : 0;
    return n;
}

}  // namespace

// The camera walks along the row: every frame's kept atlas equals a full redraw, and along the walk
// some tiles were kept and some redrawn. Every raster, since each draws tiles its own way; conservative
// and split grown by the geometry shader and, where the GPU has it, by the hardware conservative raster.
TEST(ShadowCache, KeptTilesEqualAFullRedrawOnAMovingCamera) {
    using Conservative = ShadowSettings::ConservativeRaster;
    std::vector<std::pair<ShadowSettings::Raster, Conservative>> cases;
    for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Plain, ShadowSettings::Raster::Conservative,
                                          ShadowSettings::Raster::Split, ShadowSettings::Raster::Compute})
        cases.emplace_back(raster, Conservative::GeometryShader);
    if (queryConservativeRasterSupport().hardware)
        for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split})
            cases.emplace_back(raster, Conservative::Hardware);
    for (const auto& [raster, conservative] : cases) {
        const std::string name =
            std::string(ShadowSettings::rasterName(raster)) + " (" + ShadowSettings::conservativeRasterName(conservative) + ")";
        Scene scene = castersOnAFloor();
        SceneGpu gpu(scene);
        RenderSettings settings = smallCascades(raster);
        settings.shadows.conservativeRaster = conservative;
        settings.shadows.scroll = false;  // moved tiles redrawn whole: every tile bit for bit (scrolling: below)
        ShadowMapPass state;
        fg::TexturePool pool;
        std::vector<std::string> notes;
        drawTiles(scene, gpu, settings, state, pool, &notes);
        EXPECT_EQ(countNotes(notes, "redrawn (nothing kept yet)"), notes.size()) << name;
        const uint64_t firstDrawn = state.cacheStats.drawn;
        EXPECT_EQ(state.cacheStats.kept, 0u);
        // The same camera again: everything kept.
        drawTiles(scene, gpu, settings, state, pool, &notes);
        EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << name;
        EXPECT_EQ(state.cacheStats.drawn, firstDrawn) << name;
        for (int step = 1; step <= 6; ++step) {
            scene.camera.position += glm::vec3(0.02f, 0.0f, -0.35f);
            scene.camera.target += glm::vec3(0.02f, 0.0f, -0.35f);
            const Tiles kept = drawTiles(scene, gpu, settings, state, pool);
            expectSameTiles(kept, redrawnTiles(scene, gpu, settings), name + " step " + std::to_string(step));
        }
        EXPECT_GT(state.cacheStats.kept, firstDrawn) << name << ": the walk kept (almost) nothing";
        EXPECT_GT(state.cacheStats.drawn, firstDrawn) << name << ": the walk redrew nothing: the camera did not move the cascades";
    }
}

// What a tile's depth depends on outside the camera invalidates it: the sun's direction, a caster's
// transform, the slope bias, the raster and which conservative raster grew the casters. Each change
// redraws, and the result equals a full redraw.
TEST(ShadowCache, SunGeometryAndSettingsInvalidate) {
    Scene scene = castersOnAFloor();
    SceneGpu gpu(scene);
    RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    ShadowMapPass state;
    fg::TexturePool pool;
    std::vector<std::string> notes;
    drawTiles(scene, gpu, settings, state, pool);
    drawTiles(scene, gpu, settings, state, pool, &notes);
    ASSERT_EQ(countNotes(notes, "kept (unchanged)"), notes.size());

    auto expectRedrawn = [&](const std::string& what, const std::string& reason) {
        const Tiles kept = drawTiles(scene, gpu, settings, state, pool, &notes);
        EXPECT_EQ(countNotes(notes, "redrawn (" + reason + ")"), notes.size()) << what << ": " << notes[0];
        expectSameTiles(kept, redrawnTiles(scene, gpu, settings), what);
        drawTiles(scene, gpu, settings, state, pool, &notes);  // unchanged again: kept
        EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << what << " (the frame after)";
    };
    scene.directionalLights[0].direction = glm::normalize(glm::vec3(0.45f, -1.0f, 0.3f));
    expectRedrawn("sun turned", "light matrix changed");
    // A caster moves (its GPU model matrix, what the pass draws with) by a few centimetres.
    const glm::mat4 nudge = glm::translate(glm::mat4(1.0f), glm::vec3(0.05f, 0.0f, 0.0f));
    gpu.meshes[3].model = nudge * gpu.meshes[3].model;
    scene.models[3].transform = nudge * scene.models[3].transform;
    expectRedrawn("a caster moved", "casters changed");
    settings.shadows.slopeBias = 2.0f;
    expectRedrawn("slope bias", "slope bias changed");
    settings.shadows.raster = ShadowSettings::Raster::Conservative;
    expectRedrawn("raster", "caster raster changed");
    // Hardware and geometry-shader growth write slightly different depths: switching redraws, but only
    // where the raster actually used changes (without the hardware both settings use the shader).
    settings.shadows.conservativeRaster = ShadowSettings::ConservativeRaster::GeometryShader;
    if (queryConservativeRasterSupport().hardware) {
        expectRedrawn("geometry-shader growth", "conservative raster changed to geometry shader");
        settings.shadows.conservativeRaster = ShadowSettings::ConservativeRaster::Hardware;
        expectRedrawn("hardware growth", "conservative raster changed to hardware");
    } else {
        const Tiles kept = drawTiles(scene, gpu, settings, state, pool, &notes);
        EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << "auto -> geometry-shader without the hardware";
        expectSameTiles(kept, redrawnTiles(scene, gpu, settings), "auto -> geometry-shader without the hardware");
    }
}

// A turning sun ("turn"): no cascade holds from one frame to the next, each frame's tiles equal a fresh
// redraw at that time, and the same time drawn again keeps them.
TEST(ShadowCache, ATurningSunRedrawsEveryFrame) {
    Scene scene = castersOnAFloor();
    scene.directionalLights[0].turnSpeed = 0.2f;
    SceneGpu gpu(scene);
    const RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    ShadowMapPass state;
    fg::TexturePool pool;
    std::vector<std::string> notes;
    drawTiles(scene, gpu, settings, state, pool, &notes, 0.0f);
    for (float t : {0.05f, 0.1f, 0.5f}) {
        const Tiles kept = drawTiles(scene, gpu, settings, state, pool, &notes, t);
        EXPECT_EQ(countNotes(notes, "redrawn (light matrix changed)"), notes.size()) << "t = " << t << ": " << notes[0];
        expectSameTiles(kept, redrawnTiles(scene, gpu, settings, t), "turning sun at t = " + std::to_string(t));
    }
    drawTiles(scene, gpu, settings, state, pool, &notes, 0.5f);
    EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << "the same time again: " << notes[0];
}

// A spinning caster ("spin"): its cascades are redrawn each frame it turns, equal to a fresh redraw.
TEST(ShadowCache, ASpinningCasterRedrawsTheCascadesItCrosses) {
    Scene scene = castersOnAFloor();
    ModelInstance& spinner = scene.models[2];
    spinner.animation = std::make_shared<const NodeAnimation>(spinAnimation(spinner.mesh, glm::vec3(0, 1, 0), 0.7f));
    spinner.playingClips = {0};
    SceneGpu gpu(scene);
    const RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    ShadowMapPass state;
    fg::TexturePool pool;
    std::vector<std::string> notes;
    gpu.pose(scene, 0.0, 0.0, settings.skinning);  // what the renderer does before each frame's graph
    drawTiles(scene, gpu, settings, state, pool, &notes, 0.0f);
    float previous = 0.0f;
    for (float t : {0.1f, 0.3f}) {
        gpu.pose(scene, t, previous, settings.skinning);
        previous = t;
        const Tiles kept = drawTiles(scene, gpu, settings, state, pool, &notes, t);
        EXPECT_GT(countNotes(notes, "redrawn (casters changed)"), 0u) << "t = " << t << ": " << notes[0];
        expectSameTiles(kept, redrawnTiles(scene, gpu, settings, t), "spinning caster at t = " + std::to_string(t));
    }
    gpu.pose(scene, 0.3, 0.3, settings.skinning);
    drawTiles(scene, gpu, settings, state, pool, &notes, 0.3f);
    EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << "the same time again: " << notes[0];
}

// The key alone: two tiles that differ only in how the casters were grown are not the same tile.
TEST(ShadowCache, ConservativeRasterIsPartOfTheTileKey) {
    ShadowFrustum fr;
    fr.tileSize = 64;
    fr.columns = 2;
    fr.rows = 1;
    fr.cascades.resize(2);
    fr.cascades[1].tile = 1;
    ShadowSettings settings;
    for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split}) {
        ShadowAtlasCache cache;
        cache.depth = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, 128, 64, 1, "test_kept_atlas");
        cache.width = 128;
        cache.height = 64;
        cache.casters = 7;
        for (const ShadowTileKey& k : shadowTileKeys(fr, settings, raster, false)) cache.tiles.push_back(k);
        for (const ShadowTileReason& why : shadowTilesToDraw(&cache, 128, 64, 7, shadowTileKeys(fr, settings, raster, false)))
            EXPECT_TRUE(why.kept()) << why.text;
        for (const ShadowTileReason& why : shadowTilesToDraw(&cache, 128, 64, 7, shadowTileKeys(fr, settings, raster, true))) {
            EXPECT_EQ(why.change, ShadowTileChange::ConservativeRasterChanged) << ShadowSettings::rasterName(raster);
            EXPECT_EQ(why.text, "conservative raster changed to hardware") << ShadowSettings::rasterName(raster);
        }
    }
    // Plain and compute grow nothing: the hardware's presence does not touch their tiles.
    for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Plain, ShadowSettings::Raster::Compute})
        EXPECT_EQ(shadowTileKeys(fr, settings, raster, true), shadowTileKeys(fr, settings, raster, false));
}

// --shadow-cache off: every cascade drawn every frame, and said so.
TEST(ShadowCache, OffDrawsEveryCascadeEveryFrame) {
    Scene scene = castersOnAFloor();
    SceneGpu gpu(scene);
    RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    settings.shadows.cache = false;
    ShadowMapPass state;
    fg::TexturePool pool;
    std::vector<std::string> notes;
    for (int i = 0; i < 2; ++i) drawTiles(scene, gpu, settings, state, pool, &notes);
    EXPECT_EQ(countNotes(notes, "redrawn (cache off)"), notes.size());
    EXPECT_EQ(state.cacheStats.kept, 0u);
    EXPECT_EQ(state.cacheStats.drawn, 2 * notes.size());
    EXPECT_TRUE(state.atlases.empty());
}

namespace {

// Whether texel i of a side x side tile lies next to a depth edge of `tile`: a caster's silhouette
// (a neighbour holds no caster where it does, or the reverse) or a step between casters larger than
// `step` within its 3x3 neighbourhood.
bool nextToDepthEdge(const std::vector<float>& tile, size_t side, size_t i, float step) {
    const int x = int(i % side), y = int(i / side);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= int(side) || ny >= int(side)) continue;
            const float a = tile[i], b = tile[size_t(ny) * side + size_t(nx)];
            if ((a < 1.0f) != (b < 1.0f) || std::abs(a - b) > step) return true;
        }
    return false;
}

struct ScrollDifference {
    size_t differing = 0;      // texels not bit-identical to the fresh redraw
    size_t beyond = 0;         // texels farther than kShadowScrollDepthTolerance from it
    size_t awayFromEdges = 0;  // of those, texels with no depth edge next to them
    double largestWithin = 0.0;  // largest difference within the tolerance
};

ScrollDifference compareScrolled(const std::vector<float>& scrolled, const std::vector<float>& fresh, size_t side) {
    ScrollDifference d;
    for (size_t i = 0; i < fresh.size(); ++i) {
        if (std::memcmp(&scrolled[i], &fresh[i], sizeof(float)) == 0) continue;
        ++d.differing;
        const double difference = std::abs(double(scrolled[i]) - double(fresh[i]));
        if (difference <= double(kShadowScrollDepthTolerance)) {
            d.largestWithin = std::max(d.largestWithin, difference);
            continue;
        }
        ++d.beyond;
        // A step of 1e-4 of the depth range: far more than a plane's change over a texel here.
        d.awayFromEdges += nextToDepthEdge(fresh, side, i, 1e-4f) ? 0 : 1;
    }
    return d;
}

// The cascade index of a pass note "cascade <c>: ...".
size_t noteCascade(const std::string& note) { return size_t(std::stoul(note.substr(note.find("cascade ") + 8))); }

}  // namespace

// --shadow-scroll on a moving camera: the near cascades' squares step to new origins and their tiles
// are scrolled (moved by whole texels, strips redrawn) instead of redrawn. Every frame, each scrolled
// tile agrees with a fresh redraw within kShadowScrollDepthTolerance (the depth plane evaluated from
// vertices rounded differently) but for at most kShadowScrollMaxDifferingFraction of its texels, each
// next to a depth edge (coverage at silhouettes decided by that rounding); kept and
// wholly redrawn tiles are bit-exact; and a frame that scrolls a tile leaves its kept neighbours as
// they were. Every raster that scrolls (compute redraws whole tiles).
TEST(ShadowCache, ScrolledTilesMatchAFreshRedrawWithinTheBound) {
    using Conservative = ShadowSettings::ConservativeRaster;
    // The origin step: the default (shifts of 16 texels or more: moved in place in bands) and one
    // texel (shifts of a few texels: too many bands, moved through the scratch tile).
    std::vector<std::tuple<ShadowSettings::Raster, Conservative, float>> cases;
    for (ShadowSettings::Raster raster :
         {ShadowSettings::Raster::Plain, ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split})
        cases.emplace_back(raster, Conservative::GeometryShader, ShadowSettings{}.originStep);
    cases.emplace_back(ShadowSettings::Raster::Plain, Conservative::GeometryShader, 0.0f);
    if (queryConservativeRasterSupport().hardware)
        for (ShadowSettings::Raster raster : {ShadowSettings::Raster::Conservative, ShadowSettings::Raster::Split})
            cases.emplace_back(raster, Conservative::Hardware, ShadowSettings{}.originStep);
    for (const auto& [raster, conservative, originStep] : cases) {
        const std::string name = std::string(ShadowSettings::rasterName(raster)) + " (" +
                                 ShadowSettings::conservativeRasterName(conservative) + ", origin step " +
                                 std::to_string(originStep) + ")";
        Scene scene = castersOnAFloor();
        SceneGpu gpu(scene);
        RenderSettings settings = smallCascades(raster);
        settings.shadows.conservativeRaster = conservative;
        settings.shadows.originStep = originStep;
        settings.shadows.scroll = true;
        ShadowMapPass state;
        fg::TexturePool pool;
        std::vector<std::string> notes;
        Tiles before = drawTiles(scene, gpu, settings, state, pool, &notes);
        size_t scrolledTiles = 0, differingTexels = 0, beyondTexels = 0, keptNextToScroll = 0;
        double largest = 0.0;
        for (int step = 1; step <= 8; ++step) {
            scene.camera.position += glm::vec3(0.05f, 0.0f, -0.3f);
            scene.camera.target += glm::vec3(0.05f, 0.0f, -0.3f);
            const Tiles now = drawTiles(scene, gpu, settings, state, pool, &notes);
            const Tiles fresh = redrawnTiles(scene, gpu, settings);
            ASSERT_EQ(now.depth.size(), fresh.depth.size());
            ASSERT_EQ(notes.size(), now.depth.size());
            bool anyScrolled = false;  // this frame scrolled a tile of the atlas
            for (const std::string& note : notes) anyScrolled |= note.find("scrolled by (") != std::string::npos;
            for (const std::string& note : notes) {
                const size_t c = noteCascade(note);
                const std::string what = name + " step " + std::to_string(step) + " cascade " + std::to_string(c) + ": " + note;
                const size_t side = size_t(settings.shadows.size);
                if (note.find("scrolled by (") != std::string::npos) {
                    EXPECT_NE(note.find("strip redrawn"), std::string::npos) << what;
                    const ScrollDifference d = compareScrolled(now.depth[c], fresh.depth[c], side);
                    EXPECT_LE(double(d.beyond), kShadowScrollMaxDifferingFraction * double(side * side)) << what;
                    EXPECT_EQ(d.awayFromEdges, 0u) << what;
                    ++scrolledTiles;
                    differingTexels += d.differing;
                    beyondTexels += d.beyond;
                    largest = std::max(largest, d.largestWithin);
                } else if (note.find("kept (unchanged)") != std::string::npos) {
                    // Untouched by the frame's copies and strips (a neighbour of a scrolled tile
                    // included): bit for bit what it held; within the bound of a fresh redraw (it
                    // may hold an earlier frame's scrolled texels).
                    ASSERT_LT(c, before.depth.size()) << what;
                    EXPECT_EQ(std::memcmp(now.depth[c].data(), before.depth[c].data(), side * side * sizeof(float)), 0) << what;
                    const ScrollDifference d = compareScrolled(now.depth[c], fresh.depth[c], side);
                    EXPECT_LE(double(d.beyond), kShadowScrollMaxDifferingFraction * double(side * side)) << what;
                    EXPECT_EQ(d.awayFromEdges, 0u) << what;
                    keptNextToScroll += anyScrolled ? 1 : 0;
                } else {
                    EXPECT_NE(note.find("redrawn ("), std::string::npos) << what;
                    EXPECT_EQ(std::memcmp(now.depth[c].data(), fresh.depth[c].data(), side * side * sizeof(float)), 0) << what;
                }
            }
            before = now;
        }
        const double tileTexels = double(settings.shadows.size) * double(settings.shadows.size);
        std::printf("%s: %zu tiles scrolled over the walk; against a fresh redraw %.2f%% of their texels differ in any bit, "
                    "by at most %.3g within the tolerance %.0e; %zu texels (%.4f%%, bound %.2f%%) beyond it, all next to depth edges\n",
                    name.c_str(), scrolledTiles, 100.0 * double(differingTexels) / (tileTexels * double(std::max<size_t>(scrolledTiles, 1))),
                    largest, double(kShadowScrollDepthTolerance), beyondTexels,
                    100.0 * double(beyondTexels) / (tileTexels * double(std::max<size_t>(scrolledTiles, 1))),
                    100.0 * kShadowScrollMaxDifferingFraction);
        EXPECT_GE(scrolledTiles, 2u) << name << ": the walk scrolled (almost) nothing: the comparison proves little";
        EXPECT_GE(keptNextToScroll, 1u) << name << ": no frame kept a tile beside a scrolled one";
        EXPECT_EQ(state.cacheStats.scrolled, scrolledTiles) << name;
    }
}

// A square that changes size (the camera's field of view widens its slices) is redrawn whole, not
// scrolled, and equals a fresh redraw bit for bit; --shadow-scroll off redraws moved squares whole.
TEST(ShadowCache, SizeChangeAndScrollOffRedrawWholeTiles) {
    Scene scene = castersOnAFloor();
    SceneGpu gpu(scene);
    RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    settings.shadows.scroll = true;  // even scrolling redraws a resized square whole
    ShadowMapPass state;
    fg::TexturePool pool;
    std::vector<std::string> notes;
    const test::ShadowAtlasFrame first = test::drawShadowAtlas(scene, gpu, settings, state, pool);
    scene.camera.fovYDegrees *= 1.3f;
    const test::ShadowAtlasFrame wider = test::drawShadowAtlas(scene, gpu, settings, state, pool);
    size_t resized = 0;
    for (const std::string& note : wider.notes) {
        const size_t c = noteCascade(note);
        if (c >= first.frustum.cascades.size() || c >= wider.frustum.cascades.size()) continue;
        if (glm::mat3(first.frustum.cascades[c].worldToClip) == glm::mat3(wider.frustum.cascades[c].worldToClip)) continue;
        ++resized;
        EXPECT_NE(note.find("redrawn (light matrix changed)"), std::string::npos) << note;
    }
    EXPECT_GT(resized, 0u) << "the wider field of view resized no square";
    expectSameTiles(drawTiles(scene, gpu, settings, state, pool), redrawnTiles(scene, gpu, settings), "after the resize");

    // Scrolling off: the walk's moved squares are redrawn whole ("square moved"), none scrolled.
    settings.shadows.scroll = false;
    size_t moved = 0;
    for (int step = 1; step <= 4; ++step) {
        scene.camera.position += glm::vec3(0.05f, 0.0f, -0.3f);
        scene.camera.target += glm::vec3(0.05f, 0.0f, -0.3f);
        const Tiles now = drawTiles(scene, gpu, settings, state, pool, &notes);
        moved += countNotes(notes, "redrawn (square moved)");
        EXPECT_EQ(countNotes(notes, "scrolled"), 0u);
        expectSameTiles(now, redrawnTiles(scene, gpu, settings), "scroll off step " + std::to_string(step));
    }
    EXPECT_GT(moved, 0u) << "no square moved on the walk";
    EXPECT_EQ(state.cacheStats.scrolled, 0u);
}

// --shadow-size-hold on a camera that zooms back and forth while it walks: fewer tiles are redrawn
// whole for a changed light matrix than without it (the squares keep their size, so moves scroll),
// and every frame's atlas is within the scroll bound of a fresh redraw of the same frusta (the fresh
// pass is given the same previous frame to hold from).
TEST(ShadowCache, SizeHoldTurnsResizesIntoScrolls) {
    auto walk = [](bool hold, size_t& resized, size_t& scrolled) {
        Scene scene = castersOnAFloor();
        SceneGpu gpu(scene);
        RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
        settings.shadows.sizeHold = hold;
        settings.shadows.scroll = true;
        ShadowMapPass state;
        fg::TexturePool pool;
        std::vector<std::string> notes;
        drawTiles(scene, gpu, settings, state, pool);
        resized = scrolled = 0;
        for (int step = 1; step <= 8; ++step) {
            scene.camera.position += glm::vec3(0.05f, 0.0f, -0.3f);
            scene.camera.target += glm::vec3(0.05f, 0.0f, -0.3f);
            scene.camera.fovYDegrees = step % 2 ? 47.0f : 45.0f;
            ShadowMapPass fresh;
            fresh.previousFrusta = state.previousFrusta;  // what the kept pass holds from
            settings.shadows.cache = false;
            fg::TexturePool freshPool;
            const Tiles redrawn = drawTiles(scene, gpu, settings, fresh, freshPool);
            settings.shadows.cache = true;
            const Tiles now = drawTiles(scene, gpu, settings, state, pool, &notes);
            resized += countNotes(notes, "redrawn (light matrix changed)");
            scrolled += countNotes(notes, "scrolled by (");
            ASSERT_EQ(now.depth.size(), redrawn.depth.size());
            const size_t side = size_t(settings.shadows.size);
            for (size_t c = 0; c < now.depth.size(); ++c) {
                const ScrollDifference d = compareScrolled(now.depth[c], redrawn.depth[c], side);
                EXPECT_LE(double(d.beyond), kShadowScrollMaxDifferingFraction * double(side * side)) << "step " << step << " cascade " << c;
                EXPECT_EQ(d.awayFromEdges, 0u) << "step " << step << " cascade " << c;
            }
        }
    };
    size_t resizedHeld = 0, scrolledHeld = 0, resizedFree = 0, scrolledFree = 0;
    walk(true, resizedHeld, scrolledHeld);
    walk(false, resizedFree, scrolledFree);
    std::printf("zooming walk: %zu tiles redrawn for a changed light matrix with --shadow-size-hold, %zu without; "
                "scrolled %zu / %zu\n", resizedHeld, resizedFree, scrolledHeld, scrolledFree);
    EXPECT_GT(resizedFree, 0u) << "the zoom resized nothing: the test proves nothing";
    EXPECT_LT(resizedHeld, resizedFree);
    EXPECT_GT(scrolledHeld, 0u);
}

// --shadow-redraw-budget on a camera that walks and zooms (squares move and resize every few
// frames), scrolling off (every kept tile must equal a fresh redraw of its square bit for bit) and
// on (scrolls are budget units too): no frame spends more than the budget, no cascade but the last is drawn whole after the first frame, some
// cascades lag and some new squares complete; a lagging cascade serves its tile untouched; and once
// the camera stops, the squares catch up within 4 frames a cascade and the tiles are what a pass
// without a budget draws, bit for bit (the converged atlas equals the unbudgeted one; with
// scrolling, within the scroll bound).
TEST(ShadowRedrawBudget, BudgetHeldOnAFlythroughAndTheAtlasConverges) {
    for (const auto& [budget, scroll] : {std::pair<int, bool>{1, false}, {3, false}, {2, true}}) {
        const std::string name = "budget " + std::to_string(budget) + (scroll ? ", scrolling" : "");
        Scene scene = castersOnAFloor();
        SceneGpu gpu(scene);
        RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
        settings.shadows.scroll = scroll;
        settings.shadows.redrawBudget = budget;
        ShadowMapPass state;
        fg::TexturePool pool;
        std::vector<std::string> notes;
        drawTiles(scene, gpu, settings, state, pool, &notes);
        EXPECT_EQ(state.cacheStats.drawn, notes.size()) << name;
        const size_t last = notes.size() - 1;  // the last cascade never lags: drawn whole when it changes
        uint64_t lagged = 0;
        std::map<int, std::pair<glm::mat4, std::vector<float>>> previous;  // by atlas tile: served matrix, depth
        {
            const test::ShadowAtlasFrame atlas = test::drawShadowAtlas(scene, gpu, settings, state, pool);
            const size_t side = size_t(atlas.frustum.tileSize), width = side * size_t(atlas.frustum.columns);
            for (const ShadowCascade& cascade : atlas.frustum.cascades) {
                const size_t at = size_t(cascade.tile), x0 = (at % size_t(atlas.frustum.columns)) * side,
                             y0 = (at / size_t(atlas.frustum.columns)) * side;
                std::vector<float> tile;
                for (size_t y = 0; y < side; ++y)
                    tile.insert(tile.end(), atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0),
                                atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0 + side));
                previous[cascade.tile] = {cascade.worldToClip, std::move(tile)};
            }
        }
        for (int step = 1; step <= 12; ++step) {
            scene.camera.position += glm::vec3(0.03f, 0.0f, -0.3f);
            scene.camera.target += glm::vec3(0.03f, 0.0f, -0.3f);
            scene.camera.fovYDegrees = 45.0f + 2.0f * float(step % 4);
            const uint64_t quartersBefore = state.cacheStats.quarters;
            const test::ShadowAtlasFrame atlas = test::drawShadowAtlas(scene, gpu, settings, state, pool);
            const uint64_t scrolls = countNotes(atlas.notes, "scrolled by (");
            EXPECT_LE(state.cacheStats.quarters - quartersBefore + scrolls, uint64_t(budget)) << name << " step " << step;
            lagged += countNotes(atlas.notes, "kept its previous square (");
            // A lagging cascade serves the square its tile already held, untouched: the tile's bits and
            // matrix as the frame before (its content is checked against a fresh redraw at the end).
            const size_t side = size_t(atlas.frustum.tileSize), width = side * size_t(atlas.frustum.columns);
            std::map<int, std::pair<glm::mat4, std::vector<float>>> tiles;
            for (size_t c = 0; c < atlas.frustum.cascades.size(); ++c) {
                const ShadowCascade& cascade = atlas.frustum.cascades[c];
                const size_t at = size_t(cascade.tile), x0 = (at % size_t(atlas.frustum.columns)) * side,
                             y0 = (at / size_t(atlas.frustum.columns)) * side;
                std::vector<float> tile;
                for (size_t y = 0; y < side; ++y)
                    tile.insert(tile.end(), atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0),
                                atlas.depth.begin() + std::ptrdiff_t((y0 + y) * width + x0 + side));
                const std::string& note = atlas.notes[c];
                if (note.find("kept its previous square (") != std::string::npos ||
                    note.find("kept (unchanged)") != std::string::npos) {
                    const auto last = previous.find(cascade.tile);
                    ASSERT_NE(last, previous.end()) << name << " step " << step << ": " << note;
                    EXPECT_EQ(last->second.first, cascade.worldToClip) << name << " step " << step << ": " << note;
                    EXPECT_EQ(last->second.second, tile) << name << " step " << step << ": " << note;
                }
                tiles[cascade.tile] = {cascade.worldToClip, std::move(tile)};
            }
            previous = std::move(tiles);
        }
        for (size_t c = 0; c < last; ++c)
            EXPECT_EQ(state.cacheStats.drawnPerCascade[c], 1u) << name << ": cascade " << c << " was drawn whole on the moving camera";
        EXPECT_LE(state.cacheStats.mostBudgetUnitsInAFrame, uint64_t(budget)) << name;
        EXPECT_GT(lagged, 0u) << name << ": no cascade lagged: the walk proves nothing";
        EXPECT_GT(state.cacheStats.completed, 0u) << name << ": no new square was completed";
        // The camera stops: at one quarter a frame, 4 frames per lagging cascade (and what remains of a
        // square begun before the stop, which may then lag once more), and everything is kept.
        const int settle = 4 * settings.shadows.cascades + 1;
        int frames = 0;
        for (; frames < settle; ++frames) {
            drawTiles(scene, gpu, settings, state, pool, &notes);
            if (countNotes(notes, "kept (unchanged)") == notes.size()) break;
        }
        EXPECT_LT(frames, settle) << name << ": the squares did not catch up";
        EXPECT_EQ(countNotes(notes, "kept (unchanged)"), notes.size()) << name;
        const Tiles converged = drawTiles(scene, gpu, settings, state, pool), fresh = redrawnTiles(scene, gpu, settings);
        if (!scroll) {
            expectSameTiles(converged, fresh, name + " converged");
            continue;
        }
        // Scrolled tiles: within the scroll bound of a fresh redraw (ShadowCache.ScrolledTiles...).
        EXPECT_GT(state.cacheStats.scrolled, 0u) << name << ": nothing scrolled";
        ASSERT_EQ(converged.depth.size(), fresh.depth.size());
        const size_t side = size_t(settings.shadows.size);
        for (size_t c = 0; c < converged.depth.size(); ++c) {
            const ScrollDifference d = compareScrolled(converged.depth[c], fresh.depth[c], side);
            EXPECT_LE(double(d.beyond), kShadowScrollMaxDifferingFraction * double(side * side)) << name << " cascade " << c;
            EXPECT_EQ(d.awayFromEdges, 0u) << name << " cascade " << c;
        }
    }
}

// The structured reason: what changed in a tile's key decides whether it may lag or scroll, and
// --explain's text stays as it was.
TEST(ShadowRedrawBudget, TileReasonSaysWhatChanged) {
    Scene scene = castersOnAFloor();
    RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
    const ShadowFrustum fr = fitShadowFrustum(makeFrameData(scene, settings, 0.0f), scene.directionalLights[0].direction);
    ShadowAtlasCache cache;
    const int width = fr.tileSize * fr.columns, height = fr.tileSize * fr.rows;
    cache.depth = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, width, height, 1, "test_kept_atlas");
    cache.width = width;
    cache.height = height;
    cache.casters = 7;
    const std::vector<ShadowTileKey> keys = shadowTileKeys(fr, settings.shadows, ShadowSettings::Raster::Plain, false);
    cache.tiles.resize(size_t(fr.columns * fr.rows));
    for (const ShadowTileKey& k : keys) cache.tiles[size_t(k.tile)] = k;
    auto reasonFor = [&](const FrameData& frame, glm::vec3 sun) {
        const ShadowFrustum now = fitShadowFrustum(frame, sun);
        return shadowTilesToDraw(&cache, width, height, 7, shadowTileKeys(now, settings.shadows, ShadowSettings::Raster::Plain, false))[0];
    };
    const glm::vec3 sun = scene.directionalLights[0].direction;
    EXPECT_EQ(reasonFor(makeFrameData(scene, settings, 0.0f), sun).change, ShadowTileChange::None);
    Scene moved = scene;
    moved.camera.position += glm::vec3(0.0f, 0.0f, -1.0f);
    moved.camera.target += glm::vec3(0.0f, 0.0f, -1.0f);
    const ShadowTileReason move = reasonFor(makeFrameData(moved, settings, 0.0f), sun);
    EXPECT_EQ(move.change, ShadowTileChange::SquareMoved);
    EXPECT_EQ(move.text, "square moved");
    Scene wider = scene;
    wider.camera.fovYDegrees *= 1.3f;
    const ShadowTileReason resize = reasonFor(makeFrameData(wider, settings, 0.0f), sun);
    EXPECT_EQ(resize.change, ShadowTileChange::SquareResized);
    EXPECT_EQ(resize.text, "light matrix changed");
    const ShadowTileReason turn = reasonFor(makeFrameData(scene, settings, 0.0f), glm::normalize(sun + glm::vec3(0.05f, 0.0f, 0.0f)));
    EXPECT_EQ(turn.change, ShadowTileChange::LightChanged);
    EXPECT_EQ(turn.text, "light matrix changed");
    EXPECT_EQ(shadowTilesToDraw(&cache, width, height, 8, keys)[0].change, ShadowTileChange::CastersChanged);
}

// Two suns on a walk that zooms: the budget holds for the frame, all suns together, whichever sun's
// square is pending and whichever scrolls (a scroll of one sun and quarters of the other share it).
TEST(ShadowRedrawBudget, BudgetIsSharedByTheSuns) {
    Scene scene = castersOnAFloor();
    DirectionalLight second = scene.directionalLights[0];
    second.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, 0.2f));
    scene.directionalLights.push_back(second);
    for (int budget : {1, 2}) {
        RenderSettings settings = smallCascades(ShadowSettings::Raster::Plain);
        settings.shadows.scroll = true;
        settings.shadows.redrawBudget = budget;
        Scene walk = scene;
        Renderer r(walk);
        r.render(settings);
        r.resetShadowCacheStats();
        for (int step = 1; step <= 16; ++step) {
            walk.camera.position += glm::vec3(0.03f, 0.0f, -0.3f);
            walk.camera.target += glm::vec3(0.03f, 0.0f, -0.3f);
            walk.camera.fovYDegrees = 45.0f + 2.0f * float(step % 4);
            r.render(settings);
        }
        const ShadowCacheStats& stats = r.shadowCacheStats();
        EXPECT_LE(stats.mostBudgetUnitsInAFrame, uint64_t(budget)) << "budget " << budget;
        EXPECT_GT(stats.lagging, 0u) << "budget " << budget << ": nothing lagged";
        EXPECT_GT(stats.scrolled + stats.completed, 0u) << "budget " << budget << ": nothing scrolled or completed";
        for (size_t c = 0; c + 1 < size_t(settings.shadows.cascades); ++c) EXPECT_EQ(stats.drawnPerCascade[c], 0u) << c;
    }
}
