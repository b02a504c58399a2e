#pragma once
// Per-frame inputs every pass sees. `gpu` and `shaders` are null when the graph is only built to be
// described (lightpass graph, unit tests): setup code must not touch them, execute code may.
#include <cstdint>
#include <memory>
#include <vector>

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
    // The projection everything is rasterised and reconstructed with: unjitteredProjection shifted by
    // jitterPixels (engine/render/motion.hpp; equal to it when the jitter is 0).
    glm::mat4 projection{1.0f};
    glm::mat4 unjitteredProjection{1.0f};  // the camera's own; velocity is computed from it
    glm::vec2 jitterPixels{0.0f};          // sub-pixel offset in output pixels, +x right, +y up
    // The previous frame (Renderer keeps it): its unjittered projection x view and its scene time
    // (orbits at previousTime give the lights' previous positions). Without one (first frame, camera
    // cut, resize) hasPrevious is false, previousViewProjection = unjitteredProjection x view and
    // previousTime = time, so every velocity is 0. Models are static: their previous model matrix is
    // their current one.
    glm::mat4 previousViewProjection{1.0f};
    float previousTime = 0.0f;
    bool hasPrevious = false;
    uint64_t frameIndex = 0;  // frames this renderer rendered before this one since its last cut
    float nearPlane = 0.1f;
    float farPlane = 100.0f;
    float time = 0.0f;
    float sceneExtent = 1.0f;  // distance that maps eye-space positions into the debug view's range
    const Scene* scene = nullptr;
    const RenderSettings* settings = nullptr;
    // The local lights this frame draws at `time` (localLightsForFrame), made once with the frame
    // (makeFrameData), before any pass is recorded: every pass reads the same list, and a pass's GPU
    // timing window never holds the CPU work of making it (at 16384 lights about 1-2 ms, which the
    // GPU spent idle inside the pass that made them). Null in frames made by hand: frameLocalLights
    // then makes them.
    std::shared_ptr<const std::vector<PointLight>> localLights;
    // The rasteriser is a software one (llvmpipe) or unknown (a graph described without a GPU):
    // --gbuffer-mode auto makes the classic G-buffer there, the visibility buffer on a GPU.
    bool softwareRaster = true;
    // GL_MAX_SHADER_STORAGE_BLOCK_SIZE of the GPU (0: unknown): whether the visibility buffer's resolve
    // can read the scene's geometry (--gbuffer-mode auto falls back to classic where it cannot).
    uint64_t maxStorageBlockBytes = 0;
    const SceneGpu* gpu = nullptr;
    const gl::ShaderLibrary* shaders = nullptr;
    // The frame's graph has the skinning pass (passes/skinning_pass.hpp): the passes that draw the
    // meshes read its posed vertices, so they run after it.
    bool posedVerticesOnGpu = false;
    // Environment cubes and IBL bakes, kept across frames (imported into each frame's graph).
    EnvironmentCache* environments = nullptr;
};

// Whether IBL lights a frame: a map to light with, and --ibl / --brdf-only or else the scene's
// environment.ibl.
bool iblLightsFrame(const Scene& scene, const RenderSettings& settings);
// The directional lights and the constant ambient a frame shades with: the scene's own, or its
// lightsWithoutIbl on a frame that IBL does not light (a frame without settings: the scene's own).
// A frame that IBL lights has no constant ambient: the environment replaces it. Each sun's direction is
// the one at the frame's time (a turning sun: DirectionalLight::directionAt).
std::vector<DirectionalLight> frameDirectionalLights(const FrameData& frame);
glm::vec3 frameAmbient(const FrameData& frame);

}  // namespace lp
