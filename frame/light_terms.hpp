#pragma once
// The light a sweep knob's error lives in. A knob of the shadow maps changes only what the suns
// light, an IBL or AO knob only the environment's (ambient) light, a local-light knob only the point
// lights and spots': measured on the whole frame, its error drowns in terms it does not touch (the
// constant ambient a direct-light reference lacks, a sun in view). `sweep` renders every value a
// second time in a copy of the scene lit by the knob's term alone (sceneLitBy) and measures it there,
// over the pixels that see a surface.
#include "engine/core/enum_table.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

enum class LightTerm {
    Frame,        // everything: the knob touches every light (G-buffer formats, anti-aliasing, ...)
    Suns,         // directional lights, with their shadows
    Environment,  // the environment's light: IBL, or the constant ambient standing in for it; AO
    LocalLights,  // point lights and spots
};
inline constexpr EnumName<LightTerm> kLightTermNames[] = {{LightTerm::Frame, "frame"},
                                                          {LightTerm::Suns, "suns"},
                                                          {LightTerm::Environment, "environment"},
                                                          {LightTerm::LocalLights, "local-lights"}};

// A copy of `scene` lit by `term` alone, for frames rendered with `settings` (which suns a frame
// uses depends on whether IBL lights it: frameDirectionalLights). Emission is taken out of every
// term but Frame (an emitter is its own light); flat-lit materials stay (no light reaches them).
// Frame: the scene as it is.
Scene sceneLitBy(const Scene& scene, const RenderSettings& settings, LightTerm term);

}  // namespace lp
