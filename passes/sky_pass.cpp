#include "passes/sky_pass.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId depth, cube, hdr;
};
}  // namespace

fg::ResourceId addSkyPass(fg::FrameGraph& graph, SkyPass& state, const FrameData& frame, fg::ResourceId depth,
                          fg::ResourceId environmentCube, fg::ResourceId hdr) {
    const Data& d = graph.addPass<Data>(
        "sky", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.depth = b.read(depth, fg::Usage::Sampled);
            if (environmentCube.valid()) data.cube = b.read(environmentCube, fg::Usage::Sampled);
            data.hdr = b.write(hdr, fg::Usage::ImageLoadStore);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            // Compiled for the G-buffer layout: background is depth 1, or 0 under reversed-Z.
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("sky.comp", defines);
            });
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            const Environment& environment = frame.scene->environment;
            glm::vec3 c = environment.color * environment.intensity;
            u.set("uColor", c);
            const bool hasMap = !environment.map.empty() && data.cube.valid();
            u.set("uHasMap", hasMap);
            if (hasMap) {
                glBindTextureUnit(7, res.texture(data.cube));
                u.set("uIntensity", environment.intensity);
                glm::mat4 invProjection = glm::inverse(frame.projection);
                glm::mat3 eyeToWorld = glm::transpose(glm::mat3(frame.view));
                u.set("uInvProjection", invProjection);
                u.set("uEyeToWorld", eyeToWorld);
            }
            gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
            glBindTextureUnit(0, res.texture(data.depth));
            glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindTextureUnit(7, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        });
    return d.hdr;
}

}  // namespace lp
