#include "passes/visibility_resolve_pass.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <map>
#include <set>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/gl/shader.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/scene_gpu.hpp"
#include "passes/skinning_pass.hpp"

namespace lp {

namespace {

// The storage block of the animated meshes' previous positions (visibility_resolve.comp's
// LP_PREVIOUS_POSITIONS_BINDING); 0 to 5 are the geometry's, the draws', meshes' and materials'.
constexpr GLuint kPreviousPositionsBinding = 6;

// std430 records of visibility_resolve.comp.
struct MeshRecord {
    glm::mat4 modelView, normalMatrix, clipFromModel, previousClipFromModel;
};
struct MaterialRecord {
    glm::vec4 diffuseOpacity, specularMetallic, shininessRoughnessBumpNormal, occlusionCutoff;
    glm::vec4 clearcoat;  // KHR_materials_clearcoat's factor, roughness, normal map scale
    glm::uvec4 flags;
};
// The maps the resolve samples as their MaterialMapBit (the emissive map is the emission pass's), and
// three more bits above them (visibility_resolve.comp's LP_MATERIAL_*).
enum MaterialFlag : uint32_t { AlphaMask = 2048, Flat = 4096, SpecularF90 = 8192 };
constexpr uint32_t kAnyMap = kDiffuseMapBit | kBumpMapBit | kNormalMapBit | kMetalRoughMapBit | kOcclusionMapBit |
                             kSpecularMapBit | kSpecularColorMapBit | kClearcoatMapBit | kClearcoatRoughnessMapBit |
                             kClearcoatNormalMapBit;
static_assert(kClearcoatNormalMapBit < AlphaMask, "the material flags lie above the map bits");

// material.glsl's maps, in its uMapAnisotropy order: units 0..4, the specular maps', the clearcoat maps'.
constexpr int kResolveMaps = 10;
constexpr GLuint kResolveMapUnits[kResolveMaps] = {0, 1, 2, 3, 4, kMaterialSpecularUnit, kMaterialSpecularColorUnit,
                                                   kMaterialClearcoatUnit, kMaterialClearcoatRoughnessUnit,
                                                   kMaterialClearcoatNormalUnit};

uint32_t materialFlags(const GpuMaterial& m) {
    return (m.diffuseMap ? kDiffuseMapBit : 0u) | (m.bumpMap ? kBumpMapBit : 0u) | (m.normalMap ? kNormalMapBit : 0u) |
           (m.metallicRoughnessMap ? kMetalRoughMapBit : 0u) | (m.occlusionMap ? kOcclusionMapBit : 0u) |
           (m.specularMap ? kSpecularMapBit : 0u) | (m.specularColorMap ? kSpecularColorMapBit : 0u) |
           (m.clearcoatMap ? kClearcoatMapBit : 0u) | (m.clearcoatRoughnessMap ? kClearcoatRoughnessMapBit : 0u) |
           (m.clearcoatNormalMap ? kClearcoatNormalMapBit : 0u) |
           (m.alphaMask ? AlphaMask : 0u) | (m.flat ? Flat : 0u) | (m.dielectricF90 ? SpecularF90 : 0u);
}

GLint bufferSize(GLuint buffer) {
    GLint size = 0;
    glGetNamedBufferParameteriv(buffer, GL_BUFFER_SIZE, &size);
    return size;
}

// The scene's geometry as storage buffers: every stored mesh's vertices and indices back to back
// (copied on the GPU; a model's instances share its buffers, so they are copied once) and the draw
// table. Once per scene.
void buildGeometry(VisibilityResolvePass& state, const SceneGpu& gpu) {
    struct Stored {
        const GpuMesh* mesh;
        GLint vertexBytes, indexBytes;
        GLintptr vertexOffset, indexOffset;
    };
    std::vector<Stored> stored;
    std::map<GLuint, size_t> storedIndex;  // vertex buffer -> its entry in `stored`
    std::vector<uint32_t> indexBases, vertexBases;
    GLsizeiptr vertexBytes = 0, indexBytes = 0;
    for (const GpuMesh& m : gpu.meshes) {
        auto it = storedIndex.find(m.vertices.id());
        if (it == storedIndex.end()) {
            const GLint vb = bufferSize(m.vertices.id()), ib = bufferSize(m.indices.id());
            it = storedIndex.emplace(m.vertices.id(), stored.size()).first;
            stored.push_back({&m, vb, ib, vertexBytes, indexBytes});
            vertexBytes += vb;
            indexBytes += ib;
        }
        const Stored& at = stored[it->second];
        vertexBases.push_back(uint32_t(at.vertexOffset / GLintptr(sizeof(GpuVertex))));
        indexBases.push_back(uint32_t(at.indexOffset / GLintptr(sizeof(uint32_t))));
    }
    // Empty storage buffers are not allowed: at least one element each.
    state.vertices = gl::makeBuffer(std::max<GLsizeiptr>(vertexBytes, 16), nullptr, 0, "gbuffer_resolve.vertices");
    state.indices = gl::makeBuffer(std::max<GLsizeiptr>(indexBytes, 16), nullptr, 0, "gbuffer_resolve.indices");
    for (const Stored& st : stored) {
        if (st.vertexBytes > 0) glCopyNamedBufferSubData(st.mesh->vertices.id(), state.vertices.id(), 0, st.vertexOffset, st.vertexBytes);
        if (st.indexBytes > 0) glCopyNamedBufferSubData(st.mesh->indices.id(), state.indices.id(), 0, st.indexOffset, st.indexBytes);
    }
    // The second uv set, at the same vertex numbers; only a scene that samples it has one.
    state.uv1 = {};
    if (gpu.secondUvSet) {
        const GLsizeiptr uvBytes = vertexBytes / GLsizeiptr(sizeof(GpuVertex)) * GLsizeiptr(sizeof(glm::vec2));
        state.uv1 = gl::makeBuffer(std::max<GLsizeiptr>(uvBytes, 16), nullptr, 0, "gbuffer_resolve.uv1");
        const float zero = 0.0f;
        glClearNamedBufferData(state.uv1.id(), GL_R32F, GL_RED, GL_FLOAT, &zero);
        for (const Stored& st : stored) {
            const GLuint uv1 = st.mesh->uv1.id();
            const GLint ub = uv1 != 0 ? bufferSize(uv1) : 0;
            const GLintptr uo = st.vertexOffset / GLintptr(sizeof(GpuVertex)) * GLintptr(sizeof(glm::vec2));
            if (ub > 0) glCopyNamedBufferSubData(uv1, state.uv1.id(), 0, uo, ub);
        }
    }
    state.previousPositions = {};
    if (gpu.animated) {
        const GLsizeiptr bytes = vertexBytes / GLsizeiptr(sizeof(GpuVertex)) * GLsizeiptr(sizeof(glm::vec4));
        state.previousPositions = gl::makeBuffer(std::max<GLsizeiptr>(bytes, 16), nullptr, 0, "gbuffer_resolve.previous_positions");
        const float zero = 0.0f;
        glClearNamedBufferData(state.previousPositions.id(), GL_R32F, GL_RED, GL_FLOAT, &zero);
    }
    std::vector<VisibilityDrawRecord> records = visibilityDrawRecords(gpu, indexBases, vertexBases);
    state.drawCount = uint32_t(records.size());
    if (records.empty()) records.emplace_back();
    state.draws = gl::makeBuffer(GLsizeiptr(records.size() * sizeof(VisibilityDrawRecord)), records.data(), 0,
                                 "gbuffer_resolve.draws");
    state.geometryOf = &gpu;
    state.geometryTriangles = gpu.triangleCount;
}

// An animated mesh's pose of this frame into the concatenated buffers: its vertices, and its previous
// positions for the velocity. Copies on the GPU, ordered by GL after earlier frames' reads.
void copyPoses(VisibilityResolvePass& state, const SceneGpu& gpu) {
    GLintptr vo = 0;
    std::set<GLuint> copied;  // buildGeometry's order: each vertex buffer once
    for (const GpuMesh& m : gpu.meshes) {
        if (!copied.insert(m.vertices.id()).second) continue;
        const GLint vb = bufferSize(m.vertices.id());
        if (m.animated && vb > 0) {
            glCopyNamedBufferSubData(m.vertices.id(), state.vertices.id(), 0, vo, vb);
            const GLintptr po = vo / GLintptr(sizeof(GpuVertex)) * GLintptr(sizeof(glm::vec4));
            glCopyNamedBufferSubData(m.previousPositions.id(), state.previousPositions.id(), 0, po, bufferSize(m.previousPositions.id()));
        }
        vo += vb;
    }
}

// An isotropic sampler with `texture`'s wrap modes and filters, for the resolve's own anisotropic
// filter (LP_ANISOTROPY_FROM_GRADIENTS): made once per sampling state.
GLuint isotropicSampler(VisibilityResolvePass& state, GLuint texture) {
    std::array<GLint, 4> key{};
    glGetTextureParameteriv(texture, GL_TEXTURE_WRAP_S, &key[0]);
    glGetTextureParameteriv(texture, GL_TEXTURE_WRAP_T, &key[1]);
    glGetTextureParameteriv(texture, GL_TEXTURE_MIN_FILTER, &key[2]);
    glGetTextureParameteriv(texture, GL_TEXTURE_MAG_FILTER, &key[3]);
    for (const auto& [k, sampler] : state.isotropicSamplers)
        if (k == key) return sampler.id();
    gl::Sampler sampler = gl::makeSampler("gbuffer_resolve.isotropic");
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_S, key[0]);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_WRAP_T, key[1]);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MIN_FILTER, key[2]);
    glSamplerParameteri(sampler.id(), GL_TEXTURE_MAG_FILTER, key[3]);
    glSamplerParameterf(sampler.id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, 1.0f);
    state.isotropicSamplers.emplace_back(key, std::move(sampler));
    return state.isotropicSamplers.back().second.id();
}

std::string megabytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

}  // namespace

std::string visibilityBufferUnsupported(const Scene& scene, uint64_t maxStorageBlockBytes) {
    uint64_t vertexBytes = 0, indexBytes = 0, triangles = 0;
    for (const ModelInstance& m : scene.models) {  // stored once, drawn (and numbered) per instance
        vertexBytes += uint64_t(m.mesh.vertices.size()) * sizeof(GpuVertex);
        indexBytes += uint64_t(m.mesh.indices.size()) * sizeof(uint32_t);
        triangles += uint64_t(m.instanceCount()) * (m.mesh.indices.size() / 3);
    }
    // id = triangle + 1 in 32 bits, 0 meaning none (shaders/common/visibility.glsl)
    if (triangles > uint64_t(UINT32_MAX) - 1)
        return std::to_string(triangles) + " triangles do not fit the 32-bit triangle ids";
    if (maxStorageBlockBytes == 0) return "";
    const std::string limit = " exceed this GPU's shader storage block limit (" + megabytes(maxStorageBlockBytes) +
                              ", GL_MAX_SHADER_STORAGE_BLOCK_SIZE) the resolve reads them through";
    if (vertexBytes > maxStorageBlockBytes) return "the scene's vertices (" + megabytes(vertexBytes) + ")" + limit;
    if (indexBytes > maxStorageBlockBytes) return "the scene's indices (" + megabytes(indexBytes) + ")" + limit;
    return "";
}

GBuffer addVisibilityResolvePass(fg::FrameGraph& graph, VisibilityResolvePass& state, const FrameData& frame,
                                 const VisibilityBuffer& visibility, GBufferChannels channels) {
    static_assert(offsetof(GpuVertex, normal) == 3 * sizeof(float) && offsetof(GpuVertex, uv) == 6 * sizeof(float) &&
                      offsetof(GpuVertex, tangent) == 8 * sizeof(float) && offsetof(GpuVertex, color) == 12 * sizeof(float) &&
                      sizeof(GpuVertex) == 16 * sizeof(float),
                  "visibility_resolve.comp reads vertices as floats at these offsets");
    const int w = frame.width, h = frame.height;
    const GBufferSettings layout = frame.settings->gbuffer;
    struct Data {
        GBuffer out;
        fg::ResourceId ids, depth;
    };
    const Data& data = graph.addPass<Data>(
        "gbuffer_resolve", fg::PassKind::Compute,
        [&](fg::PassBuilder& b, Data& d) {
            d.ids = b.read(visibility.ids, fg::Usage::Sampled);
            d.depth = b.read(visibility.depth, fg::Usage::Sampled);  // where the ids hold a triangle
            d.out = createGBufferColourTargets(b, w, h, layout, channels, fg::Usage::ImageStore);
            d.out.depth = d.depth;  // written by gbuffer_visibility, only read here
            readPosedVertices(b, frame, fg::Usage::Transfer);  // copies the animated meshes' vertices (copyPoses)
        },
        [&state, frame](const Data& d, const fg::PassResources& res) {
            const SceneGpu& gpu = *frame.gpu;
            if (state.geometryOf != &gpu || state.geometryTriangles != gpu.triangleCount) {
                buildGeometry(state, gpu);
                state.texturedMaterials.clear();
                for (size_t i = 0; i < gpu.materials.size(); ++i)
                    if (materialFlags(gpu.materials[i]) & kAnyMap) state.texturedMaterials.push_back(int(i));
            }
            if (gpu.animated) copyPoses(state, gpu);
            if (!state.gradientModel) state.gradientModel = gl::probeGradientSampling(*frame.shaders);
            const gl::GradientSampling& gradients = *state.gradientModel;
            const bool ownAnisotropy = !gradients.computeFollowsGradients;
            const GLuint prog = programForLayout(state.program, state.layout, frame, [&](std::vector<std::string> defines) {
                                    addGBufferImageDefines(defines, frame.settings->gbuffer);
                                    defines.push_back("LP_VERTEX_FLOATS " + std::to_string(sizeof(GpuVertex) / sizeof(float)));
                                    defines.push_back("LP_PREVIOUS_POSITIONS_BINDING " + std::to_string(kPreviousPositionsBinding));
                                    if (ownAnisotropy) defines.push_back("LP_ANISOTROPY_FROM_GRADIENTS");
                                    return frame.shaders->compute("visibility_resolve.comp", defines);
                                }).id();
            if (!state.rasterModel) state.rasterModel = gl::probeRasterInterpolation(*frame.shaders);
            // Per frame: the meshes' transforms (the view moves) and the materials (the viewer switches flat).
            const glm::mat4 viewProjection = frame.unjitteredProjection * frame.view;  // velocity is unjittered
            std::vector<MeshRecord> meshes;
            for (const GpuMesh& m : gpu.meshes) {
                const glm::mat4 mv = frame.view * m.model;
                meshes.push_back({mv, glm::mat4(glm::inverseTranspose(glm::mat3(mv))), viewProjection * m.model,
                                  frame.previousViewProjection * m.model});
            }
            // Into buffers no earlier frame's resolve still reads (gl::StreamBuffer): a moving camera
            // changes the transforms every frame.
            const GLuint meshBuffer = state.meshes.fill(meshes.data(), meshes.size() * sizeof(MeshRecord));
            std::vector<MaterialRecord> materials;
            for (const GpuMaterial& m : gpu.materials)
                materials.push_back({glm::vec4(m.diffuse, m.opacity), glm::vec4(m.specular, m.metallic),
                                     glm::vec4(m.shininess, m.roughness, m.bumpScale, m.normalScale),
                                     glm::vec4(m.occlusionStrength, m.alphaCutoff, m.dielectricF90.value_or(1.0f), 0.0f),
                                     glm::vec4(m.clearcoat, m.clearcoatRoughness, m.clearcoatNormalScale, 0.0f),
                                     glm::uvec4(materialFlags(m), m.secondUvMaps, 0u, 0u)});
            const GLuint materialBuffer = state.materials.fill(materials.data(), materials.size() * sizeof(MaterialRecord));

            const GLuint bound = bindGBufferImages(res, d.out);
            auto loc = [&frame, prog](const char* name) { return gl::Uniforms(frame.shaders, prog).location(name); };
            glProgramUniform1ui(prog, loc("uTargets"), bound);
            glProgramUniform1ui(prog, loc("uDrawCount"), state.drawCount);
            glProgramUniformMatrix4fv(prog, loc("uInverseProjection"), 1, GL_FALSE,
                                      glm::value_ptr(glm::inverse(frame.projection)));
            glProgramUniformMatrix4fv(prog, loc("uProjection"), 1, GL_FALSE, glm::value_ptr(frame.projection));
            glProgramUniform1f(prog, loc("uSubpixelSnap"), state.rasterModel->snapScale());
            if (ownAnisotropy) {
                glProgramUniform1i(prog, loc("uAnisotropyClampsRatio"), gradients.rasterClampsRatio);
                glProgramUniform1i(prog, loc("uAnisotropyLevels"), int(gradients.rasterLevels));
                glProgramUniform1i(prog, loc("uAnisotropyPerQuad"), gradients.rasterLevelPerQuad);
            }
            glProgramUniform1i(prog, loc("uDepthZeroToOne"),
                               frame.settings->gbuffer.position == GBufferPositionMode::ReversedZ);
            setBackgroundMotionUniforms(prog, frame);
            setBrdfUniforms(prog, frame);
            setMaterialInputUniform(prog, frame);
            const GLuint buffers[5] = {state.vertices.id(), state.indices.id(), state.draws.id(), meshBuffer, materialBuffer};
            for (GLuint i = 0; i < 5; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buffers[i]);
            if (state.uv1) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, state.uv1.id());
            glProgramUniform1i(prog, loc("uAnimated"), gpu.animated);
            if (gpu.animated) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPreviousPositionsBinding, state.previousPositions.id());
            glBindTextureUnit(5, res.texture(d.ids));
            glBindTextureUnit(6, res.texture(d.depth));
            glProgramUniform1f(prog, loc("uBackgroundDepth"),
                               frame.settings->gbuffer.position == GBufferPositionMode::ReversedZ ? 0.0f : 1.0f);
            glUseProgram(prog);
            const GLint filter = loc("uMaterialFilter");
            const GLuint groupsX = GLuint((frame.width + 7) / 8), groupsY = GLuint((frame.height + 7) / 8);
            // Untextured materials and the background; then each textured material with its maps.
            // The dispatches write disjoint pixels, so no barrier lies between them.
            glProgramUniform1i(prog, filter, -1);
            glDispatchCompute(groupsX, groupsY, 1);
            for (int material : state.texturedMaterials) {
                const GpuMaterial& m = gpu.materials[size_t(material)];
                glProgramUniform1i(prog, filter, material);
                // material.glsl's maps: units 0..4 and the specular maps' (its uMapAnisotropy order).
                const GLuint maps[kResolveMaps] = {m.diffuseMap,        m.bumpMap,      m.normalMap,
                                                   m.metallicRoughnessMap, m.occlusionMap, m.specularMap,
                                                   m.specularColorMap,    m.clearcoatMap, m.clearcoatRoughnessMap,
                                                   m.clearcoatNormalMap};
                float anisotropy[kResolveMaps];
                std::fill(std::begin(anisotropy), std::end(anisotropy), 1.0f);
                const int kMaps = kResolveMaps;
                const GLuint* units = kResolveMapUnits;
                for (int i = 0; i < kMaps; ++i) {
                    glBindTextureUnit(units[i], maps[i]);
                    if (!ownAnisotropy || !maps[i]) continue;
                    glGetTextureParameterfv(maps[i], GL_TEXTURE_MAX_ANISOTROPY_EXT, &anisotropy[i]);
                    glBindSampler(units[i], anisotropy[i] > 1.0f ? isotropicSampler(state, maps[i]) : 0);
                }
                if (ownAnisotropy) glProgramUniform1fv(prog, loc("uMapAnisotropy"), kMaps, anisotropy);
                glDispatchCompute(groupsX, groupsY, 1);
            }
            for (GLuint u : kResolveMapUnits) glBindSampler(u, 0);
            for (GLuint u = 0; u < 7; ++u) glBindTextureUnit(u, 0);
            unbindMaterialTextures();
            unbindGBufferImages();
            for (GLuint i = 0; i < 6; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, 0);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPreviousPositionsBinding, 0);
            glUseProgram(0);
        });
    return data.out;
}

}  // namespace lp
