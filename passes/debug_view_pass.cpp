#include "passes/debug_view_pass.hpp"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

#include "engine/render/exposure.hpp"
#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

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
        case DebugView::WorldPosition: return 9;
        case DebugView::EyeVector: return 10;
        case DebugView::DepthFitted: return 11;
        case DebugView::Tangent: return 12;
        case DebugView::Velocity: return 13;
        case DebugView::Ao: return 14;
        case DebugView::Metallic: case DebugView::Roughness: case DebugView::Occlusion: return 15;
        case DebugView::BaseColor: return 16;
        default: return 0;
    }
}

struct EnvironmentData {
    GBuffer in;
    EnvironmentTextures environment;
    fg::ResourceId ldr;
};

// The environment views (ibl_debug.comp): the cube, the irradiance cube, one prefiltered mip, the
// DFG LUT, tone-mapped into a new RGBA8 image.
fg::ResourceId addEnvironmentViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                      const GBuffer& gbuffer, const EnvironmentTextures& environment, DebugView view) {
    const int mode = view == DebugView::Environment ? 1 : view == DebugView::Irradiance ? 2
                     : view == DebugView::Prefiltered ? 3 : 4;
    const bool bake = mode == 2 || mode == 3;
    const EnvironmentData& d = graph.addPass<EnvironmentData>(
        "debug_view", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, EnvironmentData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            constexpr fg::Usage sampled = fg::Usage::Sampled;
            data.environment.cube = b.read(environment.cube, sampled);
            if (bake) {
                data.environment.irradiance = b.read(environment.irradiance, sampled);
                data.environment.prefiltered = b.read(environment.prefiltered, sampled);
            }
            data.environment.dfg = b.read(environment.dfg, sampled);
            data.ldr = b.create("ldr.debug", {frame.width, frame.height, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame, mode, bake](const EnvironmentData& data, const fg::PassResources& res) {
            const EnvironmentSettings& s = frame.settings->environment;
            const BakedEnvironment& env = frame.environments->get(*frame.scene, s, *frame.shaders, bake);  // SH, levels
            programForLayout(state.environmentProgram, state.environmentLayout, frame,
                             [&](const std::vector<std::string>& defines) {
                                 return frame.shaders->compute("ibl_debug.comp", defines);
                             });
            const GLuint prog = state.environmentProgram.id();
            const gl::Uniforms u(frame.shaders, prog);
            if (bake) glProgramUniform3fv(prog, gl::Uniforms(frame.shaders, prog).location("uSh"), 9, glm::value_ptr(env.sh[0]));
            const float maxMip = bake ? float(env.prefiltered.levels - 1) : 0.0f;
            u.set("uMode", mode);
            u.set("uDiffuseFromCube", s.diffuse == IrradianceSource::Cubemap);
            u.set("uEyeToWorld", glm::transpose(glm::mat3(frame.view)));
            u.set("uInvProjection", glm::inverse(frame.projection));
            // Without a map the environment is the plain colour, already scaled here.
            u.set("uIntensity", frame.scene->environment.intensity);
            u.set("uMip", std::min(float(s.debugMip), maxMip));
            u.set("uExposureEV", exposureEvBase(*frame.settings, *frame.scene));
            u.set("uOperator", int(s.toneMap));
            gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
            bindGBuffer(prog, res, data.in, frame, false);
            glBindTextureUnit(7, res.texture(data.environment.cube));
            glBindTextureUnit(8, bake ? res.texture(data.environment.irradiance) : 0);
            glBindTextureUnit(9, bake ? res.texture(data.environment.prefiltered) : 0);
            glBindTextureUnit(10, res.texture(data.environment.dfg));
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            for (GLuint u : {0u, 1u, 3u, 4u, 7u, 8u, 9u, 10u}) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

}  // namespace

glm::vec2 sceneDepthRange(const FrameData& frame) {
    glm::vec3 lo, hi;
    frame.scene->bounds(lo, hi);
    float nearest = frame.farPlane, farthest = frame.nearPlane;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
        const float depth = -(frame.view * glm::vec4(p, 1.0f)).z;
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    nearest = std::clamp(nearest, frame.nearPlane, frame.farPlane);
    farthest = std::clamp(farthest, nearest, frame.farPlane);
    if (!(farthest > nearest)) return {frame.nearPlane, frame.farPlane};  // a flat or empty scene
    return {nearest, farthest};
}

GBufferChannels channelsForView(DebugView view) {
    GBufferChannels c;
    c.texcoord = view == DebugView::Texcoords;
    c.tangent = view == DebugView::Tangent;
    c.velocity = view == DebugView::Velocity;
    c.materialInput = materialInputShown(view) != 0;
    return c;
}

fg::ResourceId addDebugViewPass(fg::FrameGraph& graph, DebugViewPass& state, const FrameData& frame,
                                const GBuffer& gbuffer, const ShadowMaps& shadowMaps,
                                const EnvironmentTextures& environment, DebugView view, fg::ResourceId ao) {
    if (isEnvironmentView(view)) return addEnvironmentViewPass(graph, state, frame, gbuffer, environment, view);
    const int mode = modeOf(view);
    if (mode == 0) throw Error(std::string("debug view '") + viewName(view) + "' is not a G-buffer channel");
    const LightShadowMap* shadowMap = nullptr;  // the shadowmap view's light
    if (view == DebugView::ShadowMap) {
        const int light = frame.settings->shadows.debugLight;
        for (const auto& m : shadowMaps)
            if (m.light == light) shadowMap = &m;
        if (!shadowMap)
            throw Error("view 'shadowmap': directional light " + std::to_string(light) + " has no shadow map (" +
                        std::to_string(frameDirectionalLights(frame).size()) +
                        " directional lights; its \"shadows\" is false, --no-shadows, or it is past the first " +
                        std::to_string(kMaxShadowedLights) + " shadowed lights)");
    }
    const Data& d = graph.addPass<Data>(
        std::string("debug_view"), fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            if (mode == 7 || mode == 8 || mode >= 12) {
                fg::ResourceId ch = shadowMap     ? shadowMap->depth
                                    : mode == 12 ? gbuffer.tangent
                                    : mode == 13 ? gbuffer.velocity
                                    : mode == 14 ? ao
                                    : mode >= 15 ? gbuffer.materialInput
                                                 : gbuffer.texcoord;
                if (!ch.valid())
                    throw Error(std::string("debug view '") + viewName(view) + "': the G-buffer lacks its channel");
                data.channel = b.read(ch, fg::Usage::Sampled);
            } else {
                data.in = gbuffer;
                readGBuffer(b, gbuffer, true);
            }
            data.ldr = b.create("ldr.debug", {frame.width, frame.height, GL_RGBA8}, fg::Usage::ImageStore);
        },
        [&state, frame, mode, grid = shadowMap ? glm::ivec2(shadowMap->frustum.columns, shadowMap->frustum.rows)
                                               : glm::ivec2(1)](const Data& data, const fg::PassResources& res) {
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("debug_view.comp", defines);
            });
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uMode", mode);
            u.set("uNear", frame.nearPlane);
            u.set("uFar", frame.farPlane);
            u.set("uPositionScale", 1.0f / frame.sceneExtent);
            u.set("uShadowGrid", grid);
            u.set("uOutputSize", glm::vec2(float(frame.outputWidth), float(frame.outputHeight)));
            u.set("uVelocityFullScale", kVelocityViewFullScalePixels);
            const glm::mat4 eyeToWorld = glm::inverse(frame.view);
            u.set("uEyeToWorld", eyeToWorld);
            glm::vec3 lo, hi;
            frame.scene->bounds(lo, hi);
            const glm::vec3 center = 0.5f * (lo + hi);
            const float halfSize = std::max(0.5f * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}), 1e-6f);
            u.set("uSceneCenter", center);
            u.set("uSceneHalfSize", halfSize);
            const glm::vec2 range = sceneDepthRange(frame);
            u.set("uDepthRange", range);
            if (data.channel.valid()) glBindTextureUnit(kChannelUnit, res.texture(data.channel));
            else bindGBuffer(prog, res, data.in, frame, true);
            glBindImageTexture(0, res.texture(data.ldr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            glBindTextureUnit(kChannelUnit, 0);
            unbindGBuffer();
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        });
    return d.ldr;
}

}  // namespace lp
