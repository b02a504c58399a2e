#include "passes/forward_pass.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "passes/ambient_occlusion_pass.hpp"
#include "passes/global_light_pass.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

namespace {
constexpr GLuint kSunShadowUnit = 10;  // LP_SUN_SHADOW_UNIT in forward.frag
constexpr GLuint kEmissiveUnit = 6;    // uEmissiveMap in forward.frag
constexpr GLuint kIblUnits[3] = {7, 8, 9};

struct OpaqueData {
    fg::ResourceId depth;
    ForwardLightingReads reads;
    fg::ResourceId hdr;
};
}  // namespace

ForwardLightingReads declareForwardLighting(fg::PassBuilder& b, LocalLightPass& localLights, const ForwardLighting& lighting) {
    ForwardLightingReads r;
    for (const auto& m : lighting.shadowMaps) r.shadowMaps.push_back(b.read(m.depth, fg::Usage::Sampled));
    if (lighting.environment.irradiance.valid()) {
        r.irradiance = b.read(lighting.environment.irradiance, fg::Usage::Sampled);
        r.prefiltered = b.read(lighting.environment.prefiltered, fg::Usage::Sampled);
        r.dfg = b.read(lighting.environment.dfg, fg::Usage::Sampled);
    }
    if (lighting.ao.valid()) r.ao = b.read(lighting.ao, fg::Usage::Sampled);
    if (lighting.localLights && lighting.localShadows.spot.any())
        r.spotAtlas = b.read(lighting.localShadows.spot.depth, fg::Usage::Sampled);
    if (lighting.localLights && lighting.localShadows.point.any())
        r.pointAtlas = b.read(lighting.localShadows.point.depth, fg::Usage::Sampled);
    if (lighting.localLights) {
        if (lighting.fillsLightRecords) writeLightRecords(b, localLights, lighting.lightRecords);
        else readLightRecords(b);
    }
    return r;
}

void bindForwardLighting(ForwardPass& state, LocalLightPass& localLights, const FrameData& frame,
                         const ForwardLighting& lighting, const ForwardLightingReads& reads,
                         const fg::PassResources& res, const std::vector<std::string>& defines) {
    const bool spotShadows = lighting.localLights && lighting.localShadows.spot.any();
    const bool pointShadows = lighting.localLights && lighting.localShadows.point.any();
    const int filter = int(frame.settings->shadows.filter);
    const bool vertexColors = frame.gpu != nullptr && frame.gpu->vertexColors;
    const bool secondUvSet = frame.gpu != nullptr && frame.gpu->secondUvSet;
    if (!state.program || state.spotShadowVariant != spotShadows || state.pointShadowVariant != pointShadows ||
        state.shadowFilter != filter ||
        state.vertexColors != vertexColors || state.secondUvSet != secondUvSet) {
        std::vector<std::string> d = defines;
        if (spotShadows) d.push_back("LP_SPOT_SHADOWS");
        if (pointShadows) d.push_back("LP_POINT_SHADOWS");
        if (vertexColors) d.push_back("LP_VERTEX_COLOR");
        if (secondUvSet) d.push_back("LP_SECOND_UV");
        d.push_back(sunShadowFilterDefine(frame));
        state.program = frame.shaders->graphics("gbuffer.vert", "forward.frag", d);
        state.spotShadowVariant = spotShadows;
        state.pointShadowVariant = pointShadows;
        state.shadowFilter = filter;
        state.vertexColors = vertexColors;
        state.secondUvSet = secondUvSet;
    }
    const GLuint prog = state.program.id();
    const gl::Uniforms u(frame.shaders, prog);
    setSunUniforms(prog, frame, lighting.shadowMaps);
    setMaterialInputUniform(prog, frame);
    for (size_t i = 0; i < reads.shadowMaps.size(); ++i)
        glBindTextureUnit(kSunShadowUnit + GLuint(i), res.texture(reads.shadowMaps[i]));
    const bool ibl = reads.irradiance.valid();
    u.set("uIbl", ibl);
    if (ibl) {
        setIblUniforms(prog, frame, frame.environments->get(*frame.scene, frame.settings->environment, *frame.shaders, true));
        glBindTextureUnit(kIblUnits[0], res.texture(reads.irradiance));
        glBindTextureUnit(kIblUnits[1], res.texture(reads.prefiltered));
        glBindTextureUnit(kIblUnits[2], res.texture(reads.dfg));
    }
    u.set("uAmbientOcclusion", reads.ao.valid());
    if (reads.ao.valid()) glBindTextureUnit(kAoTextureUnit, res.texture(reads.ao));
    u.set("uLightingOnly", lighting.lightingOnly);
    u.set("uLocalLightCount", 0);
    if (lighting.localLights)
        bindClusteredLightLists(localLights, prog, frame, lighting.lightRecords, res, lighting.localShadows,
                                {spotShadows ? res.texture(reads.spotAtlas) : 0, pointShadows ? res.texture(reads.pointAtlas) : 0});
    u.set("uProjection", gbufferDepthProjection(frame));
}

void unbindForwardLighting() {
    unbindClusteredLightLists();
    for (GLuint u = 0; u < 4; ++u) glBindTextureUnit(kSunShadowUnit + u, 0);
    for (GLuint u : kIblUnits) glBindTextureUnit(u, 0);
    glBindTextureUnit(kAoTextureUnit, 0);
}

ForwardMaterialUniforms::ForwardMaterialUniforms(const gl::Uniforms& u)
    : material(u), emission(u.location("uEmission")), hasEmissive(u.location("uHasEmissiveMap")),
      modelView(u.location("uModelView")), normalMatrix(u.location("uNormalMatrix")) {}

void ForwardMaterialUniforms::setModel(GLuint prog, const glm::mat4& view, const glm::mat4& model) const {
    const glm::mat4 mv = view * model;
    const glm::mat3 nm = glm::inverseTranspose(glm::mat3(mv));
    glProgramUniformMatrix4fv(prog, modelView, 1, GL_FALSE, glm::value_ptr(mv));
    glProgramUniformMatrix3fv(prog, normalMatrix, 1, GL_FALSE, glm::value_ptr(nm));
}

void ForwardMaterialUniforms::set(GLuint prog, const GpuMaterial& m) const {
    material.set(prog, m);
    glProgramUniform3fv(prog, emission, 1, glm::value_ptr(m.emission));
    glProgramUniform1i(prog, hasEmissive, m.emissiveMap != 0);
    glBindTextureUnit(kEmissiveUnit, m.emissiveMap);
}

void finishForwardDraws(GLuint fbo) {
    unbindMaterialTextures();
    glBindTextureUnit(kEmissiveUnit, 0);
    unbindForwardLighting();
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, 0, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
}

fg::ResourceId addForwardOpaquePass(fg::FrameGraph& graph, ForwardPass& state, LocalLightPass& localLights,
                                    const FrameData& frame, const GBuffer& depthPrepass, const ForwardLighting& lighting) {
    const OpaqueData& d = graph.addPass<OpaqueData>(
        "forward_opaque", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, OpaqueData& data) {
            data.depth = b.read(depthPrepass.depth, fg::Usage::DepthTest);
            data.reads = declareForwardLighting(b, localLights, lighting);
            data.hdr = b.create("hdr", {frame.width, frame.height, GL_RGBA16F}, fg::Usage::ColorAttachment);
            readPosedVertices(b, frame);
        },
        [&state, &localLights, frame, lighting](const OpaqueData& data, const fg::PassResources& res) {
            if (!state.fbo) state.fbo = gl::makeFramebuffer("forward");
            const GLuint fbo = state.fbo.id();
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, res.texture(data.hdr), 0);
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(data.depth), 0);
            glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
            const float zero[4] = {0, 0, 0, 0};
            glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);  // background: the sky pass fills it
            bindForwardLighting(state, localLights, frame, lighting, data.reads, res, {});
            const GLuint prog = state.program.id();
            {
                gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
                gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
                gl::ScopedEnable cull(GL_CULL_FACE, false);  // two-sided, as in the G-buffer pass
                gl::ScopedEnable blend(GL_BLEND, false);
                gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
                gl::ScopedRasterState saved;
                setGBufferDepthTest(frame.settings->gbuffer);  // the pre-pass's clip control
                glDepthFunc(GL_EQUAL);  // each visible fragment once: the one the pre-pass kept
                glDepthMask(GL_FALSE);
                glUseProgram(prog);
                const ForwardMaterialUniforms material(gl::Uniforms(frame.shaders, prog));
                for (const auto& mesh : frame.gpu->meshes) {
                    material.setModel(prog, frame.view, mesh.model);
                    glBindVertexArray(mesh.vao.id());
                    for (const auto& dr : mesh.draws) {
                        const GpuMaterial& m = frame.gpu->materials[size_t(dr.material)];
                        if (m.alphaBlend) continue;  // the transparent pass draws it
                        material.set(prog, m);
                        glDrawElements(GL_TRIANGLES, GLsizei(dr.indexCount), GL_UNSIGNED_INT,
                                       reinterpret_cast<const void*>(size_t(dr.firstIndex) * sizeof(uint32_t)));
                    }
                }
                glBindVertexArray(0);
                glUseProgram(0);
            }
            finishForwardDraws(fbo);
        });
    return d.hdr;
}

}  // namespace lp
