#include "engine/post/post_config.hpp"

#include <algorithm>
#include <cmath>

namespace lp::post {

int bloomKernelAtRenderSize(int outputKernel, int renderWidth, int outputWidth) {
    if (renderWidth >= outputWidth || outputWidth <= 0) return outputKernel;
    return std::max(1, int(std::lround(double(outputKernel) * renderWidth / outputWidth)));
}

PostConfig resolvePostConfig(const Effects& fx, const PostSettings& s, float farPlane) {
    PostConfig c;
    c.bloomOnly = s.bloomOnly;
    c.bloom = s.bloom.value_or(fx.bloom.enabled) || s.bloomOnly;  // the bloom view needs the buffer
    c.toon = s.toon.value_or(fx.toon.enabled);
    c.backend = s.backend;
    BloomParams& b = c.bloomParams;
    b.method = s.bloomMethod == PostSettings::BloomMethod::MipChain ? BloomMethod::MipChain : BloomMethod::Separable;
    b.kernel = s.bloomKernel.value_or(fx.bloom.kernelSize);
    b.threshold = s.bloomThreshold.value_or(fx.bloom.threshold);
    b.knee = s.bloomKnee.value_or(fx.bloom.knee);
    b.strength = s.bloomStrength.value_or(fx.bloom.strength);
    b.highlight = s.bloomHighlight;
    b.karis = s.bloomKaris;
    b.fragmentBlur = s.bloomFragmentBlur;
    ToonParams& t = c.toonParams;
    t.levels = s.toonLevels.value_or(fx.toon.levels);
    t.depthEdge = s.toonEdge.value_or(fx.toon.edgeThreshold);
    t.normalEdge = s.toonNormalEdge;
    t.farDepth = farPlane;
    return c;
}

}  // namespace lp::post
