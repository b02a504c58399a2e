#include "frame/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "engine/core/error.hpp"
#include "engine/gl/context.hpp"
#include "engine/gl/handles.hpp"
#include "engine/gl/limits.hpp"

namespace lp {

Renderer::Renderer(const Scene& scene, gl::ShaderLibrary shaders)
    : scene_(&scene),
      shaders_(std::move(shaders)),
      gpu_(std::make_unique<SceneGpu>(scene)),
      softwareRaster_(gl::currentContextIsSoftware()),
      maxStorageBlockBytes_(gl::maxShaderStorageBlockBytes()) {}

void Renderer::render(const RenderSettings& settings, float time, bool timed) {
    const auto start = std::chrono::steady_clock::now();
    if (settings.width <= 0 || settings.height <= 0) throw Error("render size must be positive");
    if (!(settings.renderScale >= kMinRenderScale && settings.renderScale <= 1.0f))
        throw Error("render scale " + std::to_string(settings.renderScale) + " is outside [0.25, 1]");
    if (!(settings.aa.ssaaScale >= 2 && settings.aa.ssaaScale <= kMaxSsaaScale))
        throw Error("SSAA scale " + std::to_string(settings.aa.ssaaScale) + " is outside [2, 4]");
    FrameData frame = makeFrameData(*scene_, settings, time);
    // TAA jitters every frame through its Halton phases; otherwise the jitter setJitterPixels chose.
    applyMotion(frame, history_, temporalAntiAliasing(settings) ? taaJitterPixels(taaFrames_++) : jitterPixels_);
    // Animated models posed at the frame's time, and at the previous frame's for their motion vectors.
    const auto poseStart = std::chrono::steady_clock::now();
    gpu_->pose(*scene_, frame.time, frame.previousTime, settings.skinning);
    if (timed && gpu_->animated)
        poseMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - poseStart).count());
    frame.gpu = gpu_.get();
    frame.shaders = &shaders_;
    frame.softwareRaster = softwareRaster_;
    frame.maxStorageBlockBytes = maxStorageBlockBytes_;
    graph_ = fg::FrameGraph();
    outputs_ = buildFrameGraph(graph_, passes_, frame);
    // Textures the CUDA passes touch come from CUDA's shared memory when CUDA runs on shared textures.
    pool_.setExternalSource(passes_.post.backend.externalTextureSource());
    graph_.compile();
    if (timed) timers_.beginFrame();
    graph_.execute(pool_, timed ? &timers_ : nullptr);
    if (timed) timers_.endFrame();
    width_ = settings.width;
    height_ = settings.height;
    history_ = motionHistoryOf(frame);
    if (timed) {
        const double total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        cpuTimes_.waitMs.push_back(timers_.lastWaitMs());
        cpuTimes_.submitMs.push_back(std::max(0.0, total - timers_.lastWaitMs()));
    }
}

void Renderer::resetPasses() {
    graph_ = fg::FrameGraph();  // the old graph's passes point into the old states
    outputs_ = {};
    pool_.setExternalSource(nullptr);  // the post backend that made the shared textures goes too
    passes_ = PassStates{};
}

GLuint Renderer::displayTexture() const { return outputs_.display.valid() ? graph_.outputTexture(outputs_.display) : 0; }
GLuint Renderer::hdrTexture() const { return outputs_.hdr.valid() ? graph_.outputTexture(outputs_.hdr) : 0; }

namespace {
template <typename T>
void flipRows(std::vector<T>& pixels, int width, int height) {
    const size_t row = size_t(width) * 4;
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(pixels.begin() + long(size_t(y) * row), pixels.begin() + long(size_t(y + 1) * row),
                         pixels.begin() + long(size_t(height - 1 - y) * row));
}
}  // namespace

Image8 Renderer::readDisplay() const {
    GLuint tex = displayTexture();
    if (!tex) throw Error("no frame has been rendered");
    Image8 img;
    img.width = width_;
    img.height = height_;
    img.rgba.resize(size_t(width_) * height_ * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(img.rgba.size()), img.rgba.data());
    flipRows(img.rgba, width_, height_);
    return img;
}

ImageF Renderer::readHdr() const {
    GLuint tex = hdrTexture();
    if (!tex) throw Error("this frame kept no HDR buffer (a G-buffer debug view has none)");
    ImageF img;
    img.width = width_;
    img.height = height_;
    img.rgba.resize(size_t(width_) * height_ * 4);
    // Read through a GPU copy: the HDR buffer may be a texture CUDA wrote last on shared memory, and
    // NVIDIA's GL can answer glGetTextureImage from what it kept of an earlier read-back and upload
    // instead of the memory CUDA wrote (tests/cuda/test_post_cuda.cpp, CudaSharedTextures).
    GLint format = 0;
    glGetTextureLevelParameteriv(tex, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    gl::Texture copy = gl::makeTexture2D(GLenum(format), width_, height_, 1, "read_hdr.copy");
    glCopyImageSubData(tex, GL_TEXTURE_2D, 0, 0, 0, 0, copy.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
    glGetTextureImage(copy.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(img.rgba.size() * sizeof(float)), img.rgba.data());
    flipRows(img.rgba, width_, height_);
    return img;
}

}  // namespace lp
