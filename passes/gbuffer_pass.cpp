#include "passes/gbuffer_pass.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/scene_gpu.hpp"

namespace lp {

GBuffer addGBufferPass(fg::FrameGraph& graph, GBufferPass& state, const FrameData& frame, GBufferChannels channels) {
    const int w = frame.width, h = frame.height;
    return graph.addPass<GBuffer>(
        "gbuffer",
        [&](fg::PassBuilder& b, GBuffer& out) {
            out.depth = b.create("gbuffer.depth", {w, h, GL_DEPTH_COMPONENT32F});
            out.normal = b.create("gbuffer.normal", {w, h, GL_RGBA32F});
            out.diffuse = b.create("gbuffer.diffuse", {w, h, GL_RGBA8});
            if (channels.position) out.position = b.create("gbuffer.position", {w, h, GL_RGBA32F});
            out.specular = b.create("gbuffer.specular", {w, h, GL_RGBA16F});
            if (channels.texcoord) out.texcoord = b.create("gbuffer.texcoord", {w, h, GL_RG32F});
        },
        [&state, frame](const GBuffer& out, const fg::PassResources& res) {
            if (!state.program) {
                state.program = frame.shaders->graphics("gbuffer.vert", "gbuffer.frag");
                state.fbo = gl::makeFramebuffer("gbuffer");
            }
            const GLuint fbo = state.fbo.id();
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(out.depth), 0);
            const fg::ResourceId colour[5] = {out.normal, out.diffuse, out.position, out.specular, out.texcoord};
            GLenum buffers[5];
            for (int i = 0; i < 5; ++i) {
                GLuint tex = colour[i].valid() ? res.texture(colour[i]) : 0;
                glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, tex, 0);
                buffers[i] = tex ? GL_COLOR_ATTACHMENT0 + i : GL_NONE;
            }
            glNamedFramebufferDrawBuffers(fbo, 5, buffers);
            gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
            gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
            gl::ScopedEnable cull(GL_CULL_FACE, false);  // thin walls and open meshes are two-sided
            gl::ScopedEnable blend(GL_BLEND, false);
            glDepthFunc(GL_LESS);
            glDepthMask(GL_TRUE);
            const float zero[4] = {0, 0, 0, 0};
            for (int i = 0; i < 5; ++i)
                if (buffers[i] != GL_NONE) glClearNamedFramebufferfv(fbo, GL_COLOR, i, zero);
            const float one = 1.0f;
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);

            const GLuint prog = state.program.id();
            glUseProgram(prog);
            glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "uProjection"), 1, GL_FALSE,
                                      glm::value_ptr(frame.projection));
            const GLint locMV = glGetUniformLocation(prog, "uModelView");
            const GLint locN = glGetUniformLocation(prog, "uNormalMatrix");
            const GLint locKd = glGetUniformLocation(prog, "uDiffuse");
            const GLint locKs = glGetUniformLocation(prog, "uSpecular");
            const GLint locNs = glGetUniformLocation(prog, "uShininess");
            const GLint locHasD = glGetUniformLocation(prog, "uHasDiffuseMap");
            const GLint locHasB = glGetUniformLocation(prog, "uHasBumpMap");
            const GLint locBs = glGetUniformLocation(prog, "uBumpScale");
            for (const auto& mesh : frame.gpu->meshes) {
                glm::mat4 mv = frame.view * mesh.model;
                glm::mat3 nm = glm::inverseTranspose(glm::mat3(mv));
                glProgramUniformMatrix4fv(prog, locMV, 1, GL_FALSE, glm::value_ptr(mv));
                glProgramUniformMatrix3fv(prog, locN, 1, GL_FALSE, glm::value_ptr(nm));
                glBindVertexArray(mesh.vao.id());
                for (const auto& d : mesh.draws) {
                    const GpuMaterial& m = frame.gpu->materials[size_t(d.material)];
                    glProgramUniform3fv(prog, locKd, 1, glm::value_ptr(m.diffuse));
                    glProgramUniform3fv(prog, locKs, 1, glm::value_ptr(m.specular));
                    glProgramUniform1f(prog, locNs, m.shininess);
                    glProgramUniform1i(prog, locHasD, m.diffuseMap != 0);
                    glProgramUniform1i(prog, locHasB, m.bumpMap != 0);
                    glProgramUniform1f(prog, locBs, m.bumpScale);
                    glBindTextureUnit(0, m.diffuseMap);
                    glBindTextureUnit(1, m.bumpMap);
                    glDrawElements(GL_TRIANGLES, GLsizei(d.indexCount), GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(size_t(d.firstIndex) * sizeof(uint32_t)));
                }
            }
            glBindVertexArray(0);
            glBindTextureUnit(0, 0);
            glBindTextureUnit(1, 0);
            glUseProgram(0);
        });
}

}  // namespace lp
