#include "passes/visibility_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

std::vector<VisibilityDrawRecord> visibilityDrawRecords(const SceneGpu& gpu, const std::vector<uint32_t>& meshIndexBases,
                                                        const std::vector<uint32_t>& meshVertexBases) {
    std::vector<VisibilityDrawRecord> records;
    uint32_t triangle = 0;
    for (size_t m = 0; m < gpu.meshes.size(); ++m) {
        const uint32_t indexBase = meshIndexBases.at(m), vertexBase = meshVertexBases.at(m);
        for (const GpuDraw& d : gpu.meshes[m].draws) {
            VisibilityDrawRecord r;
            r.firstTriangle = triangle;
            r.firstIndex = indexBase + d.firstIndex;
            r.vertexBase = vertexBase;
            r.mesh = uint32_t(m);
            r.material = d.material;
            r.indexCount = d.indexCount;
            records.push_back(r);
            triangle += d.indexCount / 3;
        }
    }
    return records;
}

VisibilityBuffer addVisibilityPass(fg::FrameGraph& graph, VisibilityPass& state, const FrameData& frame) {
    const int w = frame.width, h = frame.height;
    const GBufferSettings layout = frame.settings->gbuffer;
    return graph.addPass<VisibilityBuffer>(
        "gbuffer_visibility", fg::PassKind::Raster,
        [&](fg::PassBuilder& b, VisibilityBuffer& out) {
            out.depth = b.create("gbuffer.depth", {w, h, GL_DEPTH_COMPONENT32F}, fg::Usage::DepthAttachment);
            out.ids = b.create("gbuffer.visibility", {w, h, GL_R32UI}, fg::Usage::ColorAttachment);
            readPosedVertices(b, frame);
        },
        [&state, frame, layout](const VisibilityBuffer& out, const fg::PassResources& res) {
            auto build = [&](const char* define) {
                return [&frame, define](std::vector<std::string> defines) {
                    if (define) defines.push_back(define);
                    return frame.shaders->graphics("gbuffer.vert", "visibility.frag", defines);
                };
            };
            const GLuint opaque = programForLayout(state.opaque, state.opaqueLayout, frame, build(nullptr)).id();
            const GLuint masked =
                programForLayout(state.masked, state.maskedLayout, frame, build("LP_VISIBILITY_ALPHA_MASK")).id();
            if (!state.fbo) state.fbo = gl::makeFramebuffer("gbuffer_visibility");
            const GLuint fbo = state.fbo.id();
            glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(out.depth), 0);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, res.texture(out.ids), 0);
            glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
            gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
            gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
            gl::ScopedEnable cull(GL_CULL_FACE, false);  // on per draw for single-sided materials
            gl::ScopedEnable blend(GL_BLEND, false);
            gl::ScopedRasterState saved;
            setGBufferDepthTest(layout);  // reversed-Z: clip control 0..1, GL_GREATER
            glDepthMask(GL_TRUE);
            glCullFace(GL_BACK);
            // Only the depth is cleared: where it keeps the cleared value nothing was drawn, which the
            // resolve reads instead of an empty id. Clearing the ids too cost 0.59 ms at 4K on an H100
            // (2.76 -> 2.17 ms for the pass on the gallery), a fifth of the pass.
            const float farDepth = layout.position == GBufferPositionMode::ReversedZ ? 0.0f : 1.0f;
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &farDepth);

            const glm::mat4 projection = gbufferDepthProjection(frame);
            for (GLuint prog : {opaque, masked})
                glProgramUniformMatrix4fv(prog, gl::Uniforms(frame.shaders, prog).location("uProjection"), 1, GL_FALSE,
                                          glm::value_ptr(projection));
            const GLint opaqueMV = gl::Uniforms(frame.shaders, opaque).location("uModelView");
            const GLint opaqueFirst = gl::Uniforms(frame.shaders, opaque).location("uFirstTriangle");
            const GLint maskedMV = gl::Uniforms(frame.shaders, masked).location("uModelView");
            const GLint maskedFirst = gl::Uniforms(frame.shaders, masked).location("uFirstTriangle");
            auto loc = [&frame, masked](const char* name) { return gl::Uniforms(frame.shaders, masked).location(name); };
            const GLint locKd = loc("uDiffuse"), locOpacity = loc("uOpacity"), locHasD = loc("uHasDiffuseMap");
            const GLint locCutoff = loc("uAlphaCutoff"), locSecondUv = loc("uSecondUvMaps");
            uint32_t firstTriangle = 0;  // the numbering of visibilityDrawRecords
            GLuint current = 0;
            for (const auto& mesh : frame.gpu->meshes) {
                const glm::mat4 mv = frame.view * mesh.model;
                glProgramUniformMatrix4fv(opaque, opaqueMV, 1, GL_FALSE, glm::value_ptr(mv));
                glProgramUniformMatrix4fv(masked, maskedMV, 1, GL_FALSE, glm::value_ptr(mv));
                glBindVertexArray(mesh.vao.id());
                for (const auto& d : mesh.draws) {
                    const GpuMaterial& m = frame.gpu->materials[size_t(d.material)];
                    if (m.alphaBlend) {  // the transparent pass draws it; its triangles keep their numbers
                        firstTriangle += d.indexCount / 3;
                        continue;
                    }
                    const GLuint prog = m.alphaMask ? masked : opaque;
                    if (prog != current) glUseProgram(current = prog);
                    glProgramUniform1ui(prog, m.alphaMask ? maskedFirst : opaqueFirst, firstTriangle);
                    if (m.alphaMask) {
                        glProgramUniform3fv(prog, locKd, 1, glm::value_ptr(m.diffuse));
                        glProgramUniform1f(prog, locOpacity, m.opacity);
                        glProgramUniform1i(prog, locHasD, m.diffuseMap != 0);
                        glProgramUniform1f(prog, locCutoff, m.alphaCutoff);
                        glProgramUniform1ui(prog, locSecondUv, m.secondUvMaps);
                        glBindTextureUnit(0, m.diffuseMap);
                    }
                    if (m.doubleSided) glDisable(GL_CULL_FACE);
                    else glEnable(GL_CULL_FACE);
                    glDrawElements(GL_TRIANGLES, GLsizei(d.indexCount), GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(size_t(d.firstIndex) * sizeof(uint32_t)));
                    firstTriangle += d.indexCount / 3;
                }
            }
            glBindVertexArray(0);
            glBindTextureUnit(0, 0);
            glUseProgram(0);
        });
}

}  // namespace lp
