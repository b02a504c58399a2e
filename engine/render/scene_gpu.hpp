#pragma once
// The scene's meshes, materials and textures on the GPU. Textures are shared by path, sRGB colour
// maps are stored as SRGB8_ALPHA8 (so sampling returns linear values) with full mip chains, and a
// missing texture becomes a visible checker with a warning.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/gl/handles.hpp"
#include "engine/gl/shared_handle.hpp"
#include "engine/gl/stream_buffer.hpp"
#include "engine/io/image_io.hpp"
#include "engine/render/gpu_skinning.hpp"
#include "engine/render/settings.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// A material map's image, decoded (rows top first): its file or embedded bytes, or the checker for a
// texture known to be unusable (TextureRef::problem; the caller says why) or one that does not load
// (loadTextureOrChecker warns). The raster's textures and the path tracer's maps read maps this way.
Image8 decodeTextureRef(const TextureRef& ref);

// A vertex in the GPU's vertex buffers: lp::Vertex up to its second uv set, which a mesh whose
// materials sample it keeps in a buffer of its own (GpuMesh::uv1). 64 bytes: the visibility resolve
// reads it as four vec4.
struct GpuVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 tangent;
    glm::vec4 color;
};
static_assert(sizeof(GpuVertex) == offsetof(Vertex, uv1), "GpuVertex is lp::Vertex up to uv1");

// The vertex attribute of the previous frame's position (gbuffer.vert's LP_PREVIOUS_POSITION_ATTRIBUTE):
// 0-4 are GpuVertex's members, 5 the second uv set.
constexpr GLuint kPreviousPositionAttribute = 6;

struct GpuMaterial {
    glm::vec3 diffuse{0.8f};  // base colour
    float opacity = 1.0f;
    glm::vec3 specular{0.04f};  // dielectric F0
    std::optional<float> dielectricF90;  // Material::dielectricF90 (KHR_materials_specular)
    GLuint specularMap = 0;       // its specularTexture (weight in a), 0: none
    GLuint specularColorMap = 0;  // its specularColorTexture (sRGB rgb), 0: none
    float clearcoat = 0.0f;  // Material::clearcoat (KHR_materials_clearcoat; 0: no coat), and the rest
    float clearcoatRoughness = 0.0f;
    float clearcoatNormalScale = 1.0f;
    GLuint clearcoatMap = 0, clearcoatRoughnessMap = 0, clearcoatNormalMap = 0;  // linear, 0: none
    // Material::transmission and its volume (transmissive(): drawn by the transparent pass); maps
    // linear, 0: none.
    float transmission = 0.0f;
    GLuint transmissionMap = 0;
    float ior = 1.5f;
    float thickness = 0.0f;
    GLuint thicknessMap = 0;
    float attenuationDistance = 0.0f;  // 0: infinite (no absorption)
    glm::vec3 attenuationColor{1.0f};
    bool transmissive() const { return transmission > 0.0f && !flat; }
    float metallic = 0.0f;
    float shininess = 32.0f;
    float roughness = 0.5f;
    glm::vec3 emission{0.0f};
    GLuint diffuseMap = 0;  // 0: none
    GLuint bumpMap = 0;
    float bumpScale = 1.0f;
    GLuint normalMap = 0;
    float normalScale = 1.0f;
    GLuint metallicRoughnessMap = 0;
    GLuint occlusionMap = 0;
    float occlusionStrength = 1.0f;
    GLuint emissiveMap = 0;
    uint32_t secondUvMaps = 0;  // Material::secondUvMaps: the maps sampled with the second uv set (TEXCOORD_1)
    bool alphaMask = false;
    // BLEND / MTL d < 1, or transmissive: drawn by the transparent pass, not into the G-buffer
    bool alphaBlend = false;
    float alphaCutoff = 0.5f;
    bool doubleSided = true;
    bool flat = false;  // Material::flat; the viewer's panel switches it
    std::string name;   // the model's and the material's name, "cornell_box/light"
    bool emissive() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }
};

struct GpuDraw {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int material = 0;  // into SceneGpu::materials
    glm::vec3 centre{0.0f};  // model space, the centre of the draw's bounding box
};

// An animated mesh's inputs to the skinning pass (--skinning gpu), made on its first pose on the
// GPU: the storage buffers of its SkinningLayout, uploaded once, and the stream its poses are packed
// into each frame the pose changes. The PoseBounds give the casters', draws' and mesh's bounds in
// any pose without reading the posed vertices back.
struct GpuSkinning {
    SkinningLayout layout;  // the ranges and counts (the per-vertex arrays are on the GPU only)
    gl::Buffer rest, joints, deltas, ranges, workRange;
    gl::StreamBuffer pose{"skinning.pose"};
    std::vector<std::pair<size_t, PoseBounds>> casterBounds;  // (SceneGpu::casterClusters index, bounds)
    std::vector<PoseBounds> drawBounds;                       // one a GpuMesh::draws entry
    PoseBounds meshBounds;
};

// One dispatch of the skinning pass: mesh `mesh`'s vertices, doing `mode` (kSkinningPose*,
// kSkinningKeepPrevious) with the pose `poseBase` vec4s into its last filled pose buffer.
struct SkinningDispatch {
    size_t mesh = 0;
    unsigned mode = 0;
    uint32_t poseBase = 0;
};

// One drawn copy of a model (placements order): a model's instances share its buffers, vertex array
// and materials, each with its own `model` matrix; an animated model's instances have buffers of
// their own (its pose is written into them).
struct GpuMesh {
    std::string name;
    gl::Shared<gl::VertexArray> vao;
    gl::Shared<gl::Buffer> vertices;
    gl::Shared<gl::Buffer> indices;
    gl::Shared<gl::Buffer> uv1;  // the second uv set, a vec2 a vertex (attribute 5), where its materials sample it; else none
    glm::mat4 model{1.0f};
    size_t sourceModel = 0;  // index into Scene::models
    size_t instance = 0;     // which of its instances
    std::vector<GpuDraw> draws;
    // An animated model (a glTF clip playing, SceneGpu::pose): `vertices` holds the pose at the frame's
    // time and `previousPositions` (a vec4 a vertex, w = 1; vertex attribute 6) the positions at the
    // previous frame's time, for motion vectors. A still mesh reads attribute 6 from `vertices`' own
    // positions: its previous position is its position.
    bool animated = false;
    gl::Shared<gl::Buffer> previousPositions;
    // Changes whenever the pose in `vertices` changes (the shadow cascade cache and the visibility
    // resolve's copy of the geometry follow it); 0 for a mesh that never moves.
    uint64_t poseVersion = 0;
    // The box of the vertices in the pose `vertices` holds (mesh space): the rest pose's, then
    // posed vertices' (--skinning cpu) or joint-transformed bounds (gpu, conservative).
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
    std::unique_ptr<GpuSkinning> skinning;  // --skinning gpu; null until the mesh is first posed there
};

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);
    std::vector<GpuMesh> meshes;
    std::vector<GpuMaterial> materials;
    std::vector<CasterCluster> casterClusters;  // meshes[i] is CasterCluster::model i (shadow caster culling)
    size_t geometryBytes = 0;
    size_t textureBytes = 0;
    size_t triangleCount = 0;   // drawn: every instance's (the visibility buffer numbers them)
    size_t storedVertices = 0;  // in vertex buffers: a mesh its instances share counts once
    bool vertexColors = false;  // some vertex has a colour other than white (the G-buffer programs read them: LP_VERTEX_COLOR)
    bool secondUvSet = false;   // some material samples TEXCOORD_1 (the programs read it: LP_SECOND_UV)
    bool animated = false;      // some mesh is animated (the visibility resolve reads previous positions)
    // Whether some animated vertex is elsewhere at the previous frame's time than at this frame's
    // (set by pose): motion blur then runs with a still camera.
    bool animatedMotion = false;

    // Poses every animated model of `scene` (the scene this was made from) at `time`: positions,
    // normals and tangents into its vertex buffer, positions at `previousTime` into its previous
    // positions; a pose the buffers already hold is not made again. The casters' bounds, the
    // draws' centres and the mesh bounds follow. Node matrices and morph weights are CPU work
    // (engine/scene/animation); the vertices are posed on the CPU and uploaded (SkinningMode::Cpu),
    // or by the skinning pass (Gpu): this uploads the poses and lists its dispatches (skinningWork).
    void pose(const Scene& scene, double time, double previousTime, SkinningMode mode);

    // The dispatches the frame's skinning pass runs (passes/skinning_pass.hpp), set by pose; empty
    // when no vertex buffer changes. The pass calls skinningWorkDone() once it recorded them: a pose
    // whose dispatches never ran (the pass culled or disabled) is made again in full next time.
    const std::vector<SkinningDispatch>& skinningWork() const { return skinningWork_; }
    void skinningWorkDone() const { skinningWorkDone_ = true; }
    // World-space bounds of every model in the pose its vertex buffer holds (Scene::bounds, posed):
    // what the shadow cascades fit.
    void bounds(const Scene& scene, glm::vec3& lo, glm::vec3& hi) const;

private:
    GLuint texture(const TextureRef& ref, bool srgb);
    // What an animated mesh's buffers hold: the node matrices and morph weights of its current and previous pose.
    struct Pose {
        NodePose current, previousPose;
        std::vector<Vertex> vertices;  // the mesh's vertices as loaded, posed in place (--skinning cpu)
        std::vector<glm::vec4> previous;
        SkinningMode mode = SkinningMode::Cpu;  // how the buffers' pose was made
    };
    void poseOnCpu(size_t mesh, const ModelInstance& model, NodePose current, NodePose previousPose);
    void poseOnGpu(size_t mesh, const ModelInstance& model, NodePose current, NodePose previousPose);
    std::vector<SkinningDispatch> skinningWork_;
    mutable bool skinningWorkDone_ = true;
    std::vector<Pose> poses_;  // one a mesh; empty for meshes that are not animated
    std::map<std::string, gl::Texture> textures_;
};

}  // namespace lp
