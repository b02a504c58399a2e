#include "passes/emission_pass.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

namespace {
// emission.frag's uClearcoatLayer (beside the diffuse and emissive maps on 0 and 1).
constexpr GLuint kEmissionClearcoatUnit = 2;
struct Data {
    fg::ResourceId depth, hdr;
    fg::ResourceId clearcoat;  // gbuffer.clearcoat where the G-buffer carries it: the coat over the emission
};
}  // namespace

bool sceneHasEmission(const FrameData& frame) {
    for (const ModelInstance& model : frame.scene->models)
        for (const Material& m : model.mesh.materials)
            // Blended surfaces add their emission in the transparent pass.
            if (m.alphaMode != AlphaMode::Blend && glm::any(glm::greaterThan(m.emission, glm::vec3(0.0f)))) return true;
    return false;
}

fg::ResourceId addEmissionPass(fg::FrameGraph& graph, EmissionPass& state, const FrameData& frame, const GBuffer& gbuffer,
                               fg::ResourceId hdr) {
    const Data& d = graph.addPass<Data>(
        "emission", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, Data& data) {
            data.depth = b.read(gbuffer.depth, fg::Usage::DepthTest);
            data.hdr = b.write(hdr, fg::Usage::Blend);
            readPosedVertices(b, frame);
            if (gbuffer.clearcoat.valid()) data.clearcoat = b.read(gbuffer.clearcoat, fg::Usage::Sampled);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            const GBufferSettings layout = frame.settings->gbuffer;
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->graphics("gbuffer.vert", "emission.frag", defines);
            });
            if (!state.fbo) state.fbo = gl::makeFramebuffer("emission");
            const GLuint fbo = state.fbo.id();
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(data.depth), 0);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, res.texture(data.hdr), 0);
            glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
            gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
            gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
            gl::ScopedEnable cull(GL_CULL_FACE, false);
            gl::ScopedEnable blend(GL_BLEND, true);
            gl::ScopedRasterState saved;
            setGBufferDepthTest(layout);  // the G-buffer's clip control, then only its exact depths
            glDepthFunc(GL_EQUAL);
            glDepthMask(GL_FALSE);
            glBlendEquation(GL_FUNC_ADD);
            glBlendFunc(GL_ONE, GL_ONE);

            const GLuint prog = state.program.id();
            glUseProgram(prog);
            if (data.clearcoat.valid()) glBindTextureUnit(kEmissionClearcoatUnit, res.texture(data.clearcoat));
            glProgramUniformMatrix4fv(prog, gl::Uniforms(frame.shaders, prog).location("uProjection"), 1, GL_FALSE,
                                      glm::value_ptr(gbufferDepthProjection(frame)));
            auto loc = [&frame, prog](const char* name) { return gl::Uniforms(frame.shaders, prog).location(name); };
            const GLint locMV = loc("uModelView"), locN = loc("uNormalMatrix");
            const GLint locE = loc("uEmission"), locHasE = loc("uHasEmissiveMap");
            const GLint locOpacity = loc("uOpacity"), locHasD = loc("uHasDiffuseMap"), locMask = loc("uAlphaMask");
            const GLint locCutoff = loc("uAlphaCutoff"), locTwoSided = loc("uDoubleSided"), locSecondUv = loc("uSecondUvMaps");
            for (const auto& mesh : frame.gpu->meshes) {
                bool any = false;
                for (const auto& dr : mesh.draws) {
                    const GpuMaterial& m = frame.gpu->materials[size_t(dr.material)];
                    any |= m.emissive() && !m.alphaBlend;
                }
                if (!any) continue;
                const glm::mat4 mv = frame.view * mesh.model;
                const glm::mat3 nm = glm::inverseTranspose(glm::mat3(mv));
                glProgramUniformMatrix4fv(prog, locMV, 1, GL_FALSE, glm::value_ptr(mv));
                glProgramUniformMatrix3fv(prog, locN, 1, GL_FALSE, glm::value_ptr(nm));
                glBindVertexArray(mesh.vao.id());
                for (const auto& dr : mesh.draws) {
                    const GpuMaterial& m = frame.gpu->materials[size_t(dr.material)];
                    if (!m.emissive() || m.alphaBlend) continue;  // not in the G-buffer's depth
                    glProgramUniform3fv(prog, locE, 1, glm::value_ptr(m.emission));
                    glProgramUniform1i(prog, locHasE, m.emissiveMap != 0);
                    glProgramUniform1f(prog, locOpacity, m.opacity);
                    glProgramUniform1i(prog, locHasD, m.diffuseMap != 0);
                    glProgramUniform1i(prog, locMask, m.alphaMask);
                    glProgramUniform1f(prog, locCutoff, m.alphaCutoff);
                    glProgramUniform1i(prog, locTwoSided, m.doubleSided);
                    glProgramUniform1ui(prog, locSecondUv, m.secondUvMaps);
                    glBindTextureUnit(0, m.diffuseMap);
                    glBindTextureUnit(1, m.emissiveMap);
                    glDrawElements(GL_TRIANGLES, GLsizei(dr.indexCount), GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(size_t(dr.firstIndex) * sizeof(uint32_t)));
                }
            }
            glBindVertexArray(0);
            glBindTextureUnit(0, 0);
            glBindTextureUnit(1, 0);
            glBindTextureUnit(kEmissionClearcoatUnit, 0);
            glUseProgram(0);
        });
    return d.hdr;
}

}  // namespace lp
