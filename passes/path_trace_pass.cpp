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
#include "engine/gl/state.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/local_lights.hpp"
#include "engine/render/path_trace_scene.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/path_trace_environment.hpp"

namespace lp {

namespace {
constexpr int kMaxSuns = 16;        // MAX_SUNS in path_trace.comp
constexpr int kTraversalStack = 64; // LP_PT_STACK in common/path_trace.glsl
constexpr int kRouletteFrom = 3;    // interactions traced before Russian roulette may end a path
constexpr int kSamplesPerWait = 32; // samples queued before the tracer waits for the GPU (below)
constexpr GLuint kEnvironmentUnit = 0;

struct Data {
    fg::ResourceId hdr;
};

GLint loc(GLuint prog, const char* name) { return glGetUniformLocation(prog, name); }

template <typename T>
gl::Buffer storage(const std::vector<T>& records, const std::string& name) {
    // An empty block still needs a buffer to bind: one zeroed record.
    const std::vector<T> one(1);
    const std::vector<T>& data = records.empty() ? one : records;
    return gl::makeBuffer(GLsizeiptr(data.size() * sizeof(T)), data.data(), 0, name);
}

// The scene's triangles, materials and BVH, and its environment map, uploaded once per scene.
void uploadScene(PathTracePass& state, const Scene& scene) {
    const PathTraceScene traced = buildPathTraceScene(scene);
    if (traced.bvh.depth + 1 > kTraversalStack)
        throw Error("path tracer: the scene's BVH is " + std::to_string(traced.bvh.depth) + " levels deep, above the " +
                    std::to_string(kTraversalStack - 1) + " its traversal stack holds");
    if (traced.texturedMaterials > 0)
        logWarn("path tracer: " + std::to_string(traced.texturedMaterials) +
                " textured materials are traced with their factors alone (no texture, normal or bump map)");
    if (traced.blendedMaterials > 0)
        logWarn("path tracer: " + std::to_string(traced.blendedMaterials) + " alpha-blended materials are traced as opaque");
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
}

// Everything the traced image depends on besides the scene's geometry: a change starts the
// accumulation again. The frame's time only through what moves with it (the camera, orbiting lights),
// so an unchanged view keeps its samples while the clock runs (the viewer).
std::string accumulationKey(const FrameData& frame, const std::vector<GpuLocalLight>& lights) {
    const RenderSettings& s = *frame.settings;
    std::ostringstream key;
    key.precision(9);
    key << frame.scene << ' ' << frame.width << 'x' << frame.height << ' ' << s.pathTrace.samples << ' '
        << s.pathTrace.interactions() << ' ' << s.pathTrace.pixelCentre << ' ' << int(s.brdf) << ' '
        << int(s.specularMasking) << ' ' << s.localLights.specular << s.localLights.specularOutsideRange << ' '
        << s.localLights.enabled << ' ' << s.localLights.rangeScale << ' ' << s.pathTrace.environmentSampling;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) key << ' ' << frame.view[i][j] << ' ' << frame.projection[i][j];
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
    glProgramUniformMatrix4fv(prog, loc(prog, "uClipToWorld"), 1, GL_FALSE, glm::value_ptr(clipToWorld));
    glProgramUniform3fv(prog, loc(prog, "uCameraPosition"), 1, glm::value_ptr(camera));
    glProgramUniform1i(prog, loc(prog, "uPixelCentre"), s.pathTrace.pixelCentre);
    glProgramUniform1i(prog, loc(prog, "uBounces"), s.pathTrace.interactions());
    glProgramUniform1i(prog, loc(prog, "uRouletteFrom"), kRouletteFrom);
    glProgramUniform1i(prog, loc(prog, "uPtNodeCount"), state.nodeCount);
    glProgramUniform1f(prog, loc(prog, "uRayEpsilon"), state.rayEpsilon);
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
    glProgramUniform1i(prog, loc(prog, "uSunCount"), sunCount);
    if (sunCount > 0) {
        glProgramUniform3fv(prog, loc(prog, "uSunToLight"), sunCount, glm::value_ptr(toLight[0]));
        glProgramUniform3fv(prog, loc(prog, "uSunIrradiance"), sunCount, glm::value_ptr(irradiance[0]));
    }
    glProgramUniform1i(prog, loc(prog, "uLocalLightCount"), state.localLightCount);
    glProgramUniform1i(prog, loc(prog, "uSpecularMode"),
                       !s.localLights.specular ? 0 : (s.localLights.specularOutsideRange ? 2 : 1));
    const Environment& e = scene.environment;
    glProgramUniform1i(prog, loc(prog, "uHasEnvironmentMap"), bool(state.environment));
    const glm::ivec2 cells = s.pathTrace.environmentSampling ? state.environmentCells : glm::ivec2(0);
    glProgramUniform2i(prog, loc(prog, "uEnvironmentCells"), cells.x, cells.y);
    const glm::vec3 color = e.color * e.intensity;
    glProgramUniform3fv(prog, loc(prog, "uEnvironmentColor"), 1, glm::value_ptr(color));
    glProgramUniform1f(prog, loc(prog, "uEnvironmentIntensity"), e.intensity);
    glProgramUniform1f(prog, loc(prog, "uEnvironmentRotation"), float(glm::radians(double(e.rotationDegrees))));
    setBrdfUniforms(prog, s);
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
            if (state.scene != frame.scene) {
                uploadScene(state, *frame.scene);
                state.accumulatedFor.clear();
            }
            const int samples = std::max(frame.settings->pathTrace.samples, 1);
            std::vector<GpuLocalLight> records;  // world space
            if (frame.settings->localLights.enabled)
                for (const PointLight& l : *frameLocalLights(frame)) records.push_back(gpuLocalLight(l, glm::mat4(1.0f), -1));
            const std::string key = accumulationKey(frame, records);
            if (key != state.accumulatedFor) {
                state.accumulatedFor = key;
                state.accumulated = 0;
                if (!state.accumulation || state.accumulation.width != frame.width || state.accumulation.height != frame.height)
                    state.accumulation = gl::makeTexture2D(GL_RGBA32F, frame.width, frame.height, 1, "path_trace.accumulation");
                state.lights = storage(records, "path_trace.lights");
                state.localLightCount = int(records.size());
            }
            const GLuint prog = state.program.id();
            setUniforms(prog, state, frame);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindNodes, state.nodes.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindTriangles, state.triangles.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindMaterials, state.materials.id());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindLights, state.lights.id());
            // An unread block still needs a buffer bound: the lights' when the map has no tables.
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPtBindEnvironment,
                             state.environmentTables ? state.environmentTables.id() : state.lights.id());
            if (state.environment) glBindTextureUnit(kEnvironmentUnit, state.environment.id());
            glBindImageTexture(0, state.accumulation.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            glBindImageTexture(1, res.texture(data.hdr), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            glUseProgram(prog);
            // The samples still missing, the last dispatch writing the mean into the HDR target; with
            // none missing (an unchanged view) one dispatch only divides the sums again (the target is
            // a new transient each frame).
            const bool tracing = state.accumulated < samples;  // samples missing: trace them now
            if (tracing) {
                glProgramUniform1i(prog, loc(prog, "uTrace"), 1);
                for (int i = state.accumulated; i < samples; ++i) {
                    glProgramUniform1i(prog, loc(prog, "uSample"), i);
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
                glProgramUniform1i(prog, loc(prog, "uTrace"), 0);
                glProgramUniform1i(prog, loc(prog, "uSample"), samples - 1);
                gl::dispatch2D(frame.width, frame.height);
            }
            glUseProgram(0);
            state.accumulated = samples;
            glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
            glBindImageTexture(1, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            if (state.environment) glBindTextureUnit(kEnvironmentUnit, 0);
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
