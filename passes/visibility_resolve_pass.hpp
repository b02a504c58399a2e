#pragma once
// gbuffer_resolve (--gbuffer-mode visibility): the compute half of the visibility-buffer G-buffer.
// Reads gbuffer.visibility (passes/visibility_pass) and writes the same targets, formats and values
// the classic gbuffer pass writes (normal, diffuse, position, specular, texcoord, tangent, velocity:
// whichever some pass reads), by image stores; gbuffer.depth passes through from the raster half.
// The scene's vertex and index buffers are concatenated once into storage buffers, with a draw table
// and, per frame, the meshes' transforms and the materials (shaders/visibility_resolve.comp).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/gl/gradient_probe.hpp"
#include "engine/gl/raster_probe.hpp"
#include "engine/gl/stream_buffer.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/visibility_pass.hpp"

namespace lp {

struct VisibilityResolvePass {
    gl::Program program;
    GBufferProgramKey layout;  // what `program` was compiled for
    // The scene the storage buffers below hold (its address and triangle count: a scene loaded later
    // at the same address is told apart by its size).
    const SceneGpu* geometryOf = nullptr;
    size_t geometryTriangles = 0;
    gl::Buffer vertices, indices, draws;
    // Every vertex's previous-frame position (vec4, w = 1) where its mesh is animated, else 0: the
    // velocity reads it when the scene animates (uAnimated).
    gl::Buffer previousPositions;
    gl::Buffer uv1;  // every mesh's second uv set, a vec2 a vertex (0 where a mesh has none), when the scene samples it
    gl::StreamBuffer meshes{"gbuffer_resolve.meshes"}, materials{"gbuffer_resolve.materials"};  // refilled every frame
    uint32_t drawCount = 0;
    std::vector<int> texturedMaterials;  // one dispatch each, with its maps bound
    std::optional<gl::RasterInterpolation> rasterModel;  // probed on the first resolve
    // Whether textureGrad's gradients reach the driver's anisotropic filter in compute; where not,
    // the program filters anisotropically itself (LP_ANISOTROPY_FROM_GRADIENTS) through isotropic
    // samplers, one per sampling state (wrap s, wrap t, min and mag filter) of the scene's maps.
    std::optional<gl::GradientSampling> gradientModel;  // probed before the first compile
    std::vector<std::pair<std::array<GLint, 4>, gl::Sampler>> isotropicSamplers;
};

// Why the visibility buffer cannot make `scene`'s G-buffer on a GPU whose shader storage blocks hold
// at most maxStorageBlockBytes (GL_MAX_SHADER_STORAGE_BLOCK_SIZE; 0: unknown, not checked): the
// resolve reads all vertices, and all indices, each through one storage block, and ids number every
// triangle in 32 bits. Empty when it can.
std::string visibilityBufferUnsupported(const Scene& scene, uint64_t maxStorageBlockBytes);

GBuffer addVisibilityResolvePass(fg::FrameGraph& graph, VisibilityResolvePass& state, const FrameData& frame,
                                 const VisibilityBuffer& visibility, GBufferChannels channels);

}  // namespace lp
