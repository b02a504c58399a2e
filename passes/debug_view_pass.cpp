#include "passes/debug_view_pass.hpp"

#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
struct Data {
    fg::ResourceId channel, ldr;
};

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

fg::ResourceId channelOf(const GBuffer& g, DebugView v) {
    switch (v) {
        case DebugView::Depth: return g.depth;
        case DebugView::Normals: return g.normal;
        case DebugView::Diffuse: return g.diffuse;
        case DebugView::Position: return g.position;
        case DebugView::Shininess:
        case DebugView::Specular: return g.specular;
        case DebugView::Texcoords: return g.texcoord;
        default: return {};
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
            fg::ResourceId ch = shadowMap ? shadowMap->depth : channelOf(gbuffer, view);
            if (!ch.valid()) throw Error(std::string("debug view '") + viewName(view) + "': the G-buffer lacks its channel");
            data.channel = b.read(ch);
            data.ldr = b.create("ldr.debug", {frame.width, frame.height, GL_RGBA8});
        },
        [&state, frame, mode, grid = shadowMap ? glm::ivec2(shadowMap->frustum.columns, shadowMap->frustum.rows)
                                               : glm::ivec2(1)](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("debug_view.comp");
            const GLuint prog = state.program.id();
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uMode"), mode);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uNear"), frame.nearPlane);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uFar"), frame.farPlane);
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uPositionScale"), 1.0f / frame.sceneExtent);
            glProgramUniform2i(prog, glGetUniformLocation(prog, "uShadowGrid"), grid.x, grid.y);
            glBindTextureUnit(0, res.texture(data.channel));
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                            GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

}  // namespace lp
