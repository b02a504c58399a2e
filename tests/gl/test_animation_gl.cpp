// Animated models on the GPU: the velocity of an animated vertex in gbuffer.velocity (classic and
// visibility G-buffer; moved by a node, a skin or a morph target) against its analytic screen motion, motion blur under a still camera, and the
// shadow cascade cache invalidated by what moved, not by the clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/graph/texture_pool.hpp"
#include "engine/render/motion.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/scene/animation.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/scene_loader.hpp"
#include "frame/frame_builder.hpp"
#include "frame/renderer.hpp"
#include "passes/shadow_map_pass.hpp"
#include "tests/gl/gl_fixture.hpp"

namespace lp {
namespace {

constexpr float kSpeed = 2.0f;  // metres per second along +x
constexpr float kHeight = 0.5f;

// How the sliding plane is moved: by its node's translation, by a skin (its one joint translated;
// the mesh's own node placed far away, which a skin ignores), or by a morph target (a delta of
// (kSpeed, 0, 0) whose weight runs from 0 to 1). The same motion all three ways.
enum class Motion { Node, Skin, Morph };

// `mesh` moving linearly from (0, kHeight, 0) at t = 0 to (kSpeed, kHeight, 0) at t = 1 s, looping:
// the rest pose at (0, kHeight, 0).
ModelInstance slidingModel(const char* name, MeshData mesh, Motion motion = Motion::Node) {
    auto animation = std::make_shared<NodeAnimation>();
    AnimationClip clip;
    clip.name = "slide";
    AnimationSampler sampler;
    sampler.times = {0.0f, 1.0f};
    const uint32_t count = uint32_t(mesh.vertices.size());
    if (motion == Motion::Morph) {
        AnimatedNode node;
        node.translation = glm::vec3(0.0f, kHeight, 0.0f);
        node.weights = {0.0f};
        animation->nodes.push_back(node);
        NodeVertexRange range{0, 0, count, 0, false};
        range.morphTargets = 1;
        animation->ranges.push_back(range);
        MorphDelta delta;
        delta.position = glm::vec3(kSpeed, 0.0f, 0.0f);
        animation->morphDeltas.assign(count, delta);
        animation->restLocal = mesh.vertices;
        sampler.weights = {0.0f, 1.0f};
        sampler.weightCount = 1;
        clip.channels.push_back({0, AnimationPath::Weights, 0});
    } else if (motion == Motion::Skin) {
        AnimatedNode joint, meshNode;
        joint.translation = glm::vec3(0.0f, kHeight, 0.0f);
        meshNode.translation = glm::vec3(50.0f, -20.0f, 7.0f);  // ignored: the skin places the vertices
        animation->nodes = {joint, meshNode};
        Skin skin;
        skin.joints = {0};
        skin.inverseBind = {glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -kHeight, 0.0f))};
        animation->skins.push_back(skin);
        NodeVertexRange range{1, 0, count, 0, false};
        range.skin = 0;
        animation->ranges.push_back(range);
        VertexJoints joints;
        joints.weight[0] = 1.0f;
        animation->vertexJoints.assign(count, joints);
        animation->restLocal = mesh.vertices;  // the bind pose, in the mesh's space
        for (Vertex& v : animation->restLocal) v.position.y += kHeight;
        sampler.values = {glm::vec4(0.0f, kHeight, 0.0f, 0.0f), glm::vec4(kSpeed, kHeight, 0.0f, 0.0f)};
        clip.channels.push_back({0, AnimationPath::Translation, 0});
    } else {
        AnimatedNode node;
        node.translation = glm::vec3(0.0f, kHeight, 0.0f);
        animation->nodes.push_back(node);
        animation->restLocal = mesh.vertices;
        animation->ranges.push_back({0, 0, count, 0, false});
        sampler.values = {glm::vec4(0.0f, kHeight, 0.0f, 0.0f), glm::vec4(kSpeed, kHeight, 0.0f, 0.0f)};
        clip.channels.push_back({0, AnimationPath::Translation, 0});
    }
    animation->order = motion == Motion::Skin ? std::vector<int>{0, 1} : std::vector<int>{0};
    clip.samplers.push_back(sampler);
    clip.duration = 1.0f;
    animation->clips.push_back(clip);
    for (Vertex& v : mesh.vertices) v.position.y += kHeight;  // the rest pose, as the loader places it
    ModelInstance m;
    m.name = name;
    m.mesh = std::move(mesh);
    m.animation = animation;
    m.playingClips = {0};
    return m;
}

// A still 6 m floor and a 1 m plane sliding above it, seen from above and in front.
Scene slidingScene(Motion motion = Motion::Node) {
    Scene s;
    ModelInstance floor;
    floor.name = "floor";
    floor.mesh = makePlane(6.0f, 2);
    s.models.push_back(std::move(floor));
    s.models.push_back(slidingModel("slider", makePlane(1.0f, 2), motion));
    s.camera.position = {0.5f, 4.0f, 3.0f};
    s.camera.target = {0.5f, 0.0f, 0.0f};
    s.camera.fovYDegrees = 50.0f;
    s.camera.nearPlane = 0.1f;
    s.camera.farPlane = 30.0f;
    return s;
}

RenderSettings smallSettings() {
    RenderSettings s;
    s.aa.method = AntiAliasing::Off;
    s.autoExposure = false;
    s.width = 64;
    s.height = 48;
    return s;
}

struct Velocities {
    std::vector<float> depth;
    std::vector<glm::vec2> velocity;
};

// The G-buffer of `mode` alone, with velocity, for the frame at `time` after one at `previousTime`,
// the models posed as the Renderer poses them.
Velocities renderVelocity(const Scene& scene, GBufferMode mode, float previousTime, float time, FrameData* frameOut,
                          SkinningMode skinning = SkinningMode::Gpu) {
    RenderSettings settings = smallSettings();
    settings.gbuffer.mode = mode;
    settings.skinning = skinning;
    const FrameData previous = makeFrameData(scene, settings, previousTime);
    FrameData frame = makeFrameData(scene, settings, time);
    applyMotion(frame, motionHistoryOf(previous), glm::vec2(0.0f));
    SceneGpu gpu(scene);
    gpu.pose(scene, frame.time, frame.previousTime, skinning);
    gl::ShaderLibrary shaders;
    frame.gpu = &gpu;
    frame.shaders = &shaders;
    PassStates states;
    fg::FrameGraph graph;
    fg::TexturePool pool;
    if (skinningSkipReason(frame).empty()) {  // --skinning gpu: posed by the skinning pass, before the G-buffer
        addSkinningPass(graph, states.skinning, frame);
        frame.posedVerticesOnGpu = true;
    }
    GBufferChannels channels;
    channels.velocity = true;
    GBuffer g;
    if (mode == GBufferMode::Visibility) {
        const VisibilityBuffer v = addVisibilityPass(graph, states.visibility, frame);
        g = addVisibilityResolvePass(graph, states.visibilityResolve, frame, v, channels);
    } else {
        g = addGBufferPass(graph, states.gbuffer, frame, channels);
    }
    graph.markOutput(g.depth);
    graph.markOutput(g.velocity);
    graph.compile();
    graph.execute(pool);
    const size_t n = size_t(frame.width) * size_t(frame.height);
    Velocities out;
    out.depth.resize(n);
    out.velocity.resize(n);
    glGetTextureImage(graph.outputTexture(g.depth), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(n * sizeof(float)), out.depth.data());
    glGetTextureImage(graph.outputTexture(g.velocity), 0, GL_RG, GL_FLOAT, GLsizei(n * sizeof(glm::vec2)), out.velocity.data());
    frame.gpu = nullptr;
    frame.shaders = nullptr;
    *frameOut = frame;
    return out;
}

}  // namespace

// Every pixel of the sliding plane moves as its point does: the point rebuilt from the pixel's depth,
// moved back by the plane's motion over the frame (kSpeed x dt along x), projected with the same
// (still) camera; the floor's pixels do not move. In both G-buffer modes, within 0.02 output pixels;
// moved by its node, by a skin and by a morph target (posed once a frame into the buffers every pass reads),
// posed by the skinning pass (--skinning gpu) and on the CPU; the two give the same motion vectors.
TEST(AnimationGl, AnimatedVelocityMatchesTheAnalyticScreenMotion) {
    const float dt = 1.0f / 30.0f, time = 0.5f;
    for (Motion motion : {Motion::Node, Motion::Skin, Motion::Morph})
    for (GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility})
    for (SkinningMode skinning : {SkinningMode::Gpu, SkinningMode::Cpu}) {
        const Scene scene = slidingScene(motion);
        SCOPED_TRACE(std::string(motion == Motion::Node ? "node" : motion == Motion::Skin ? "skin" : "morph") +
                     (mode == GBufferMode::Classic ? ", classic" : ", visibility") + ", --skinning " + skinningModeName(skinning));
        FrameData frame;
        const Velocities img = renderVelocity(scene, mode, time - dt, time, &frame, skinning);
        if (skinning == SkinningMode::Gpu) {  // the same motion vectors as the CPU's posing, texel by texel
            FrameData cpuFrame;
            const Velocities cpu = renderVelocity(scene, mode, time - dt, time, &cpuFrame, SkinningMode::Cpu);
            for (size_t i = 0; i < img.velocity.size(); ++i) {
                ASSERT_EQ(img.depth[i] < 1.0f, cpu.depth[i] < 1.0f) << "texel " << i % size_t(frame.width) << "," << i / size_t(frame.width);
                ASSERT_LT(glm::length(img.velocity[i] - cpu.velocity[i]) * float(frame.width), 1e-3f)
                    << "texel " << i % size_t(frame.width) << "," << i / size_t(frame.width);
            }
        }
        ASSERT_TRUE(frame.hasPrevious);
        const glm::dmat4 viewProjection = glm::dmat4(frame.unjitteredProjection) * glm::dmat4(frame.view);
        const glm::dmat4 inverse = glm::inverse(glm::dmat4(frame.projection) * glm::dmat4(frame.view));
        const glm::dmat4 movedBack = viewProjection * glm::translate(glm::dmat4(1.0), glm::dvec3(-double(kSpeed) * dt, 0.0, 0.0));
        int sliderPixels = 0, floorPixels = 0;
        double worst = 0.0;
        for (int y = 0; y < frame.height; ++y)
            for (int x = 0; x < frame.width; ++x) {
                const size_t i = size_t(y) * size_t(frame.width) + size_t(x);
                if (!(img.depth[i] < 1.0f)) continue;
                const glm::dvec2 ndc((x + 0.5) / frame.width * 2.0 - 1.0, (y + 0.5) / frame.height * 2.0 - 1.0);
                const glm::dvec4 h = inverse * glm::dvec4(ndc, img.depth[i] * 2.0 - 1.0, 1.0);
                const glm::dvec3 p = glm::dvec3(h) / h.w;
                const bool slider = p.y > 0.5 * kHeight;
                (slider ? sliderPixels : floorPixels)++;
                const glm::dvec2 expected = velocityOfPoint(viewProjection, slider ? movedBack : viewProjection, p);
                const glm::dvec2 error = (glm::dvec2(img.velocity[i]) - expected) * glm::dvec2(frame.width, frame.height);
                worst = std::max(worst, glm::length(error));
                if (!slider) EXPECT_EQ(img.velocity[i], glm::vec2(0.0f)) << x << "," << y;
            }
        EXPECT_LT(worst, 0.02);
        EXPECT_GT(sliderPixels, 50);  // 91 of 3072 on this 64x48 frame
        EXPECT_GT(floorPixels, 100);
        // Not trivially small: the plane moves 2/30 m, about a pixel or more on this 64 px image.
        float largest = 0.0f;
        for (const glm::vec2& v : img.velocity) largest = std::max(largest, std::abs(v.x) * float(frame.width));
        EXPECT_GT(largest, 0.5f);
    }
}

// A skinned and morphed glTF (tests/data/gltf/skinned_grid.gltf: 8 bending joints, 2 animated morph
// targets), loaded as `lightpass render --model` loads it: under a still camera every pixel it covers
// moves (the whole surface is morphed, and skinned by at least one bending joint) and the background
// does not, in both G-buffer modes; with no clip playing nothing moves.
TEST(AnimationGl, LoadedSkinnedModelMovesWhereItIsDrawn) {
    Scene scene = sceneForModel(test::repoPath("tests/data/gltf/skinned_grid.gltf"));
    ASSERT_EQ(scene.models.size(), 1u);
    ASSERT_TRUE(scene.models[0].animation);
    ASSERT_EQ(scene.models[0].animation->skins.size(), 1u);
    for (GBufferMode mode : {GBufferMode::Classic, GBufferMode::Visibility}) {
        SCOPED_TRACE(mode == GBufferMode::Classic ? "classic" : "visibility");
        FrameData frame;
        const Velocities img = renderVelocity(scene, mode, 0.5f - 1.0f / 30.0f, 0.5f, &frame);
        size_t covered = 0, moving = 0;
        for (size_t i = 0; i < img.depth.size(); ++i) {
            if (img.depth[i] < 1.0f) {
                ++covered;
                moving += img.velocity[i] != glm::vec2(0.0f);
            } else {
                EXPECT_EQ(img.velocity[i], glm::vec2(0.0f)) << "background pixel " << i;
            }
        }
        EXPECT_GT(covered, 100u);
        EXPECT_EQ(moving, covered);
    }
    scene.models[0].playingClips.clear();
    FrameData frame;
    const Velocities still = renderVelocity(scene, GBufferMode::Classic, 0.4f, 0.5f, &frame);
    for (const glm::vec2& v : still.velocity) ASSERT_EQ(v, glm::vec2(0.0f));
}

// With no clip playing (--animation none) the model keeps its rest pose and writes no motion.
TEST(AnimationGl, NoClipPlayingIsStill) {
    Scene scene = slidingScene();
    scene.models[1].playingClips.clear();
    FrameData frame;
    const Velocities img = renderVelocity(scene, GBufferMode::Classic, 0.4f, 0.5f, &frame);
    for (const glm::vec2& v : img.velocity) ASSERT_EQ(v, glm::vec2(0.0f));
}

// Motion blur runs under a still camera when an animated model moves, and not when it holds still.
TEST(AnimationGl, MotionBlurRunsForAMovingModelUnderAStillCamera) {
    RenderSettings settings = smallSettings();
    settings.motionBlur.enabled = true;
    auto blurRuns = [&](const Scene& scene, float t0, float t1) {
        Renderer renderer(scene);
        renderer.render(settings, t0, false);
        renderer.render(settings, t1, false);
        for (const auto& d : renderer.graph().explain())
            if (d.name == "motion_blur") return d.runs;
        return false;
    };
    const Scene scene = slidingScene();
    EXPECT_TRUE(blurRuns(scene, 0.5f, 0.55f));
    EXPECT_FALSE(blurRuns(scene, 1.0f, 2.0f));  // the same point of the loop: nothing moved
    Scene still = scene;
    still.models[1].playingClips.clear();
    EXPECT_FALSE(blurRuns(still, 0.5f, 0.55f));
}

// The sun's cascade cache: an animated caster that moved (by its node, a skin or a morph target)
// redraws the tiles (as a fresh redraw draws them); the clock moving a model that does not move (no clip playing), or not moving at all, keeps them.
// Posed by the skinning pass (--skinning gpu) and on the CPU alike.
TEST(AnimationGl, ShadowCacheFollowsWhatMovedNotTheClock) {
    RenderSettings settings = smallSettings();
    settings.shadows.size = 256;
    settings.shadows.cascades = 2;
    settings.shadows.redrawBudget = 0;
    for (Motion motion : {Motion::Node, Motion::Skin, Motion::Morph})
    for (SkinningMode mode : {SkinningMode::Gpu, SkinningMode::Cpu}) {
    settings.skinning = mode;
    SCOPED_TRACE(std::string(motion == Motion::Node ? "node" : motion == Motion::Skin ? "skin" : "morph") + ", --skinning " +
                 skinningModeName(mode));
    Scene scene = slidingScene();
    scene.models[1] = slidingModel("slider", makeCube(0.5f), motion);
    DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f));
    scene.directionalLights.push_back(sun);
    auto allNotes = [](const std::vector<std::string>& notes, const std::string& text) {
        return !notes.empty() && std::all_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
    };
    {
        SceneGpu gpu(scene);
        ShadowMapPass state;
        fg::TexturePool pool;
        gpu.pose(scene, 0.2, 0.2, mode);
        test::drawShadowAtlas(scene, gpu, settings, state, pool);
        gpu.pose(scene, 0.2, 0.2, mode);
        EXPECT_TRUE(allNotes(test::drawShadowAtlas(scene, gpu, settings, state, pool).notes, "kept (unchanged)"));
        gpu.pose(scene, 0.4, 0.2, mode);
        const test::ShadowAtlasFrame moved = test::drawShadowAtlas(scene, gpu, settings, state, pool);
        EXPECT_TRUE(allNotes(moved.notes, "redrawn (casters changed)")) << moved.notes[0];
        // The kept atlas holds what a fresh one draws of the moved caster, tile by tile.
        RenderSettings fresh = settings;
        fresh.shadows.cache = false;
        ShadowMapPass freshState;
        fg::TexturePool freshPool;
        const test::ShadowAtlasFrame redrawn = test::drawShadowAtlas(scene, gpu, fresh, freshState, freshPool);
        const ShadowFrustum& fr = moved.frustum;
        const size_t side = size_t(fr.tileSize), width = side * size_t(fr.columns);
        size_t differing = 0;
        for (const auto& cascade : fr.cascades) {
            const size_t x0 = size_t(cascade.tile % fr.columns) * side, y0 = size_t(cascade.tile / fr.columns) * side;
            for (size_t y = 0; y < side; ++y)
                for (size_t x = 0; x < side; ++x) differing += moved.depth[(y0 + y) * width + x0 + x] != redrawn.depth[(y0 + y) * width + x0 + x];
        }
        EXPECT_EQ(differing, 0u);
    }
    {
        Scene still = scene;
        still.models[1].playingClips.clear();
        SceneGpu gpu(still);
        ShadowMapPass state;
        fg::TexturePool pool;
        gpu.pose(still, 0.2, 0.2, mode);
        test::drawShadowAtlas(still, gpu, settings, state, pool);
        gpu.pose(still, 0.4, 0.2, mode);
        EXPECT_TRUE(allNotes(test::drawShadowAtlas(still, gpu, settings, state, pool).notes, "kept (unchanged)"));
    }
    }
}

// The point-light cube's cache: an animated caster within the light's range that moved (by its
// node, a skin or a morph target) redraws the cube, as a fresh redraw draws it; the same motion out
// of the range, or the clock moving a model that does not move, keeps it.
TEST(AnimationGl, PointShadowCacheFollowsTheCasterInRange) {
    RenderSettings settings = smallSettings();
    settings.shadows.size = 256;
    RenderSettings fresh = settings;
    fresh.shadows.cache = false;
    auto note = [](const Renderer& r) {
        for (const fg::PassDecision& d : r.graph().explain())
            if (d.name == "point_shadows" && !d.notes.empty()) return d.notes.front();
        return std::string();
    };
    auto readHdr = [](Renderer& r, RenderSettings s, float time) {
        s.keepHdr = true;
        r.render(s, time, false);
        return r.readHdr().rgba;
    };
    for (Motion motion : {Motion::Node, Motion::Skin, Motion::Morph}) {
        SCOPED_TRACE(motion == Motion::Node ? "node" : motion == Motion::Skin ? "skin" : "morph");
        Scene scene = slidingScene();
        scene.models[1] = slidingModel("slider", makeCube(0.5f), motion);
        PointLight light;  // over the slider's path (x 0.4 .. 0.8 at t 0.2 .. 0.4), reaching it
        light.position = {0.6f, 1.5f, 0.0f};
        light.range = 4.0f;
        light.intensity = 2.0f;
        light.castsShadow = true;
        scene.pointLights.push_back(light);
        {
            Renderer renderer(scene);
            readHdr(renderer, settings, 0.2f);
            readHdr(renderer, settings, 0.2f);
            EXPECT_NE(note(renderer).find("kept (unchanged)"), std::string::npos) << note(renderer);
            const std::vector<float> moved = readHdr(renderer, settings, 0.4f);
            EXPECT_NE(note(renderer).find("redrawn (casters in range changed)"), std::string::npos) << note(renderer);
            Renderer redraw(scene);
            const std::vector<float> redrawn = readHdr(redraw, fresh, 0.4f);
            size_t differing = 0;
            for (size_t i = 0; i < moved.size(); ++i) differing += moved[i] != redrawn[i];
            EXPECT_EQ(differing, 0u);
        }
        {
            Scene far = scene;  // the light at the floor's far end: the slider never reaches its range
            far.pointLights[0].position = {-2.8f, 0.5f, 0.0f};
            far.pointLights[0].range = 1.5f;
            Renderer renderer(far);
            readHdr(renderer, settings, 0.2f);
            readHdr(renderer, settings, 0.4f);
            EXPECT_NE(note(renderer).find("kept (unchanged)"), std::string::npos) << note(renderer);
        }
        {
            Scene still = scene;
            still.models[1].playingClips.clear();
            Renderer renderer(still);
            readHdr(renderer, settings, 0.2f);
            readHdr(renderer, settings, 0.4f);
            EXPECT_NE(note(renderer).find("kept (unchanged)"), std::string::npos) << note(renderer);
        }
    }
}

}  // namespace lp
