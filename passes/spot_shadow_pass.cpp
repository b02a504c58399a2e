#include "passes/spot_shadow_pass.hpp"
#include "passes/shadow_map_pass.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/skinning_pass.hpp"
#include "passes/shadow_depth_raster.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId depth;
};
}  // namespace

std::string spotShadowSkipReason(const FrameData& frame) {
    const std::shared_ptr<const std::vector<PointLight>> lights = frameLocalLights(frame);
    if (std::none_of(lights->begin(), lights->end(), [](const PointLight& l) { return l.spot && l.castsShadow; }))
        return "no spot light casts a shadow";
    if (!frame.settings->shadows.enabled) return "shadows are off (--no-shadows)";
    return "";
}

SpotShadowMaps addSpotShadowPass(fg::FrameGraph& graph, SpotShadowPass& state, const FrameData& frame) {
    SpotShadowMaps maps;
    const RenderSettings& s = *frame.settings;
    const std::shared_ptr<const std::vector<PointLight>> frameLights = frameLocalLights(frame);
    const std::vector<PointLight>& lights = *frameLights;
    if (!spotShadowSkipReason(frame).empty()) return maps;
    const int casting = int(std::count_if(lights.begin(), lights.end(), [](const PointLight& l) { return l.spot && l.castsShadow; }));
    for (size_t i = 0; i < lights.size() && int(maps.light.size()) < kMaxSpotShadows; ++i) {
        const PointLight& l = lights[i];
        if (!l.spot || !l.castsShadow) continue;
        // The frustum holds the outer cone (+1 degree so PCF taps at the edge stay inside the tile);
        // its depth runs from 0.5% of the range (at least 1 mm) to the range, where the light ends.
        const float fovY = 2.0f * std::min(l.spot->outerDegrees + 1.0f, 89.5f);
        const float nearPlane = std::max(0.005f * l.range, 1e-3f), farPlane = std::max(l.range, nearPlane * 2.0f);
        const glm::vec3 dir = l.spot->direction;
        const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
        const glm::mat4 view = glm::lookAt(l.position, l.position + dir, up);
        maps.worldToClip.push_back(glm::perspective(glm::radians(fovY), 1.0f, nearPlane, farPlane) * view);
        maps.light.push_back(int(i));
        maps.nearPlane.push_back(nearPlane);
        maps.farPlane.push_back(farPlane);
        maps.texelSlope.push_back(0.0f);  // set below, once the tile size is known
    }
    const int n = int(maps.light.size());
    maps.columns = int(std::ceil(std::sqrt(double(n))));
    const int rows = (n + maps.columns - 1) / maps.columns;
    // Tiles of half the sun's map size: a spot covers far less of the scene than a sun's cascade.
    maps.tileSize = std::clamp(s.shadows.size / 2, 64, 4096 / maps.columns);
    for (int t = 0; t < n; ++t) {
        const PointLight& l = lights[size_t(maps.light[size_t(t)])];
        const float halfFov = glm::radians(std::min(l.spot->outerDegrees + 1.0f, 89.5f));
        maps.texelSlope[size_t(t)] = 2.0f * std::tan(halfFov) / float(maps.tileSize);
    }
    if (casting > n)
        logWarn("spot_shadows: " + std::to_string(casting - n) + " shadow-casting spots past the first " +
                std::to_string(kMaxSpotShadows) + " are unshadowed");
    const fg::TextureDesc desc{maps.tileSize * maps.columns, maps.tileSize * rows, GL_DEPTH_COMPONENT32F};
    const std::vector<glm::mat4> matrices = maps.worldToClip;
    const int columns = maps.columns, tile = maps.tileSize;
    const Data& data = graph.addPass<Data>(
        "spot_shadows", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, Data& out) {
            out.depth = b.create("spot_shadows.depth", desc, fg::Usage::DepthAttachment);
            readPosedVertices(b, frame);
        },
        [&state, frame, matrices, columns, tile](const Data& out, const fg::PassResources& res) {
            if (!state.program) {
                state.program = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag");
                state.fbo = gl::makeFramebuffer("spot_shadows");
            }
            // MASK and BLEND casters: drawn after the opaque ones by the alpha-tested twin.
            const bool alphaTested = hasAlphaTestedCasters(frame.gpu->casterClusters);
            if (alphaTested && !state.alphaProgram)
                state.alphaProgram = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.frag",
                                                             std::vector<std::string>{"LP_SHADOW_ALPHA_TEST"});
            // Every caster (the sun cascades' clusters, not culled), opaque and alpha-tested draws apart.
            const CasterList casters = cullCasters(frame.gpu->casterClusters, *frame.scene, glm::mat4(1.0f), 0.0f, false);
            const GLuint fbo = state.fbo.id();
            const fg::TextureDesc& d = res.desc(out.depth);
            const ShadowDepthRaster raster(fbo, res.texture(out.depth), d.width, d.height, frame.settings->shadows.slopeBias);
            const float one = 1.0f;
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
            for (size_t t = 0; t < matrices.size(); ++t) {
                glViewport(GLint(t % size_t(columns)) * tile, GLint(t / size_t(columns)) * tile, tile, tile);
                drawCasters(frame, state.program.id(), alphaTested ? state.alphaProgram.id() : 0, matrices[t], casters);
            }
            glBindVertexArray(0);
            glUseProgram(0);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
        });
    maps.depth = data.depth;
    return maps;
}

}  // namespace lp
