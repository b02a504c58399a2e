#include "passes/ibl_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
struct Data {
    GBuffer in;
    EnvironmentTextures environment;
    fg::ResourceId ao;  // invalid: no ambient occlusion
    fg::ResourceId hdr;
};
}  // namespace

bool isEnvironmentView(DebugView view) {
    return view == DebugView::Environment || view == DebugView::Irradiance || view == DebugView::Prefiltered ||
           view == DebugView::Dfg;
}

EnvironmentTextures importEnvironment(fg::FrameGraph& graph, const FrameData& frame, bool bake) {
    const EnvironmentSettings& s = frame.settings->environment;
    // Asked during execute, once ibl_bake (if this frame has one) has made them.
    auto baked = [frame](bool withBake) -> const BakedEnvironment& {
        return frame.environments->get(*frame.scene, frame.settings->environment, *frame.shaders, withBake);
    };
    EnvironmentTextures t;
    t.cube = graph.importTexture("environment.cube", {s.cubeSize, s.cubeSize, GL_RGBA16F, environmentCubeLevels(s), true},
                                 [baked] { return baked(false).cube.id(); });
    if (!bake) return t;
    t.irradiance = graph.importTexture("ibl.irradiance", {s.irradianceSize, s.irradianceSize, GL_RGBA16F, 1, true},
                                       [baked] { return baked(true).irradiance.id(); });
    t.prefiltered = graph.importTexture("ibl.prefiltered",
                                        {s.specularSize, s.specularSize, GL_RGBA16F, s.specularLevels, true},
                                        [baked] { return baked(true).prefiltered.id(); });
    t.dfg = graph.importTexture("ibl.dfg_lut", {s.dfgSize, s.dfgSize, GL_RG16F},
                                [frame] {
                                    return frame.environments->dfgLut(frame.settings->environment,
                                                                      frame.settings->specularMasking, *frame.shaders).id();
                                });
    return t;
}

EnvironmentTextures addIblBakePass(fg::FrameGraph& graph, const FrameData& frame, const EnvironmentTextures& in,
                                   bool bake) {
    return graph.addPass<EnvironmentTextures>(
        "ibl_bake", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, EnvironmentTextures& out) {
            // Compute shaders store into every texel of the cubes and the LUT.
            for (auto [from, to] : {std::pair{in.cube, &out.cube}, {in.irradiance, &out.irradiance},
                                    {in.prefiltered, &out.prefiltered}, {in.dfg, &out.dfg}})
                if (from.valid()) *to = b.write(from, fg::Usage::ImageStore);
        },
        [frame, bake](const EnvironmentTextures&, const fg::PassResources&) {
            frame.environments->get(*frame.scene, frame.settings->environment, *frame.shaders, bake);
            if (bake) frame.environments->dfgLut(frame.settings->environment, frame.settings->specularMasking, *frame.shaders);
        });
}

void setIblUniforms(GLuint prog, const FrameData& frame, const BakedEnvironment& env) {
    const EnvironmentSettings& s = frame.settings->environment;
    const gl::Uniforms u(frame.shaders, prog);
    u.setArray("uSh", env.sh.data(), 9);
    u.set("uDiffuseFromCube", s.diffuse == IrradianceSource::Cubemap);
    u.set("uEyeToWorld", glm::transpose(glm::mat3(frame.view)));
    u.set("uIntensity", frame.scene->environment.intensity);
    u.set("uMaxLod", float(env.prefiltered.levels - 1));
    setBrdfUniforms(prog, frame);
    u.set("uSpecularSamples", s.specular == IblSpecular::Sampled ? s.specularRuntimeSamples : 0);
    const int lights = std::min(int(env.lights.size()), kMaxEnvironmentLights);
    std::array<glm::vec3, kMaxEnvironmentLights> direction{}, irradiance{};
    std::array<float, kMaxEnvironmentLights> sinRadius{};
    for (int i = 0; i < lights; ++i) {
        direction[size_t(i)] = env.lights[size_t(i)].direction;
        irradiance[size_t(i)] = env.lights[size_t(i)].irradiance;
        sinRadius[size_t(i)] = std::sin(std::min(env.lights[size_t(i)].angularRadius, 1.5707963f));
    }
    u.set("uIblLightCount", lights);
    u.setArray("uIblLightDirection", direction.data(), kMaxEnvironmentLights);
    u.setArray("uIblLightIrradiance", irradiance.data(), kMaxEnvironmentLights);
    u.setArray("uIblLightSinRadius", sinRadius.data(), kMaxEnvironmentLights);
}

fg::ResourceId addIblPass(fg::FrameGraph& graph, IblPass& state, const FrameData& frame, const GBuffer& gbuffer,
                          const EnvironmentTextures& environment, fg::ResourceId hdr, bool lightingOnly,
                          fg::ResourceId ao) {
    const Data& d = graph.addPass<Data>(
        "ibl", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, !lightingOnly, true);
            data.environment.irradiance = b.read(environment.irradiance, fg::Usage::Sampled);
            data.environment.prefiltered = b.read(environment.prefiltered, fg::Usage::Sampled);
            data.environment.dfg = b.read(environment.dfg, fg::Usage::Sampled);
            if (ao.valid()) data.ao = b.read(ao, fg::Usage::Sampled);
            data.hdr = b.write(hdr, fg::Usage::ImageLoadStore);
        },
        [&state, frame, lightingOnly](const Data& data, const fg::PassResources& res) {
            // CPU data of the bake (SH coefficients); its textures come through the graph.
            const BakedEnvironment& env =
                frame.environments->get(*frame.scene, frame.settings->environment, *frame.shaders, true);
            programForLayout(state.program, state.layout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("ibl.comp", defines);
            });
            const GLuint prog = state.program.id();
            setIblUniforms(prog, frame, env);
            glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uLightingOnly"), lightingOnly);
            glProgramUniform1i(prog, gl::Uniforms(frame.shaders, prog).location("uAmbientOcclusion"), data.ao.valid());
            gl::ScopedEnable seamless(GL_TEXTURE_CUBE_MAP_SEAMLESS, true);
            bindGBuffer(prog, res, data.in, frame, !lightingOnly, true);
            glBindTextureUnit(7, res.texture(data.environment.irradiance));
            glBindTextureUnit(8, res.texture(data.environment.prefiltered));
            glBindTextureUnit(9, res.texture(data.environment.dfg));
            if (data.ao.valid()) glBindTextureUnit(kAoTextureUnit, res.texture(data.ao));
            glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            unbindGBuffer();
            for (GLuint u : {7u, 8u, 9u, GLuint(kAoTextureUnit)}) glBindTextureUnit(u, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
        });
    return d.hdr;
}

}  // namespace lp
