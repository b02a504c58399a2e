#pragma once
// What bloom and toon do this frame: the scene's `effects` overridden by the user's flags.
#include <optional>
#include <string>

#include "engine/post/post_params.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp::post {

struct PostConfig {
    bool bloom = false;
    bool toon = false;
    bool bloomOnly = false;  // display the bloom buffer alone
    BloomParams bloomParams;
    ToonParams toonParams;
    PostSettings::Backend backend = PostSettings::Backend::Auto;
};

// A flag that is set wins; an unset one takes the scene's effects.bloom / effects.toon value.
// The bloom kernel is given in output pixels. At render scale < 1 the blur runs on the smaller image,
// so it spans kernel x renderWidth / outputWidth of its pixels (at least 1): the glow keeps its size
// on screen.
int bloomKernelAtRenderSize(int outputKernel, int renderWidth, int outputWidth);

PostConfig resolvePostConfig(const Effects& sceneEffects, const PostSettings& settings, float farPlane);

inline constexpr EnumName<BloomMethod> kBloomMethodNames[] = {{BloomMethod::Separable, "separable"},
                                                              {BloomMethod::MipChain, "mip-chain"}};
inline const char* bloomMethodName(BloomMethod m) { return enumName(kBloomMethodNames, m); }
inline std::optional<BloomMethod> parseBloomMethod(const std::string& name) { return parseEnum(kBloomMethodNames, name); }
inline std::optional<PostSettings::Backend> parseBackend(const std::string& name) {
    return parseEnum(PostSettings::kBackendNames, name);
}

}  // namespace lp::post
