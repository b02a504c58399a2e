#include "passes/auto_exposure_pass.hpp"

#include <algorithm>
#include <cmath>

#include "engine/gl/shader.hpp"
#include "engine/gl/state.hpp"

namespace lp {

namespace {
// shaders/common/exposure.glsl
constexpr int kBins = 128;
constexpr double kMinLog2 = -16.0, kMaxLog2 = 16.0, kWeightScale = 64.0, kCentreSigma = 0.35, kLow = 0.20,
                 kHigh = 0.70, kKey = 0.18;

struct Data {
    fg::ResourceId hdr, histogram, exposure;
};
}  // namespace

fg::ResourceId addAutoExposurePass(fg::FrameGraph& graph, AutoExposurePass& state, const FrameData& frame,
                                   fg::ResourceId hdr) {
    const Data& d = graph.addPass<Data>(
        "auto_exposure", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.read(hdr, fg::Usage::Sampled);
            // Row 0 counts, row 1 places within the bins: cleared, then added to with atomics.
            data.histogram = b.create("exposure.histogram", {kBins, 2, GL_R32UI},
                                      fg::Usage::Transfer | fg::Usage::ImageLoadStore);
            data.exposure = b.create("exposure", {1, 1, GL_R32F}, fg::Usage::ImageStore);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            if (!state.histogram) state.histogram = frame.shaders->compute("auto_exposure_histogram.comp");
            if (!state.average) state.average = frame.shaders->compute("auto_exposure_average.comp");
            const GLuint histogram = res.texture(data.histogram);
            const GLuint zero = 0;
            glClearTexImage(histogram, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            const fg::TextureDesc& in = res.desc(data.hdr);
            glBindTextureUnit(0, res.texture(data.hdr));
            glBindImageTexture(0, histogram, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
            glUseProgram(state.histogram.id());
            gl::dispatch2D(in.width, in.height, 16);
            glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);  // the average reads the histogram (same pass)
            glBindImageTexture(1, res.texture(data.exposure), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
            glUseProgram(state.average.id());
            glDispatchCompute(1, 1, 1);
            glUseProgram(0);
            glBindTextureUnit(0, 0);
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
            glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        });
    return d.exposure;
}

double autoExposureEvReference(const std::vector<float>& luminances, int width, int height) {
    std::vector<double> count(kBins, 0.0), place(kBins, 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double l = luminances[size_t(y) * size_t(width) + size_t(x)];
            if (!(l >= std::exp2(kMinLog2))) continue;
            const double dx = (x + 0.5) / width * 2.0 - 1.0, dy = (y + 0.5) / height * 2.0 - 1.0;
            const double w = std::floor(
                std::exp(-(dx * dx + dy * dy) / (2.0 * kCentreSigma * kCentreSigma)) * kWeightScale + 0.5);
            if (w <= 0.0) continue;
            const double t = (std::min(std::log2(l), kMaxLog2) - kMinLog2) / (kMaxLog2 - kMinLog2);
            const double position = std::min(t * kBins, kBins - 1e-3);
            const int bin = int(position);
            count[size_t(bin)] += w;
            place[size_t(bin)] += std::floor((position - bin) * w + 0.5);  // the shader's fixed point
        }
    double total = 0.0;
    for (double c : count) total += c;
    const double low = kLow * total, high = kHigh * total;
    double below = 0.0, weight = 0.0, sumLog2 = 0.0;
    for (int b = 0; b < kBins; ++b) {
        const double c = count[size_t(b)];
        if (c == 0.0) continue;
        const double take = std::clamp(std::min(below + c, high) - std::max(below, low), 0.0, c);
        below += c;
        if (take <= 0.0) continue;
        const double meanPlace = place[size_t(b)] / c;
        sumLog2 += take * (kMinLog2 + (b + meanPlace) / kBins * (kMaxLog2 - kMinLog2));
        weight += take;
    }
    return weight > 0.0 ? std::clamp(std::log2(kKey) - sumLog2 / weight, -16.0, 16.0) : 0.0;
}

}  // namespace lp
