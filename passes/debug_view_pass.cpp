#include "passes/debug_view_pass.hpp"

#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    GBuffer in;                // the decoded channels' targets (modes 1-6)
    fg::ResourceId channel;    // texcoords or the shadow-map atlas (modes 7, 8)
    fg::ResourceId ldr;
};
constexpr GLuint kChannelUnit = 12;  // uChannel in debug_view.comp

int modeOf(DebugView v) {
    switch (v) {
        case DebugView::Depth: return 1;
        case DebugView::Normals: return 2;
        case DebugView::Diffuse: return 3;
        case DebugView::Position: return 4;
        case DebugView::Shininess: return 5;
        case DebugView::Specular: return 6;
        case DebugView::Texcoords: return 7;
        case DebugView::ShadowMap: return 8;
        default: return 0;
    }
}

}  // namespace

GBufferChannels channelsForView(DebugView view) {
    GBufferChannels c;
    c.texcoord = view == DebugView::Texcoords;
    return c;
}

fg::ResourceId addDebugViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                const GBuffer& gbuffer, DebugView view) {
    if (isEnvironmentView(view) && state.ibl)
        return addIblDebugViewPass(graph, *state.ibl, frame, gbuffer, view);
    const int mode = modeOf(view);
    if (mode == 0) throw Error(std::string("debug view '") + viewName(view) + "' is not a G-buffer channel");
    const LightShadowMap* shadowMap = nullptr;  // the shadowmap view's light
    if (view == DebugView::ShadowMap) {
        const int light = frame.settings->shadows.debugLight;
        if (state.shadowMaps)
            for (const auto& m : *state.shadowMaps)
                if (m.light == light) shadowMap = &m;
        if (!shadowMap)
            throw Error("view 'shadowmap': directional light " + std::to_string(light) + " has no shadow map (" +
                        std::to_string(frame.scene->directionalLights.size()) +
                        " directional lights; its \"shadows\" is false, --no-shadows, or it is past the first " +
                        std::to_string(kMaxShadowedLights) + " shadowed lights)");
    }
    const Data& d = graph.addPass<Data>(
        std::string("debug_view"),
        [&](fg::PassBuilder& b, Data& data) {
            if (mode == 7 || mode == 8) {
                fg::ResourceId ch = shadowMap ? shadowMap->depth : gbuffer.texcoord;
                if (!ch.valid())
                    throw Error(std::string("debug view '") + viewName(view) + "': the G-buffer lacks its channel");
                data.channel = b.read(ch);
            } else {
                data.in = gbuffer;
                readGBuffer(b, gbuffer, true);
            }
            data.ldr = b.create("ldr.debug", {frame.width, frame.height, GL_RGBA8});
        },
        [&state, frame, mode, grid = shadowMap ? glm::ivec2(shadowMap->frustum.columns, shadowMap->frustum.rows)
                                               : glm::ivec2(1)](const Data& data, const fg::PassResources& res) {
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("debug_view.comp", defines);
            });
            const GLuint prog = state.program.id();
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uMode"), mode);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uNear"), frame.nearPlane);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uFar"), frame.farPlane);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uPositionScale"), 1.0f / frame.sceneExtent);
            glProgramUniform2i(prog, glGetUniformLocation(prog, "uShadowGrid"), grid.x, grid.y);
            if (data.channel.valid()) glBindTextureUnit(kChannelUnit, res.texture(data.channel));
            else bindGBuffer(prog, res, data.in, frame, true);
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glUseProgram(0);
            glBindTextureUnit(kChannelUnit, 0);
            unbindGBuffer();
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

}  // namespace lp
