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

const char* bloomMethodName(BloomMethod m) { return m == BloomMethod::MipChain ? "mip-chain" : "separable"; }

std::optional<BloomMethod> parseBloomMethod(const std::string& name) {
    if (name == "separable") return BloomMethod::Separable;
    if (name == "mip-chain") return BloomMethod::MipChain;
    return std::nullopt;
}

const char* cudaInteropName(PostSettings::CudaInterop i) {
    switch (i) {
        case PostSettings::CudaInterop::External: return "external";
        case PostSettings::CudaInterop::Map: return "map";
        case PostSettings::CudaInterop::Auto: break;
    }
    return "auto";
}

const char* backendName(PostSettings::Backend b) {
    switch (b) {
        case PostSettings::Backend::Cuda: return "cuda";
        case PostSettings::Backend::Glsl: return "glsl";
        case PostSettings::Backend::Auto: break;
    }
    return "auto";
}

std::optional<PostSettings::Backend> parseBackend(const std::string& name) {
    if (name == "auto") return PostSettings::Backend::Auto;
    if (name == "cuda") return PostSettings::Backend::Cuda;
    if (name == "glsl") return PostSettings::Backend::Glsl;
    return std::nullopt;
}

}  // namespace lp::post
