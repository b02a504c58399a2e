#pragma once
// Checks a command makes before its first GPU allocation, so that a size the GPU cannot hold, or a
// pass name that is not in the frame, is one line naming it.
#include <memory>
#include <string>

#include "engine/gl/context.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp::app {

// Sizes the frame graph's render targets for `settings` (no GPU work) and compares them, and the
// output size, with what the current context's GPU can hold. Also checks every --disable-pass name
// against the frame's candidate passes (checkDisabledPasses), before any frame bakes an environment.
void requireFrameFitsGpu(const gl::GpuContext& context, const Scene& scene, const RenderSettings& settings);

// The headless context a one-frame command (render, reference, report) draws with: created, named
// in the log ("<verb> on <GPU> (<platform>)") and the frame checked against it (requireFrameFitsGpu).
std::unique_ptr<gl::GpuContext> openHeadlessFor(const std::string& verb, const Scene& scene, const RenderSettings& settings);

}  // namespace lp::app
