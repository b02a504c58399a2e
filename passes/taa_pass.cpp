#include "passes/taa_pass.hpp"

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"

namespace lp {

double halton(uint64_t index, uint32_t base) {
    double f = 1.0, r = 0.0;
    for (uint64_t i = index; i > 0; i /= base) {
        f /= base;
        r += f * double(i % base);
    }
    return r;
}

glm::vec2 taaJitterPixels(uint64_t index) {
    const uint64_t phase = index % 16 + 1;
    return {float(halton(phase, 2) - 0.5), float(halton(phase, 3) - 0.5)};
}

bool taaHistoryUsable(const TaaPass& state, const FrameData& frame, const std::string& signature) {
    return state.latest >= 0 && frame.hasPrevious && state.size == glm::ivec2(frame.outputWidth, frame.outputHeight) &&
           state.signature == signature;
}

namespace {
struct Data {
    fg::ResourceId current, velocity, history, historyVelocity, resolved, resolvedVelocity;
};
// Units of the shader's samplers; the images are 0 (colour) and 1 (velocity).
constexpr GLuint kCurrentUnit = 0, kVelocityUnit = 1, kHistoryUnit = 2, kHistoryVelocityUnit = 3;

void ensureHistory(TaaPass& state, glm::ivec2 size) {
    if (state.size == size && state.color[0]) return;
    for (int i = 0; i < 2; ++i) {
        state.color[i] = gl::makeTexture2D(GL_RGBA16F, size.x, size.y, 1, "taa.history");
        state.velocity[i] = gl::makeTexture2D(GL_RG16F, size.x, size.y, 1, "taa.history_velocity");
    }
    state.size = size;
    state.latest = -1;
}
}  // namespace

fg::ResourceId addTaaPass(fg::FrameGraph& graph, TaaPass& state, const FrameData& frame, fg::ResourceId hdr,
                          fg::ResourceId velocity, const std::string& signature) {
    const glm::ivec2 size(frame.outputWidth, frame.outputHeight);
    const bool usable = taaHistoryUsable(state, frame, signature);
    // The pair's other texture is written; its partner is read (and ignored when !usable).
    const int write = state.latest == 0 ? 1 : 0, read = 1 - write;
    TaaPass* s = &state;
    auto texture = [s, size](bool color, int index) {
        return [s, size, color, index]() -> GLuint {
            ensureHistory(*s, size);
            return color ? s->color[index].id() : s->velocity[index].id();
        };
    };
    const fg::TextureDesc colorDesc{size.x, size.y, GL_RGBA16F}, velocityDesc{size.x, size.y, GL_RG16F};
    const fg::ResourceId history = graph.importTexture("taa.history", colorDesc, texture(true, read));
    const fg::ResourceId historyVelocity = graph.importTexture("taa.history_velocity", velocityDesc, texture(false, read));
    const fg::ResourceId resolved = graph.importTexture("taa.resolved", colorDesc, texture(true, write));
    const fg::ResourceId resolvedVelocity = graph.importTexture("taa.resolved_velocity", velocityDesc, texture(false, write));
    const Data& d = graph.addPass<Data>(
        "taa", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.current = b.read(hdr, fg::Usage::Sampled);
            data.velocity = b.read(velocity, fg::Usage::Sampled);
            data.history = b.read(history, fg::Usage::Sampled);
            data.historyVelocity = b.read(historyVelocity, fg::Usage::Sampled);
            data.resolved = b.write(resolved, fg::Usage::ImageStore);
            data.resolvedVelocity = b.write(resolvedVelocity, fg::Usage::ImageStore);
        },
        [s, frame, usable, write, signature, size](const Data& data, const fg::PassResources& res) {
            if (!s->program) s->program = frame.shaders->compute("taa.comp");
            const GLuint prog = s->program.id();
            const gl::Uniforms u(frame.shaders, prog);
            u.set("uHistoryValid", usable);
            u.set("uCurrentWeight", frame.settings->aa.taaHistoryWeight);
            const GLuint units[] = {kCurrentUnit, kVelocityUnit, kHistoryUnit, kHistoryVelocityUnit};
            const fg::ResourceId inputs[] = {data.current, data.velocity, data.history, data.historyVelocity};
            for (int i = 0; i < 4; ++i) glBindTextureUnit(units[i], res.texture(inputs[i]));
            glBindImageTexture(0, res.texture(data.resolved), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glBindImageTexture(1, res.texture(data.resolvedVelocity), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
            glUseProgram(prog);
            gl::dispatch2D(size.x, size.y);
            glUseProgram(0);
            for (GLuint unit : units) glBindTextureUnit(unit, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
            s->latest = write;
            s->signature = signature;
        });
    return d.resolved;
}

}  // namespace lp
