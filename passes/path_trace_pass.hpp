#pragma once
// The reference path tracer (docs/path-tracer.md): --render-path pathtraced and `lightpass reference`.
// One compute pass, `path_trace`, makes the frame's HDR buffer from the scene's triangles (a BVH built
// when the scene is first traced), its materials without textures, its suns, local lights and
// environment; progressive: it accumulates RenderSettings::pathTrace.samples samples a pixel and keeps
// them while the frame's inputs stay the same, so later frames of an unchanged view trace nothing.
#include <cstddef>
#include <string>

#include "engine/gl/handles.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"

namespace lp {

// Storage-block bindings of shaders/common/path_trace.glsl (LP_PT_BIND_*).
enum PathTraceBinding : GLuint {
    kPtBindNodes = 0,
    kPtBindTriangles = 1,
    kPtBindMaterials = 2,
    kPtBindLights = 3,
    kPtBindEnvironment = 4,  // the environment map's sampling tables (passes/path_trace_environment.hpp)
};

// The noise of an accumulated image: per pixel the variance of the mean of its samples' luminance,
// s^2 / N with s^2 the samples' unbiased variance; its square root over the mean luminance is the
// pixel's relative standard error, averaged over the pixels whose mean is above zero.
struct PathTraceNoise {
    int samples = 0;
    size_t pixels = 0;                      // pixels with a mean above zero
    double meanRelativeStandardError = 0.0;  // average of sqrt(var(mean)) / mean over those pixels
    double meanLuminance = 0.0;             // over every pixel
    // sqrt of the mean over every pixel of var(mean luminance): the RMSE the reference's own noise
    // puts into an error measured against it (the floor of `sweep --reference pathtraced`).
    double rmsStandardError = 0.0;
};
// `sums`: RGBA per pixel, rgb the sum of the samples' radiance, a the sum of their squared luminance
// (the accumulation image), after `samples` samples (at least 2 for a variance).
PathTraceNoise pathTraceNoise(const std::vector<float>& sums, int samples);
// One line for a user: size, samples, bounces and the noise (render --render-path pathtraced,
// reference, sweep --reference pathtraced).
std::string describePathTraceNoise(const RenderSettings& settings, const PathTraceNoise& noise);

struct PathTracePass {
    gl::Program program;
    gl::Buffer nodes, triangles, materials, lights;
    gl::Texture environment;   // the equirectangular map, when the scene has one
    gl::Buffer environmentTables;  // its sampling tables (passes/path_trace_environment.hpp), when it has light
    glm::ivec2 environmentCells{0};  // their width and height; 0: none
    gl::Texture accumulation;  // RGBA32F sums (rgb radiance, a squared luminance)
    gl::Texture srgbMaps, linearMaps;  // the materials' maps as array textures (one layer each), or 1x1
    bool hasMaskedMaterials = false;   // rays test MASK / BLEND alpha at their hits
    const Scene* scene = nullptr;  // what the buffers hold
    bool animated = false;         // the scene has a model whose clips play: its pose follows the clock
    double poseTime = 0.0;         // the time the buffers' animated models are posed at
    int nodeCount = 0;
    int localLightCount = 0;
    float rayEpsilon = 1e-4f;
    std::string accumulatedFor;  // the inputs of the samples in `accumulation`
    int accumulated = 0;
    PathTraceNoise noise;        // of the last finished accumulation (read back once when it finished)
};

fg::ResourceId addPathTracePass(fg::FrameGraph& graph, PathTracePass& state, const FrameData& frame);

}  // namespace lp
