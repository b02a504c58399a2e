#pragma once
// Checks a command makes before its first GPU allocation, so that a size the GPU cannot hold is one
// line naming the size and the limit.
#include "engine/gl/context.hpp"
#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp::app {

// Sizes the frame graph's render targets for `settings` (no GPU work) and compares them, and the
// output size, with what the current context's GPU can hold.
void requireFrameFitsGpu(const gl::GpuContext& context, const Scene& scene, const RenderSettings& settings);

}  // namespace lp::app
