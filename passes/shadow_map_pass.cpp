#include "passes/shadow_map_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/render/scene_gpu.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId depth;
};

}  // namespace

ShadowMaps addShadowMapPasses(fg::FrameGraph& graph, ShadowMapPass& state, const FrameData& frame) {
    ShadowMaps maps;
    // Say why a frame has no (or fewer) shadow passes: 'lightpass graph' and the viewer show it.
    const auto& lights = frame.scene->directionalLights;
    int casting = 0;
    for (const auto& l : lights) casting += (l.castsShadows || frame.settings->allPasses) ? 1 : 0;
    if (casting == 0) graph.skipPass("shadow_map", "no directional light casts shadows");
    else if (!frame.settings->shadows.enabled) graph.skipPass("shadow_map", "shadows are off (--no-shadows)");
    else if (casting > kMaxShadowedLights)
        graph.skipPass("shadow_map", std::to_string(casting - kMaxShadowedLights) + " shadow-casting lights past the first " +
                                         std::to_string(kMaxShadowedLights) + " are unshadowed");
    for (int light : shadowCastingLights(frame)) {
        LightShadowMap map;
        map.light = light;
        map.frustum = fitShadowFrustum(frame, frame.scene->directionalLights[size_t(light)].direction);
        const ShadowFrustum& fr = map.frustum;
        const std::string name = "shadow_map_" + std::to_string(light);
        // A small scene needs fewer cascades than asked for: say which were dropped and why.
        if (const std::string why = droppedCascadesReason(fr, frame.settings->shadows.cascades); !why.empty())
            graph.skipPass(name + " cascades", why);
        const fg::TextureDesc desc{fr.tileSize * fr.columns, fr.tileSize * fr.rows, GL_DEPTH_COMPONENT32F};
        const Data& data = graph.addPass<Data>(
            name, fg::PassKind::Raster,
            [&](fg::PassBuilder& b, Data& out) { out.depth = b.create(name + ".depth", desc, fg::Usage::DepthAttachment); },
            [&state, frame, fr](const Data& out, const fg::PassResources& res) {
                const fg::ResourceId depth = out.depth;
                if (!state.program) {
                    state.program = frame.shaders->graphics("shadow_depth.vert", "shadow_depth.geom", "shadow_depth.frag",
                                                            {"LP_SHADOW_CONSERVATIVE"});
                    state.fbo = gl::makeFramebuffer("shadow_map");
                }
                const GLuint fbo = state.fbo.id();
                glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, res.texture(depth), 0);
                glNamedFramebufferDrawBuffer(fbo, GL_NONE);
                glNamedFramebufferReadBuffer(fbo, GL_NONE);
                const fg::TextureDesc& d = res.desc(depth);
                gl::ScopedFramebuffer bind(fbo, d.width, d.height);
                gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);
                gl::ScopedEnable cull(GL_CULL_FACE, false);  // thin walls and open meshes cast from both sides
                gl::ScopedEnable blend(GL_BLEND, false);
                gl::ScopedEnable clamp(GL_DEPTH_CLAMP, true);  // casters past the light's near plane still cast
                gl::ScopedRasterState saved;  // depth function and mask
                glDepthFunc(GL_LESS);
                glDepthMask(GL_TRUE);
                const float one = 1.0f;
                glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);

                const GLuint prog = state.program.id();
                const GLint locMvp = glGetUniformLocation(prog, "uModelToClip");
                const GLint locViewport = glGetUniformLocation(prog, "uViewport");
                GLint clipDepth = GL_NEGATIVE_ONE_TO_ONE;
                glGetIntegerv(GL_CLIP_DEPTH_MODE, &clipDepth);
                glProgramUniform1i(prog, glGetUniformLocation(prog, "uDepthZeroToOne"), clipDepth == GL_ZERO_TO_ONE ? 1 : 0);
                // Slope-scaled bias against acne, for the faces towards the light only (shadow_depth.frag);
                // the constant part is the receiver's (see shadow.glsl).
                glProgramUniform1f(prog, glGetUniformLocation(prog, "uSlopeBias"), frame.settings->shadows.slopeBias);
                glUseProgram(prog);
                for (size_t c = 0; c < fr.cascades.size(); ++c) {
                    const GLint x = GLint(c % size_t(fr.columns)) * fr.tileSize;
                    const GLint y = GLint(c / size_t(fr.columns)) * fr.tileSize;
                    glViewport(x, y, fr.tileSize, fr.tileSize);
                    glProgramUniform4f(prog, locViewport, float(x), float(y), float(fr.tileSize), float(fr.tileSize));
                    drawShadowCasters(frame, prog, locMvp, fr.cascades[c].worldToClip);
                }
                glBindVertexArray(0);
                glUseProgram(0);
                glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
            });
        map.depth = data.depth;
        maps.push_back(std::move(map));
    }
    return maps;
}

void drawShadowCasters(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip) {
    for (const auto& mesh : frame.gpu->meshes) {
        const glm::mat4 mvp = worldToClip * mesh.model;
        glProgramUniformMatrix4fv(prog, locMvp, 1, GL_FALSE, glm::value_ptr(mvp));
        glBindVertexArray(mesh.vao.id());
        for (const auto& draw : mesh.draws) {
            if (frame.gpu->materials[size_t(draw.material)].alphaBlend) continue;  // blended surfaces cast no shadow
            glDrawElements(GL_TRIANGLES, GLsizei(draw.indexCount), GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(size_t(draw.firstIndex) * sizeof(uint32_t)));
        }
    }
}

}  // namespace lp
