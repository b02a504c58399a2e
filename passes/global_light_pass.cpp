#include "passes/global_light_pass.hpp"

#include <algorithm>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/log.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
constexpr int kMaxLights = 16;            // matches MAX_LIGHTS in global_light.comp
constexpr GLuint kShadowMapUnit = 8;      // matches the uShadowMap binding in global_light.comp
struct Data {
    GBuffer in;
    std::vector<fg::ResourceId> shadowMaps;  // parallel to GlobalLightPass::shadowMaps
    fg::ResourceId ao;                       // invalid: no ambient occlusion
    fg::ResourceId hdr;
};

// Shadow uniforms: per light its slot (or -1), per slot its cascades (see global_light.comp).
void setShadowUniforms(GLuint prog, const FrameData& frame, const ShadowMaps& maps, int lightCount) {
    std::vector<GLint> slotOfLight(size_t(kMaxLights), -1);
    std::vector<GLint> cascadeCount(size_t(kMaxShadowedLights), 0);
    std::vector<glm::mat4> eyeToClip(size_t(kMaxShadowedLights * kMaxShadowCascades), glm::mat4(1.0f));
    std::vector<glm::vec4> cascadeInfo(size_t(kMaxShadowedLights * kMaxShadowCascades), glm::vec4(0.0f));
    std::vector<glm::mat3> eyeToLight(size_t(kMaxShadowedLights), glm::mat3(1.0f));
    int columns = 1, tileSize = 1;
    bool marked = false;  // every light's atlas is drawn with the same raster
    for (size_t slot = 0; slot < maps.size() && slot < size_t(kMaxShadowedLights); ++slot) {
        const LightShadowMap& m = maps[slot];
        if (m.light < lightCount) slotOfLight[size_t(m.light)] = GLint(slot);
        cascadeCount[slot] = GLint(m.frustum.cascades.size());
        eyeToLight[slot] = m.frustum.eyeToLight;
        columns = m.frustum.columns;  // the same settings for every light
        tileSize = m.frustum.tileSize;
        marked = m.marked && *m.marked;
        for (size_t c = 0; c < m.frustum.cascades.size(); ++c) {
            const ShadowCascade& sc = m.frustum.cascades[c];
            eyeToClip[slot * kMaxShadowCascades + c] = sc.eyeToClip;
            cascadeInfo[slot * kMaxShadowCascades + c] = glm::vec4(sc.splitFar, sc.texelWorld, sc.texelWorld / sc.depthRange, float(sc.tile));
        }
    }
    const ShadowSettings& s = frame.settings->shadows;
    const gl::Uniforms u(frame.shaders, prog);
    u.setArray("uLightShadowSlot", slotOfLight.data(), kMaxLights);
    u.setArray("uShadowCascadeCount", cascadeCount.data(), kMaxShadowedLights);
    u.setArray("uShadowEyeToClip", eyeToClip.data(), int(eyeToClip.size()));
    u.setArray("uShadowCascade", cascadeInfo.data(), int(cascadeInfo.size()));
    u.setArray("uShadowEyeToLight", eyeToLight.data(), kMaxShadowedLights);
    u.set("uShadowColumns", columns);
    u.set("uShadowTileSize", tileSize);
    u.set("uShadowAtlasMarked", marked);
    u.set("uShadowDepthBias", s.depthBias);
    u.set("uShadowNormalBias", s.normalBias);
}
}  // namespace

std::string sunShadowFilterDefine(const FrameData& frame) {
    return "LP_SHADOW_FILTER_MODE " + std::to_string(int(frame.settings->shadows.filter));
}

int setSunUniforms(GLuint prog, const FrameData& frame, const ShadowMaps& shadowMaps) {
    const auto& lights = frameDirectionalLights(frame);
    if (int(lights.size()) > kMaxLights)
        logWarn("only the first " + std::to_string(kMaxLights) + " of " + std::to_string(lights.size()) +
                " directional lights are drawn");
    const int count = std::min<int>(int(lights.size()), kMaxLights);
    std::vector<glm::vec3> dirs, irr;
    for (int i = 0; i < count; ++i) {
        glm::vec3 toLight = -lights[size_t(i)].direction;
        dirs.push_back(glm::normalize(glm::mat3(frame.view) * toLight));
        irr.push_back(lights[size_t(i)].color * lights[size_t(i)].intensity);
    }
    const gl::Uniforms u(frame.shaders, prog);
    u.set("uLightCount", count);
    u.setArray("uLightDirEye", dirs.data(), count);
    u.setArray("uLightIrradiance", irr.data(), count);
    u.set("uAmbient", frameAmbient(frame));
    setBrdfUniforms(prog, frame);
    setShadowUniforms(prog, frame, shadowMaps, count);
    return count;
}

fg::ResourceId addGlobalLightPass(fg::FrameGraph& graph, GlobalLightPass& state, const FrameData& frame,
                                  const GBuffer& gbuffer, const ShadowMaps& shadowMaps, bool lightingOnly,
                                  fg::ResourceId ao) {
    const Data& d = graph.addPass<Data>(
        "global_lights", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, !lightingOnly, true);
            for (const auto& m : shadowMaps) data.shadowMaps.push_back(b.read(m.depth, fg::Usage::Sampled));
            if (ao.valid()) data.ao = b.read(ao, fg::Usage::Sampled);
            data.hdr = b.create("hdr", {frame.width, frame.height, GL_RGBA16F}, fg::Usage::ImageStore);
        },
        [&state, frame, lightingOnly, shadowMaps](const Data& data, const fg::PassResources& res) {
            const int filter = int(frame.settings->shadows.filter);
            if (state.shadowFilter != filter) state.program = {};  // rebuilt below for this filter
            state.shadowFilter = filter;
            programForLayout(state.program, state.layout, frame, [&](std::vector<std::string> defines) {
                defines.push_back(sunShadowFilterDefine(frame));
                return frame.shaders->compute("global_light.comp", defines);
            });
            const GLuint prog = state.program.id();
            setSunUniforms(prog, frame, shadowMaps);
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uLightingOnly", lightingOnly);
            u.set("uAmbientOcclusion", data.ao.valid());
            bindGBuffer(prog, res, data.in, frame, !lightingOnly, true);
            for (size_t i = 0; i < data.shadowMaps.size(); ++i)
                glBindTextureUnit(kShadowMapUnit + GLuint(i), res.texture(data.shadowMaps[i]));
            if (data.ao.valid()) glBindTextureUnit(kAoTextureUnit, res.texture(data.ao));
            glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            unbindGBuffer();
            for (size_t i = 0; i < data.shadowMaps.size(); ++i) glBindTextureUnit(kShadowMapUnit + GLuint(i), 0);
            if (data.ao.valid()) glBindTextureUnit(kAoTextureUnit, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        });
    return d.hdr;
}

}  // namespace lp
