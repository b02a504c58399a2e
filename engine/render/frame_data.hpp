#pragma once
// Per-frame inputs every pass sees. `gpu` and `shaders` are null when the graph is only built to be
// described (lightpass graph, unit tests): setup code must not touch them, execute code may.
#include <glm/glm.hpp>

#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp {
namespace gl {
class ShaderLibrary;
}
class SceneGpu;
class EnvironmentCache;

struct FrameData {
    int width = 0;          // the size the G-buffer, lighting and post effects run at:
    int height = 0;         // the output size x RenderSettings::renderScale
    int outputWidth = 0;    // the size of the displayed / saved image (the tone map's target)
    int outputHeight = 0;
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    float nearPlane = 0.1f;
    float farPlane = 100.0f;
    float time = 0.0f;
    float sceneExtent = 1.0f;  // distance that maps eye-space positions into the debug view's range
    const Scene* scene = nullptr;
    const RenderSettings* settings = nullptr;
    const SceneGpu* gpu = nullptr;
    const gl::ShaderLibrary* shaders = nullptr;
    // Environment cubes and IBL bakes, kept across frames (imported into each frame's graph).
    EnvironmentCache* environments = nullptr;
};

}  // namespace lp
