#include "passes/point_shadow_pass.hpp"
#include "passes/shadow_map_pass.hpp"
#include "passes/shadow_depth_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/fnv1a.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/scene_gpu.hpp"
#include "engine/render/shadow_casters.hpp"

namespace lp {

float pointShadowFaceTan(int tileSize) {
    // The 45-degree edge at NDC 1 - 2 margin / tileSize: tan(half-angle) = 1 / that.
    const float edge = 1.0f - 2.0f * float(kPointShadowFaceMargin) / float(std::max(tileSize, 4 * kPointShadowFaceMargin));
    return 1.0f / edge;
}

int pointShadowTileSize(int shadowSize, int lights) {
    return std::clamp(shadowSize / 2, 64, kPointShadowAtlasMaxSide / std::max(kPointShadowFaces, lights));
}

std::array<glm::mat4, kPointShadowFaces> pointShadowFaceMatrices(glm::vec3 position, float nearPlane, float farPlane,
                                                                 float faceTan) {
    const glm::mat4 projection = glm::perspective(2.0f * std::atan(faceTan), 1.0f, nearPlane, farPlane);
    std::array<glm::mat4, kPointShadowFaces> m;
    for (int f = 0; f < kPointShadowFaces; ++f) {
        glm::vec3 axis(0.0f);
        axis[f / 2] = f % 2 == 0 ? 1.0f : -1.0f;
        const glm::vec3 up = f / 2 == 1 ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        m[size_t(f)] = projection * glm::lookAt(position, position + axis, up);
    }
    return m;
}

int pointShadowFace(glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    return 2 * axis + (d[axis] >= 0.0f ? 0 : 1);
}

bool PointShadowKey::operator==(const PointShadowKey& o) const {
    // Bit for bit: any change of the light's place moves every depth.
    return std::memcmp(&position, &o.position, sizeof position) == 0 && std::memcmp(&range, &o.range, sizeof range) == 0 &&
           tileSize == o.tileSize && std::memcmp(&slopeBias, &o.slopeBias, sizeof slopeBias) == 0 && casters == o.casters;
}

uint64_t pointShadowCasterSignature(const FrameData& frame, glm::vec3 position, float range) {
    Fnv1a f;
    const Scene& scene = *frame.scene;
    if (!frame.gpu) {  // 'lightpass graph': nothing is drawn; the scene's transforms stand in
        for (const ModelInstance& m : scene.models)
            for (size_t k = 0; k < m.instanceCount(); ++k) f.add(m.instanceTransform(k));
        return f.h;
    }
    const SceneGpu& gpu = *frame.gpu;
    f.add(&gpu);
    size_t within = 0;
    for (const CasterCluster& c : gpu.casterClusters) {
        if (c.model < 0 || size_t(c.model) >= gpu.meshes.size()) continue;
        const glm::mat4& transform = gpu.meshes[size_t(c.model)].model;  // the instance's placement
        if (!casterBoxReachesSphere(transform, c.boundsMin, c.boundsMax, position, range)) continue;
        ++within;
        const GpuMesh& mesh = gpu.meshes[size_t(c.model)];
        f.add(c.model);
        f.add(transform);
        f.add(mesh.model);
        f.add(mesh.vao.id());
        f.add(mesh.vertices.id());
        f.add(mesh.indices.id());
        f.add(mesh.poseVersion);  // an animated mesh posed anew since the cube was drawn
        f.add(c.firstIndex);
        f.add(c.indexCount);
        f.add(c.alpha);
        f.add(c.material);
        if (c.material >= 0 && size_t(c.material) < gpu.materials.size()) {  // what the alpha-tested casters read
            const GpuMaterial& m = gpu.materials[size_t(c.material)];
            f.add(m.alphaMask);
            f.add(m.alphaBlend);
            f.add(m.alphaCutoff);
            f.add(m.opacity);
            f.add(m.diffuseMap);
            f.add(m.secondUvMaps);
        }
    }
    f.add(within);
    return f.h;
}

namespace {
struct Data {
    fg::ResourceId depth;
};

// One cube's row as the execute draws it.
struct CubeWork {
    std::array<glm::mat4, kPointShadowFaces> worldToClip;
    std::array<CasterList, kPointShadowFaces> casters;  // per face: those in range and in its view
    bool redraw = false;
};
}  // namespace

std::string pointShadowSkipReason(const FrameData& frame) {
    const std::shared_ptr<const std::vector<PointLight>> lights = frameLocalLights(frame);
    if (std::none_of(lights->begin(), lights->end(), [](const PointLight& l) { return !l.spot && l.castsShadow; }))
        return "no point light casts a shadow (castsShadow, or a glTF model's \"lightShadows\")";
    if (!frame.settings->shadows.enabled) return "shadows are off (--no-shadows)";
    return "";
}

PointShadowMaps addPointShadowPass(fg::FrameGraph& graph, PointShadowPass& state, const FrameData& frame) {
    PointShadowMaps maps;
    const RenderSettings& s = *frame.settings;
    const std::shared_ptr<const std::vector<PointLight>> frameLights = frameLocalLights(frame);
    const std::vector<PointLight>& lights = *frameLights;
    int casting = 0;
    for (const auto& l : lights) casting += (!l.spot && l.castsShadow) ? 1 : 0;
    const bool caching = s.shadows.cache;
    if (!caching) {  // the kept atlas is let go
        state.atlas = gl::Texture{};
        state.width = state.height = 0;
        state.rows.clear();
    }
    if (!pointShadowSkipReason(frame).empty()) return maps;
    for (size_t i = 0; i < lights.size() && int(maps.light.size()) < kMaxPointShadows; ++i)
        if (!lights[i].spot && lights[i].castsShadow) maps.light.push_back(int(i));
    const int n = int(maps.light.size());
    if (casting > n)
        logWarn("point_shadows: " + std::to_string(casting - n) + " shadow-casting point lights past the first " +
                std::to_string(kMaxPointShadows) + " are unshadowed");
    maps.tileSize = pointShadowTileSize(s.shadows.size, n);
    const float faceTan = pointShadowFaceTan(maps.tileSize);
    maps.texelSlope = 2.0f * faceTan / float(maps.tileSize);
    const fg::TextureDesc desc{maps.tileSize * kPointShadowFaces, maps.tileSize * n, GL_DEPTH_COMPONENT32F};
    // Caster clusters: made once at load with the GPU meshes; 'lightpass graph' (no GPU) makes them here.
    std::vector<CasterCluster> localClusters;
    if (!frame.gpu) localClusters = buildCasterClusters(*frame.scene);
    const std::vector<CasterCluster>& clusters = frame.gpu ? frame.gpu->casterClusters : localClusters;
    const bool atlasKept = caching && state.atlas && state.width == desc.width && state.height == desc.height;
    std::vector<CubeWork> work(static_cast<size_t>(n));
    std::vector<PointShadowKey> keys(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r) {
        const PointLight& l = lights[size_t(maps.light[size_t(r)])];
        // Depth from 0.5% of the range (at least 1 mm) to the range, where the light ends (the spots' range).
        const float nearPlane = std::max(0.005f * l.range, 1e-3f), farPlane = std::max(l.range, nearPlane * 2.0f);
        maps.nearPlane.push_back(nearPlane);
        maps.farPlane.push_back(farPlane);
        maps.worldToClip.push_back(pointShadowFaceMatrices(l.position, nearPlane, farPlane, faceTan));
        CubeWork& w = work[size_t(r)];
        w.worldToClip = maps.worldToClip.back();
        // Each face: the casters in range that the rasteriser would not clip away wholly.
        for (int f = 0; f < kPointShadowFaces; ++f)
            w.casters[size_t(f)] = castersInSphereAndView(clusters, *frame.scene, l.position, farPlane, w.worldToClip[size_t(f)]);
        PointShadowKey& key = keys[size_t(r)];
        key.position = l.position;
        key.range = farPlane;
        key.tileSize = maps.tileSize;
        key.slopeBias = s.shadows.slopeBias;
        key.casters = caching ? pointShadowCasterSignature(frame, l.position, farPlane) : 0;
        std::string why;
        if (!caching) why = "cache off";
        else if (!atlasKept) why = state.atlas ? "atlas resized" : "nothing kept";
        else if (size_t(r) >= state.rows.size() || !state.rows[size_t(r)]) why = "row not drawn";
        else {
            const PointShadowKey& kept = *state.rows[size_t(r)];
            if (std::memcmp(&kept.position, &key.position, sizeof key.position) != 0 ||
                std::memcmp(&kept.range, &key.range, sizeof key.range) != 0)
                why = "light moved";
            else if (kept.slopeBias != key.slopeBias) why = "slope bias changed";
            else if (kept.casters != key.casters) why = "casters in range changed";
        }
        w.redraw = !why.empty();
        const CasterList inRange = castersInSphere(clusters, *frame.scene, l.position, farPlane);
        size_t draws = 0, triangles = 0, alphaTriangles = 0;
        for (const CasterList& c : w.casters) {
            draws += c.draws.size() + c.alphaDraws.size();
            triangles += c.triangles;
            alphaTriangles += c.alphaTriangles;
        }
        graph.notePass("point_shadows", "light " + std::to_string(maps.light[size_t(r)]) + ": " +
                                            std::to_string(inRange.triangles) + " triangles in range; 6 faces of " +
                                            std::to_string(maps.tileSize) + "^2 draw " + std::to_string(triangles) +
                                            " in " + std::to_string(draws) + " draws" +
                                            (alphaTriangles ? " (" + std::to_string(alphaTriangles) + " alpha-tested)" : "") +
                                            "; " + (w.redraw ? "redrawn (" + why + ")" : std::string("kept (unchanged)")));
    }
    PointShadowPass* st = &state;
    fg::ResourceId keptAtlas;
    if (caching)  // the kept atlas, made (cleared to 1: no caster) when first asked for or resized
        keptAtlas = graph.importTexture("point_shadows.depth", desc, [st, desc, n]() -> GLuint {
            if (!st->atlas || st->width != desc.width || st->height != desc.height) {
                st->atlas = gl::makeTexture2D(GL_DEPTH_COMPONENT32F, desc.width, desc.height, 1, "point_shadows.kept_atlas");
                st->width = desc.width;
                st->height = desc.height;
                st->rows.assign(size_t(n), std::nullopt);
                const float one = 1.0f;
                glClearTexImage(st->atlas.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, &one);
            }
            return st->atlas.id();
        });
    const int tile = maps.tileSize;
    const Data& data = graph.addPass<Data>(
        "point_shadows", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, Data& out) {
            out.depth = caching ? b.write(keptAtlas, fg::Usage::DepthAttachment)
                                : b.create("point_shadows.depth", desc, fg::Usage::DepthAttachment);
        },
        [st, frame, work, keys, tile, caching](const Data& out, const fg::PassResources& res) {
            PointShadowPass& state = *st;
            if (!state.program) {
                state.program = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag");
                state.fbo = gl::makeFramebuffer("point_shadows");
            }
            const bool alphaTested = hasAlphaTestedCasters(frame.gpu->casterClusters);
            if (alphaTested && !state.alphaProgram)
                state.alphaProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag",
                                                             std::vector<std::string>{"LP_SHADOW_ALPHA_TEST"});
            const GLuint fbo = state.fbo.id();
            const fg::TextureDesc& d = res.desc(out.depth);
            const ShadowDepthRaster raster(fbo, res.texture(out.depth), d.width, d.height, frame.settings->shadows.slopeBias);
            gl::ScopedEnable scissor(GL_SCISSOR_TEST, true);  // a row's clear leaves the kept rows alone
            const float one = 1.0f;
            if (caching && state.rows.size() != work.size()) state.rows.resize(work.size());
            for (size_t r = 0; r < work.size(); ++r) {
                if (!work[r].redraw) {
                    ++state.stats.kept;
                    continue;
                }
                glScissor(0, GLint(r) * tile, kPointShadowFaces * tile, tile);
                glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
                for (int f = 0; f < kPointShadowFaces; ++f) {
                    glViewport(f * tile, GLint(r) * tile, tile, tile);
                    glScissor(f * tile, GLint(r) * tile, tile, tile);
                    drawCasters(frame, state.program.id(), alphaTested ? state.alphaProgram.id() : 0,
                                work[r].worldToClip[size_t(f)], work[r].casters[size_t(f)]);
                }
                if (caching) state.rows[r] = keys[r];
                ++state.stats.drawn;
            }
            glBindVertexArray(0);
            glUseProgram(0);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
        });
    maps.depth = data.depth;
    return maps;
}

}  // namespace lp
