#include "passes/ambient_occlusion_pass.hpp"

#include <algorithm>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
constexpr GLuint kRawUnit = 13;  // uRaw in ambient_occlusion_denoise.comp

struct GtaoData {
    GBuffer in;
    fg::ResourceId raw;
};
struct DenoiseData {
    GBuffer in;
    fg::ResourceId raw, ao;
};

int scaleOf(const FrameData& frame) { return frame.settings->ao.resolution == AoResolution::Half ? 2 : 1; }
}  // namespace

glm::ivec2 aoRawSize(const FrameData& frame) {
    const int s = scaleOf(frame);
    return {std::max(1, (frame.width + s - 1) / s), std::max(1, (frame.height + s - 1) / s)};
}

fg::ResourceId addAmbientOcclusionPasses(fg::FrameGraph& graph, AmbientOcclusionPass& state, const FrameData& frame,
                                         const GBuffer& gbuffer) {
    const glm::ivec2 rawSize = aoRawSize(frame);
    const GtaoData& g = graph.addPass<GtaoData>(
        "ao", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, GtaoData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.raw = b.create("ao.raw", {rawSize.x, rawSize.y, GL_RG16F}, fg::Usage::ImageStore);
        },
        [&state, frame, rawSize](const GtaoData& data, const fg::PassResources& res) {
            programForLayout(state.gtao, state.gtaoLayout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("ambient_occlusion.comp", defines);
            });
            const AoSettings& s = frame.settings->ao;
            const GLuint prog = state.gtao.id();
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uScale"), scaleOf(frame));
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uRadius"), s.radius);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uDirections"), s.directions);
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uSteps"), s.steps);
            // projection[1][1] = 1 / tan(fov / 2): a metre at eye depth 1 spans height / 2 x that pixels.
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uPixelsPerMetre"),
                               0.5f * float(frame.height) * frame.projection[1][1]);
            bindGBuffer(prog, res, data.in, frame, false);
            glBindImageTexture(0, res.texture(data.raw), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
            glUseProgram(prog);
            gl::dispatch2D(rawSize.x, rawSize.y);
            glUseProgram(0);
            unbindGBuffer();
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
        });
    const fg::ResourceId raw = g.raw;
    const DenoiseData& d = graph.addPass<DenoiseData>(
        "ao_denoise", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, DenoiseData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.raw = b.read(raw, fg::Usage::Sampled);
            data.ao = b.create("ao", {frame.width, frame.height, GL_R8}, fg::Usage::ImageStore);
        },
        [&state, frame](const DenoiseData& data, const fg::PassResources& res) {
            programForLayout(state.denoise, state.denoiseLayout, frame, [&](const std::vector<std::string>& defines) {
                return frame.shaders->compute("ambient_occlusion_denoise.comp", defines);
            });
            const GLuint prog = state.denoise.id();
            glProgramUniform1i(prog, glGetUniformLocation(prog, "uScale"), scaleOf(frame));
            glProgramUniform1f(prog, glGetUniformLocation(prog, "uIntensity"), frame.settings->ao.intensity);
            bindGBuffer(prog, res, data.in, frame, false);
            glBindTextureUnit(kRawUnit, res.texture(data.raw));
            glBindImageTexture(0, res.texture(data.ao), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
            glUseProgram(prog);
            gl::dispatch2D(frame.width, frame.height);
            glUseProgram(0);
            unbindGBuffer();
            glBindTextureUnit(kRawUnit, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8);
        });
    return d.ao;
}

}  // namespace lp
