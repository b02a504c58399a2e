#pragma once
// Owns everything a scene needs on the GPU (meshes, textures, pass programs, the transient texture
// pool, the timers) and renders frames through a freshly built frame graph.
#include <memory>
#include <vector>

#include "engine/gl/gpu_timer.hpp"
#include "engine/gl/shader.hpp"
#include "engine/graph/texture_pool.hpp"
#include "engine/io/image_io.hpp"
#include "frame/frame_builder.hpp"
#include "engine/render/motion.hpp"
#include "engine/render/scene_gpu.hpp"

namespace lp {

class Renderer {
public:
    // `scene` must outlive the renderer. Needs a current GL 4.5 context.
    Renderer(const Scene& scene, gl::ShaderLibrary shaders = gl::ShaderLibrary());

    // Builds, compiles and executes one frame; timings go to timers() when `timed`. The frame's
    // motion is measured against the previous frame this renderer rendered (engine/render/motion.hpp).
    void render(const RenderSettings& settings, float time = 0.0f, bool timed = true);

    // Sub-pixel jitter (output pixels, +x right, +y up) of the frames rendered from now on; 0 by default.
    // With --aa taa the frames take TAA's Halton jitter instead (taaJitterPixels).
    void setJitterPixels(glm::vec2 jitterPixels) { jitterPixels_ = jitterPixels; }
    glm::vec2 jitterPixels() const { return jitterPixels_; }
    // A camera cut: the next frame has no previous frame (its velocity is 0 everywhere).
    void cutMotion() { history_ = MotionHistory{}; }
    // What the last rendered frame left for the next (its unjittered view-projection, time, size).
    const MotionHistory& motionHistory() const { return history_; }

    const fg::FrameGraph& graph() const { return graph_; }
    gl::GpuTimerRing& timers() { return timers_; }
    // CPU ms of each timed frame since the last clearCpuTimes(): building, compiling and submitting
    // the graph (`submitMs`), without the time render() waited for older GPU results (`waitMs`).
    struct CpuTimes {
        std::vector<double> submitMs, waitMs;
    };
    const CpuTimes& cpuTimes() const { return cpuTimes_; }
    void clearCpuTimes() { cpuTimes_ = {}; }
    const fg::TexturePool& pool() const { return pool_; }
    // GPU bytes of the textures that outlive a frame outside the pool: environment cubes, IBL bakes,
    // DFG LUT, and the suns' and point lights' kept shadow atlases (--shadow-cache).
    size_t persistentTextureBytes() const {
        return passes_.environments.gpuBytes() + passes_.shadowMaps.cacheBytes() + passes_.pointShadows.cacheBytes();
    }
    // Sun cascade tiles drawn and kept (--shadow-cache) since the last resetShadowCacheStats().
    const ShadowCacheStats& shadowCacheStats() const { return passes_.shadowMaps.cacheStats; }
    // --render-path pathtraced: the noise of the last finished accumulation.
    const PathTraceNoise& pathTraceNoise() const { return passes_.pathTrace.noise; }
    // Point-light cubes drawn and kept (--shadow-cache) since the last resetShadowCacheStats().
    const PointShadowStats& pointShadowStats() const { return passes_.pointShadows.stats; }
    void resetShadowCacheStats() {
        passes_.shadowMaps.cacheStats = {};
        passes_.pointShadows.stats = {};
    }
    // What the last frame's local-light pass did (the clustered method: which kernel shaded, the race's times).
    const LocalLightStats& localLightStats() const { return passes_.localLights.stats; }
    // The environment cubes and IBL bakes (imported into each frame's graph), e.g. to time a fresh bake.
    EnvironmentCache& environments() { return passes_.environments; }
    const SceneGpu& sceneGpu() const { return *gpu_; }
    // CPU milliseconds each timed frame spent posing its animated models (SceneGpu::pose: evaluating
    // the clips, posing the vertices, handing the uploads to the driver); empty without animation.
    const std::vector<double>& poseMilliseconds() const { return poseMs_; }
    // Switches a material (index into sceneGpu().materials) flat-lit or lit from the next frame.
    void setMaterialFlat(size_t material, bool flat) { gpu_->materials.at(material).flat = flat; }
    const gl::ShaderLibrary& shaders() const { return shaders_; }
    // Drops every pass's programs and GPU state so the next frame rebuilds them from the current
    // shader files (hot reload; environments are baked again).
    void resetPasses();
    GLuint displayTexture() const;
    GLuint hdrTexture() const;

    // Read back the last frame (rows top first). readHdr needs settings.keepHdr and a lit view.
    Image8 readDisplay() const;
    ImageF readHdr() const;

private:
    const Scene* scene_;
    gl::ShaderLibrary shaders_;
    std::unique_ptr<SceneGpu> gpu_;
    PassStates passes_;
    fg::TexturePool pool_;
    gl::GpuTimerRing timers_;
    CpuTimes cpuTimes_;
    fg::FrameGraph graph_;
    FrameOutputs outputs_;
    int width_ = 0, height_ = 0;
    glm::vec2 jitterPixels_{0.0f};
    uint64_t taaFrames_ = 0;  // TAA frames rendered: the next one's jitter phase
    MotionHistory history_;
    std::vector<double> poseMs_;
    bool softwareRaster_ = true;        // the current context's rasteriser (--gbuffer-mode auto)
    uint64_t maxStorageBlockBytes_ = 0;  // its GL_MAX_SHADER_STORAGE_BLOCK_SIZE (the same)
};

}  // namespace lp
