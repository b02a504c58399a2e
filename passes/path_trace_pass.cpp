#include "passes/path_trace_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/limits.hpp"
#include "engine/gl/shader.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/gl/state.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/path_trace_scene.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/path_trace_environment.hpp"

namespace lp {

namespace {
constexpr int kMaxSuns = 16;        // MAX_SUNS in path_trace.comp
constexpr int kTraversalStack = 64; // LP_PT_STACK in common/path_trace.glsl
constexpr int kRouletteFrom = 3;    // interactions traced before Russian roulette may end a path
constexpr int kSamplesPerWait = 32; // samples queued before the tracer waits for the GPU (below)
constexpr GLuint kEnvironmentUnit = 0;
constexpr GLuint kSrgbMapsUnit = 1;    // uPtSrgbMaps in path_trace.comp
constexpr GLuint kLinearMapsUnit = 2;  // uPtLinearMaps
// The maps' layers: every image resampled to the largest one's size, at most this (a reference
// samples level 0 with every pixel's jittered rays, so no mips), and the array at most this many bytes.
constexpr int kMaxMapSize = 2048;
constexpr uint64_t kMaxMapBytes = uint64_t(1) << 30;

struct Data {
    fg::ResourceId hdr;
};

template <typename T>
gl::Buffer storage(const std::vector<T>& records, const std::string& name) {
    // An empty block still needs a buffer to bind: one zeroed record.
    const std::vector<T> one(1);
    const std::vector<T>& data = records.empty() ? one : records;
    return gl::makeBuffer(GLsizeiptr(data.size() * sizeof(T)), data.data(), 0, name);
}

// `img` bilinearly resampled to size x size (texel centres onto texel centres).
Image8 resampleSquare(const Image8& img, int size) {
    if (img.width == size && img.height == size) return img;
    Image8 out;
    out.width = out.height = size;
    out.rgba.resize(size_t(size) * size_t(size) * 4);
    for (int y = 0; y < size; ++y) {
        const float fy = std::clamp((float(y) + 0.5f) * float(img.height) / float(size) - 0.5f, 0.0f, float(img.height - 1));
        const int y0 = int(fy), y1 = std::min(y0 + 1, img.height - 1);
        const float ty = fy - float(y0);
        for (int x = 0; x < size; ++x) {
            const float fx = std::clamp((float(x) + 0.5f) * float(img.width) / float(size) - 0.5f, 0.0f, float(img.width - 1));
            const int x0 = int(fx), x1 = std::min(x0 + 1, img.width - 1);
            const float tx = fx - float(x0);
            for (int c = 0; c < 4; ++c) {
                auto at = [&](int xx, int yy) { return float(img.rgba[(size_t(yy) * size_t(img.width) + size_t(xx)) * 4 + size_t(c)]); };
                const float v = (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x1, y0)) + ty * ((1 - tx) * at(x0, y1) + tx * at(x1, y1));
                out.rgba[(size_t(y) * size_t(size) + size_t(x)) * 4 + size_t(c)] = uint8_t(std::clamp(v + 0.5f, 0.0f, 255.0f));
            }
        }
    }
    return out;
}

// The maps as one array texture, one layer per image (rows bottom first, as the raster uploads
// them: v = 0 at the bottom); a 1x1 white layer when there are none (the sampler needs a texture).
gl::Texture uploadMapArray(const std::vector<TextureRef>& refs, bool srgb, const char* label) {
    std::vector<Image8> images;
    int size = 1;
    for (const TextureRef& ref : refs) {
        Image8 img = decodeTextureRef(ref);  // the raster frame warned about an unusable one already
        size = std::max({size, img.width, img.height});
        images.push_back(std::move(img));
    }
    GLint maxSize = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (int(images.size()) > maxLayers)
        throw Error("path tracer: the scene has " + std::to_string(images.size()) + " " + label + " maps, above the " +
                    std::to_string(maxLayers) + " layers of an array texture on this GPU");
    size = std::min({size, kMaxMapSize, int(maxSize)});
    while (size > 64 && uint64_t(size) * uint64_t(size) * 4 * images.size() > kMaxMapBytes) size /= 2;
    const int layers = std::max<int>(1, int(images.size()));
    if (images.empty()) size = 1;
    gl::Texture t = gl::makeTexture2DArray(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, size, size, layers,
                                           std::string("path_trace.") + label + "_maps");
    if (images.empty()) {
        const uint8_t white[4] = {255, 255, 255, 255};
        glTextureSubImage3D(t.id(), 0, 0, 0, 0, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white);
    }
    for (size_t i = 0; i < images.size(); ++i) {
        Image8 img = resampleSquare(images[i], size);
        std::vector<uint8_t> flipped(img.rgba.size());
        const size_t row = size_t(size) * 4;
        for (int y = 0; y < size; ++y) std::copy_n(&img.rgba[size_t(size - 1 - y) * row], row, &flipped[size_t(y) * row]);
        glTextureSubImage3D(t.id(), 0, 0, 0, GLint(i), size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    }
    // Wrapping is the shader's (each map's own sampler wraps); the array clamps at the edges.
    return t;
}

// The scene's triangles, materials and BVH, and its environment map, uploaded once per scene.
void uploadScene(PathTracePass& state, const Scene& scene, double time) {
    const PathTraceScene traced = buildPathTraceScene(scene, time);
    if (traced.bvh.depth + 1 > kTraversalStack)
        throw Error("path tracer: the scene's BVH is " + std::to_string(traced.bvh.depth) + " levels deep, above the " +
                    std::to_string(kTraversalStack - 1) + " its traversal stack holds");
    if (traced.unsampledMapMaterials > 0)
        logWarn("path tracer: " + std::to_string(traced.unsampledMapMaterials) +
                 " materials have a height (bump) map or KHR_materials_specular, _clearcoat, _transmission or _volume maps, which "
                "the tracer does not sample (their factors are used)");
    state.srgbMaps = uploadMapArray(traced.srgbMaps, true, "srgb");
    state.linearMaps = uploadMapArray(traced.linearMaps, false, "linear");
    state.hasMaskedMaterials = traced.hasMaskedMaterials;
    std::vector<BvhNode> nodes = traced.bvh.nodes;
    // Leaves index the triangle buffer, which is already in leaf order: first is a position there.
    state.nodes = storage(nodes, "path_trace.bvh_nodes");
    state.triangles = storage(traced.triangles, "path_trace.triangles");
    state.materials = storage(traced.materials, "path_trace.materials");
    state.nodeCount = int(nodes.size());
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    // Secondary rays start this far (relative to the coordinates' size) off the surface: above float's
    // rounding of a hit point, far below any scene feature.
    state.rayEpsilon = 2e-5f;
    state.environment = {};
    state.environmentTables = {};
    state.environmentCells = glm::ivec2(0);
    if (!scene.environment.map.empty()) {
        ImageF map = loadHdrImage(scene.environment.map);
        if (const gl::TextureFit fit = gl::fitTexture(GL_RGBA32F, map.width, map.height); fit.halvings > 0) {
            const int w = map.width, h = map.height;
            map = downscaleToFit(map, std::max(w, h) >> fit.halvings);
            logWarn(scene.environment.map.string() + ": " + std::to_string(w) + "x" + std::to_string(h) + " is " +
                    fit.reason + "; downscaled to " + std::to_string(map.width) + "x" + std::to_string(map.height));
        }
        state.environment = gl::makeTexture2D(GL_RGBA32F, map.width, map.height, 1, "path_trace.environment");
        glTextureSubImage2D(state.environment.id(), 0, 0, 0, map.width, map.height, GL_RGBA, GL_FLOAT, map.rgba.data());
        glTextureParameteri(state.environment.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(state.environment.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(state.environment.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(state.environment.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        const EnvironmentDistribution cells = buildEnvironmentDistribution(map);
        if (!cells.empty()) {
            std::vector<float> tables = cells.marginal;  // the order common/path_trace_environment.glsl reads
            tables.insert(tables.end(), cells.conditional.begin(), cells.conditional.end());
            tables.insert(tables.end(), cells.cellPdf.begin(), cells.cellPdf.end());
            state.environmentTables = storage(tables, "path_trace.environment_tables");
            state.environmentCells = glm::ivec2(cells.width, cells.height);
        }
    }
    state.scene = &scene;
    state.poseTime = time;
    state.animated = std::any_of(scene.models.begin(), scene.models.end(),
                                 [](const ModelInstance& m) { return m.animation && !m.playingClips.empty(); });
}

// Whether the uploaded triangles are no longer where the frame at `time` has them: a scene whose
// animated models moved since their upload is posed and uploaded again (the BVH rebuilt on the CPU).
bool poseChanged(const PathTracePass& state, const Scene& scene, double time) {
    if (!state.animated || time == state.poseTime) return false;
    return std::any_of(scene.models.begin(), scene.models.end(),
                       [&](const ModelInstance& m) { return m.movesBetween(state.poseTime, time); });
}

// Everything the traced image depends on besides the scene's geometry: a change starts the
// accumulation again. The frame's time only through what moves with it (the camera, orbiting lights),
// so an unchanged view keeps its samples while the clock runs (the viewer).
std::string accumulationKey(const PathTracePass& state, const FrameData& frame, const std::vector<GpuLocalLight>& lights) {
    const RenderSettings& s = *frame.settings;
    std::ostringstream key;
    key.precision(9);
    key << frame.scene << ' ' << frame.width << 'x' << frame.height << ' ' << s.pathTrace.samples << ' '
        << s.pathTrace.interactions() << ' ' << s.pathTrace.pixelCentre << ' ' << int(s.brdf) << ' '
        << int(s.specularMasking) << ' ' << s.localLights.specular << s.localLights.specularOutsideRange << ' '
        << s.localLights.enabled << ' ' << s.localLights.rangeScale << ' ' << s.pathTrace.environmentSampling;
    key << " pose " << state.poseTime;  // where the animated models were posed (a still scene: never changes)
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) key << ' ' << frame.view[i][j] << ' ' << frame.projection[i][j];
    for (const DirectionalLight& sun : frameDirectionalLights(frame))  // a turning sun moves with the clock
        key << ' ' << sun.direction.x << ' ' << sun.direction.y << ' ' << sun.direction.z;
    for (const GpuLocalLight& l : lights)
        key << ' ' << l.positionRange.x << ' ' << l.positionRange.y << ' ' << l.positionRange.z << ' ' << l.directionCos.x
            << ' ' << l.directionCos.y << ' ' << l.directionCos.z;
    return key.str();
}

void setUniforms(GLuint prog, const PathTracePass& state, const FrameData& frame) {
    const RenderSettings& s = *frame.settings;
    const Scene& scene = *frame.scene;
    const glm::mat4 clipToWorld = glm::inverse(frame.projection * frame.view);
    const glm::vec3 camera = glm::vec3(glm::inverse(frame.view)[3]);
    const gl::Uniforms u(frame.shaders, prog);
    u.set("uClipToWorld", clipToWorld);
    u.set("uCameraPosition", camera);
    u.set("uPixelCentre", s.pathTrace.pixelCentre);
    u.set("uBounces", s.pathTrace.interactions());
    u.set("uRouletteFrom", kRouletteFrom);
    u.set("uPtNodeCount", state.nodeCount);
    u.set("uRayEpsilon", state.rayEpsilon);
    u.set("uHasMaskedMaterials", state.hasMaskedMaterials);
    const auto& suns = frameDirectionalLights(frame);
    if (int(suns.size()) > kMaxSuns)
        logWarn("path tracer: only the first " + std::to_string(kMaxSuns) + " of " + std::to_string(suns.size()) +
                " directional lights are traced");
    const int sunCount = std::min<int>(int(suns.size()), kMaxSuns);
    std::vector<glm::vec3> toLight, irradiance;
    for (int i = 0; i < sunCount; ++i) {
        toLight.push_back(glm::normalize(-suns[size_t(i)].direction));
        irradiance.push_back(suns[size_t(i)].color * suns[size_t(i)].intensity);
    }
    u.set("uSunCount", sunCount);
    u.setArray("uSunToLight", toLight.data(), sunCount);
    u.setArray("uSunIrradiance", irradiance.data(), sunCount);
    u.set("uLocalLightCount", state.localLightCount);
    u.set("uSpecularMode", !s.localLights.specular ? 0 : (s.localLights.specularOutsideRange ? 2 : 1));
    const Environment& e = scene.environment;
    u.set("uHasEnvironmentMap", bool(state.environment));
    const glm::ivec2 cells = s.pathTrace.environmentSampling ? state.environmentCells : glm::ivec2(0);
    u.set("uEnvironmentCells", cells);
    const glm::vec3 color = e.color * e.intensity;
    u.set("uEnvironmentColor", color);
    u.set("uEnvironmentIntensity", e.intensity);
    u.set("uEnvironmentRotation", float(glm::radians(double(e.rotationDegrees))));
    setBrdfUniforms(prog, frame);
}
}  // namespace

PathTraceNoise pathTraceNoise(const std::vector<float>& sums, int samples) {
    PathTraceNoise noise;
    noise.samples = samples;
    const size_t pixels = sums.size() / 4;
    if (pixels == 0 || samples <= 0) return noise;
    const double n = double(samples);
    double relative = 0.0, luminance = 0.0, variance = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        const double y = (0.2126 * sums[4 * i] + 0.7152 * sums[4 * i + 1] + 0.0722 * sums[4 * i + 2]) / n;
        luminance += y;
        if (!(y > 0.0) || samples < 2) continue;
        const double sampleVariance = std::max(0.0, (double(sums[4 * i + 3]) - n * y * y) / (n - 1.0));
        variance += sampleVariance / n;
        relative += std::sqrt(sampleVariance / n) / y;
        ++noise.pixels;
    }
    noise.meanLuminance = luminance / double(pixels);
    noise.rmsStandardError = std::sqrt(variance / double(pixels));
    noise.meanRelativeStandardError = noise.pixels ? relative / double(noise.pixels) : 0.0;
    return noise;
}

// The path tracer's noise estimate, one line (render --render-path pathtraced, reference).
std::string describePathTraceNoise(const RenderSettings& s, const PathTraceNoise& n) {
    char line[320];
    std::snprintf(line, sizeof line,
                  "path tracer: %dx%d, %d samples a pixel, %s: mean relative standard error %.3f%% over %zu lit pixels "
                  "(mean luminance %.6g)",
                  s.width, s.height, n.samples,
                  s.pathTrace.directOnly ? "direct light only" : ("up to " + std::to_string(s.pathTrace.bounces) + " bounces").c_str(),
                  100.0 * n.meanRelativeStandardError, n.pixels, n.meanLuminance);
    return line;
}

fg::ResourceId addPathTracePass(fg::FrameGraph& graph, PathTracePass& state, const FrameData& frame) {
    const Data& d = graph.addPass<Data>(
        "path_trace", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& data) {
            data.hdr = b.create("hdr", {frame.width, frame.height, GL_RGBA16F}, fg::Usage::ImageStore);
        },
        [&state, frame](const Data& data, const fg::PassResources& res) {
            if (!state.program) state.program = frame.shaders->compute("path_trace.comp");
            if (state.scene != frame.scene || poseChanged(state, *frame.scene, frame.time)) {
                uploadScene(state, *frame.scene, frame.time);
                state.accumulatedFor.clear();
            }
            const int samples = std::max(frame.settings->pathTrace.samples, 1);
            std::vector<GpuLocalLight> records;  // world space
            if (frame.settings->localLights.enabled)
                for (const PointLight& l : *frameLocalLights(frame)) records.push_back(gpuLocalLight(l, glm::mat4(1.0f), -1));
            const std::string key = accumulationKey(state, frame, records);
            if (key != state.accumulatedFor) {
                state.accumulatedFor = key;
                state.accumulated = 0;
                if (!state.accumulation || state.accumulation.width != frame.width || state.accumulation.height != frame.height)
                    state.accumulation = gl::makeTexture2D(GL_RGBA32F, frame.width, frame.height, 1, "path_trace.accumulation");
                state.lights = storage(records, "path_trace.lights");
                state.localLightCount = int(records.size());
            }
            const GLuint prog = state.program.id();
            const gl::Uniforms u(frame.shaders, prog);
            setUniforms(prog, state, frame);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindNodes, state.nodes.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindTriangles, state.triangles.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindMaterials, state.materials.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindLights, state.lights.id());
            // An unread block still needs a buffer bound: the lights' when the map has no tables.
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindEnvironment,
                             state.environmentTables ? state.environmentTables.id() : state.lights.id());
            if (state.environment) glBindTextureUnit(kEnvironmentUnit, state.environment.id());
            glBindTextureUnit(kSrgbMapsUnit, state.srgbMaps.id());
            glBindTextureUnit(kLinearMapsUnit, state.linearMaps.id());
            glBindImageTexture(0, state.accumulation.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            glBindImageTexture(1, res.texture(data.hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUseProgram(prog);
            // The samples still missing, the last dispatch writing the mean into the HDR target; with
            // none missing (an unchanged view) one dispatch only divides the sums again (the target is
            // a new transient each frame).
            const bool tracing = state.accumulated < samples;  // samples missing: trace them now
            if (tracing) {
                u.set("uTrace", 1);
                for (int i = state.accumulated; i < samples; ++i) {
                    u.set("uSample", i);
                    gl::dispatch2D(frame.width, frame.height);
                    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
                    // Seconds of samples queued at once lost the context on an H100 (1024 samples of
                    // the Cornell box at 1080p, 16 s, came back black): waited on in batches instead.
                    if ((i + 1) % kSamplesPerWait == 0) glFinish();
                }
                if (glGetGraphicsResetStatus() != GL_NO_ERROR)
                    throw Error("path tracer: the GPU reset the GL context while tracing " + std::to_string(samples) +
                                " samples a pixel at " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                                " (fewer --spp or a smaller --size)");
            } else {
                u.set("uTrace", 0);
                u.set("uSample", samples - 1);
                gl::dispatch2D(frame.width, frame.height);
            }
            glUseProgram(0);
            state.accumulated = samples;
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            if (state.environment) glBindTextureUnit(kEnvironmentUnit, 0);
            glBindTextureUnit(kSrgbMapsUnit, 0);
            glBindTextureUnit(kLinearMapsUnit, 0);
            for (GLuint b : {kPtBindNodes, kPtBindTriangles, kPtBindMaterials, kPtBindLights, kPtBindEnvironment})
                glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
            if (tracing) {  // the accumulation is now complete: its noise
                glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
                std::vector<float> sums(size_t(frame.width) * size_t(frame.height) * 4);
                glGetTextureImage(state.accumulation.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(sums.size() * sizeof(float)),
                                  sums.data());
                state.noise = pathTraceNoise(sums, samples);
            }
        });
    return d.hdr;
}

}  // namespace lp
