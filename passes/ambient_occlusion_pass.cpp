#include "passes/ambient_occlusion_pass.hpp"

#include <algorithm>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

namespace {
constexpr GLuint kDepthUnit = 12;  // uAoDepth in ambient_occlusion.comp, _blur.comp and _denoise.comp
constexpr GLuint kRawUnit = 13;    // uRaw in ambient_occlusion_blur.comp, uBlurred in _denoise.comp

struct DepthData {
    GBuffer in;
    fg::ResourceId depth;
};
struct GtaoData {
    GBuffer in;
    fg::ResourceId depth, raw;
};
struct BlurData {
    GBuffer in;
    fg::ResourceId depth, raw, blurred;
};
struct DenoiseData {
    GBuffer in;
    fg::ResourceId depth, blurred, ao;
};

int scaleOf(const FrameData& frame) { return frame.settings->ao.resolution == AoResolution::Half ? 2 : 1; }

// `file`'s program for the frame's G-buffer layout (compiled again when it changed).
GLuint programFor(gl::Program& program, GBufferProgramKey& key, const FrameData& frame, const char* file) {
    return programForLayout(program, key, frame, [&](const std::vector<std::string>& defines) {
               return frame.shaders->compute(file, defines);
           }).id();
}


// Runs `prog` once per texel of a w x h target bound as image 0 in `format`, with the G-buffer bound,
// and puts the bindings it made back to 0 (the texture units in `units` too).
void dispatchOver(GLuint prog, const fg::PassResources& res, const GBuffer& g, const FrameData& frame,
                  GLuint target, GLenum format, int w, int h, std::initializer_list<GLuint> units) {
    bindGBuffer(prog, res, g, frame, false);
    glBindImageTexture(0, target, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    glUseProgram(prog);
    gl::dispatch2D(w, h);
    glUseProgram(0);
    unbindGBuffer();
    for (GLuint u : units) glBindTextureUnit(u, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
}
}  // namespace

const std::array<const char*, 4>& ambientOcclusionPassNames() {
    static const std::array<const char*, 4> names = {"ao_depth", "ao", "ao_blur", "ao_denoise"};
    return names;
}

glm::ivec2 aoRawSize(const FrameData& frame) {
    const int s = scaleOf(frame);
    return {std::max(1, (frame.width + s - 1) / s), std::max(1, (frame.height + s - 1) / s)};
}

fg::ResourceId addAmbientOcclusionPasses(fg::FrameGraph& graph, AmbientOcclusionPass& state, const FrameData& frame,
                                         const GBuffer& gbuffer) {
    const glm::ivec2 rawSize = aoRawSize(frame);
    const int scale = scaleOf(frame);

    const DepthData& dd = graph.addPass<DepthData>(
        "ao_depth", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, DepthData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.depth = b.create("ao.depth", {rawSize.x, rawSize.y, GL_R32F}, fg::Usage::ImageStore);
        },
        [&state, frame, rawSize, scale](const DepthData& data, const fg::PassResources& res) {
            const GLuint prog = programFor(state.depth, state.depthLayout, frame, "ambient_occlusion_depth.comp");
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uScale", scale);
            dispatchOver(prog, res, data.in, frame, res.texture(data.depth), GL_R32F, rawSize.x, rawSize.y, {});
        });
    const fg::ResourceId depth = dd.depth;

    const GtaoData& g = graph.addPass<GtaoData>(
        "ao", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, GtaoData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.depth = b.read(depth, fg::Usage::Sampled);
            data.raw = b.create("ao.raw", {rawSize.x, rawSize.y, GL_R16F}, fg::Usage::ImageStore);
        },
        [&state, frame, rawSize, scale](const GtaoData& data, const fg::PassResources& res) {
            const GLuint prog = programFor(state.gtao, state.gtaoLayout, frame, "ambient_occlusion.comp");
            const gl::Uniforms u(frame.shaders, prog);
            const AoSettings& s = frame.settings->ao;
            u.set("uScale", scale);
            u.set("uRadius", s.radius);
            u.set("uDirections", s.directions);
            u.set("uSteps", s.steps);
            // projection[1][1] = 1 / tan(fov / 2): a metre at eye depth 1 spans height / 2 x that pixels.
            u.set("uPixelsPerMetre", 0.5f * float(frame.height) * frame.projection[1][1]);
            glBindTextureUnit(kDepthUnit, res.texture(data.depth));
            dispatchOver(prog, res, data.in, frame, res.texture(data.raw), GL_R16F, rawSize.x, rawSize.y,
                         {kDepthUnit});
        });
    const fg::ResourceId raw = g.raw;

    const BlurData& bl = graph.addPass<BlurData>(
        "ao_blur", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, BlurData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.depth = b.read(depth, fg::Usage::Sampled);
            data.raw = b.read(raw, fg::Usage::Sampled);
            data.blurred = b.create("ao.blurred", {rawSize.x, rawSize.y, GL_R16F}, fg::Usage::ImageStore);
        },
        [&state, frame, rawSize, scale](const BlurData& data, const fg::PassResources& res) {
            const GLuint prog = programFor(state.blur, state.blurLayout, frame, "ambient_occlusion_blur.comp");
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uScale", scale);
            glBindTextureUnit(kDepthUnit, res.texture(data.depth));
            glBindTextureUnit(kRawUnit, res.texture(data.raw));
            dispatchOver(prog, res, data.in, frame, res.texture(data.blurred), GL_R16F, rawSize.x, rawSize.y,
                         {kDepthUnit, kRawUnit});
        });
    const fg::ResourceId blurred = bl.blurred;

    const DenoiseData& d = graph.addPass<DenoiseData>(
        "ao_denoise", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, DenoiseData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, false);
            data.depth = b.read(depth, fg::Usage::Sampled);
            data.blurred = b.read(blurred, fg::Usage::Sampled);
            data.ao = b.create("ao", {frame.width, frame.height, GL_R8}, fg::Usage::ImageStore);
        },
        [&state, frame, scale](const DenoiseData& data, const fg::PassResources& res) {
            const GLuint prog = programFor(state.denoise, state.denoiseLayout, frame, "ambient_occlusion_denoise.comp");
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uScale", scale);
            u.set("uIntensity", frame.settings->ao.intensity);
            glBindTextureUnit(kDepthUnit, res.texture(data.depth));
            glBindTextureUnit(kRawUnit, res.texture(data.blurred));
            dispatchOver(prog, res, data.in, frame, res.texture(data.ao), GL_R8, frame.width, frame.height,
                         {kDepthUnit, kRawUnit});
        });
    return d.ao;
}

}  // namespace lp
