#include "engine/render/scene_gpu.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <cmath>
#include <limits>

#include "engine/core/log.hpp"
#include "engine/gl/limits.hpp"
#include "engine/io/image_io.hpp"

namespace lp {

namespace {
// A non-default sampler's part of the texture cache's key: one image sampled two ways is two textures.
std::string samplerKey(const TextureSampler& s) {
    if (s.isDefault()) return "";
    return "#sampler(" + std::to_string(s.wrapS) + "," + std::to_string(s.wrapT) + "," + std::to_string(s.magFilter) + "," +
           std::to_string(s.minFilter) + ")";
}
}  // namespace

Image8 decodeTextureRef(const TextureRef& ref) {
    if (!ref.problem.empty()) return makeCheckerImage();
    const std::filesystem::path path = ref.encoded ? std::filesystem::path(ref.key) : ref.path;
    return ref.encoded ? decodeTextureOrChecker(*ref.encoded, path) : loadTextureOrChecker(path);
}

GLuint SceneGpu::texture(const TextureRef& ref, bool srgb) {
    const std::string key = ref.key + samplerKey(ref.sampler) + (srgb ? "#srgb" : "#linear");
    auto it = textures_.find(key);
    if (it != textures_.end()) return it->second.id();
    const std::filesystem::path path = ref.encoded || !ref.problem.empty() ? std::filesystem::path(ref.key) : ref.path;
    if (!ref.problem.empty()) logWarn(ref.key + ": " + ref.problem + "; using a checker texture");
    Image8 img = decodeTextureRef(ref);
    // Over the GPU's texture limits: halved until it fits, with a warning (docs/bad-input.md).
    if (const gl::TextureFit fit = gl::fitTexture(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height); fit.halvings > 0) {
        const int w = img.width, h = img.height;
        img = downscaleToFit(img, std::max(w, h) >> fit.halvings);
        logWarn(path.string() + ": " + std::to_string(w) + "x" + std::to_string(h) + " is " + fit.reason +
                "; downscaled to " + std::to_string(img.width) + "x" + std::to_string(img.height));
    }
    // Rows arrive top first; OBJ texture coordinates put v = 0 at the bottom.
    std::vector<uint8_t> flipped(img.rgba.size());
    const size_t row = size_t(img.width) * 4;
    for (int y = 0; y < img.height; ++y)
        std::copy_n(&img.rgba[size_t(img.height - 1 - y) * row], row, &flipped[size_t(y) * row]);
    int levels = gl::fullMipCount(img.width, img.height);
    gl::Texture t = gl::makeTexture2D(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height, levels,
                                      path.filename().string());
    glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    glGenerateTextureMipmap(t.id());
    // The material's sampler (glTF's codes are OpenGL's enums); by default repeating, trilinear and
    // anisotropic. Any other filter gets no anisotropy: it would blend the texels that nearest
    // magnification asks to keep apart (llvmpipe does), or the mip levels a nearest one keeps.
    const TextureSampler& sampler = ref.sampler;
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GLint(sampler.wrapS));
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GLint(sampler.wrapT));
    if (sampler.magFilter != 0) glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GLint(sampler.magFilter));
    if (sampler.minFilter != 0) glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GLint(sampler.minFilter));
    const bool trilinear = (sampler.minFilter == 0 || sampler.minFilter == GL_LINEAR_MIPMAP_LINEAR) &&
                           (sampler.magFilter == 0 || sampler.magFilter == GL_LINEAR);
    if (GLAD_GL_EXT_texture_filter_anisotropic && trilinear)
        glTextureParameterf(t.id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, 8.0f);
    textureBytes += size_t(img.width) * img.height * 4 * 4 / 3;
    GLuint id = t.id();
    textures_.emplace(key, std::move(t));
    return id;
}

static_assert(offsetof(GpuVertex, normal) == offsetof(Vertex, normal) && offsetof(GpuVertex, uv) == offsetof(Vertex, uv) &&
                  offsetof(GpuVertex, tangent) == offsetof(Vertex, tangent) && offsetof(GpuVertex, color) == offsetof(Vertex, color),
              "GpuVertex is copied from the front of lp::Vertex");

SceneGpu::SceneGpu(const Scene& scene) {
    std::map<std::string, size_t> geometryOwners;  // a geometry key (and uv1 or not) -> the mesh that uploaded it
    for (size_t modelIndex = 0; modelIndex < scene.models.size(); ++modelIndex) {
        const ModelInstance& model = scene.models[modelIndex];
        const MeshData& mesh = model.mesh;
        // An animated model's vertices are rewritten each frame it moves (pose); every other buffer is
        // immutable, and a still model's instances share it.
        const bool animatedModel =
            model.animation && !model.playingClips.empty() && !model.animation->ranges.empty() && !mesh.vertices.empty();
        const int base = int(materials.size());
        for (const auto& m : mesh.materials) {
            GpuMaterial g;
            g.diffuse = m.diffuse;
            g.opacity = m.opacity;
            g.specular = m.specular;
            g.dielectricF90 = m.dielectricF90;
            g.metallic = m.metallic;
            g.shininess = m.shininess;
            g.roughness = m.roughness;
            g.emission = m.emission;
            g.bumpScale = m.bumpScale;
            g.normalScale = m.normalScale;
            g.occlusionStrength = m.occlusionStrength;
            g.alphaMask = m.alphaMode == AlphaMode::Mask;
            // Transmissive materials refract the opaque frame: the transparent pass draws them too.
            g.alphaBlend = m.alphaMode == AlphaMode::Blend || m.transmissive();
            g.alphaCutoff = m.alphaCutoff;
            g.doubleSided = m.doubleSided;
            g.flat = m.flat;
            g.name = model.name + "/" + m.name;
            if (!m.diffuseMap.empty()) g.diffuseMap = texture(m.diffuseMap, true);
            if (!m.bumpMap.empty()) g.bumpMap = texture(m.bumpMap, false);
            if (!m.normalMap.empty()) g.normalMap = texture(m.normalMap, false);
            if (!m.metallicRoughnessMap.empty()) g.metallicRoughnessMap = texture(m.metallicRoughnessMap, false);
            if (!m.occlusionMap.empty()) g.occlusionMap = texture(m.occlusionMap, false);
            if (!m.emissiveMap.empty()) g.emissiveMap = texture(m.emissiveMap, true);
            if (!m.specularMap.empty()) g.specularMap = texture(m.specularMap, false);
            if (!m.specularColorMap.empty()) g.specularColorMap = texture(m.specularColorMap, true);
            if (m.hasClearcoat()) {
                g.clearcoat = m.clearcoat;
                g.clearcoatRoughness = m.clearcoatRoughness;
                g.clearcoatNormalScale = m.clearcoatNormalScale;
                if (!m.clearcoatMap.empty()) g.clearcoatMap = texture(m.clearcoatMap, false);
                if (!m.clearcoatRoughnessMap.empty()) g.clearcoatRoughnessMap = texture(m.clearcoatRoughnessMap, false);
                if (!m.clearcoatNormalMap.empty()) g.clearcoatNormalMap = texture(m.clearcoatNormalMap, false);
            }
            if (m.transmissive()) {
                g.transmission = m.transmission;
                g.ior = m.ior;
                g.thickness = m.thickness;
                g.attenuationDistance = std::isfinite(m.attenuationDistance) ? m.attenuationDistance : 0.0f;
                g.attenuationColor = m.attenuationColor;
                if (!m.transmissionMap.empty()) g.transmissionMap = texture(m.transmissionMap, false);
                if (!m.thicknessMap.empty()) g.thicknessMap = texture(m.thicknessMap, false);
            }
            g.secondUvMaps = m.secondUvMaps();
            secondUvSet |= g.secondUvMaps != 0;
            materials.push_back(g);
        }
        std::vector<GpuDraw> draws;
        for (const auto& sm : mesh.subMeshes) {
            // The centre of the draw's bounding box: the transparent pass sorts draws by its view depth.
            glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
            for (uint32_t i = sm.firstIndex; i < sm.firstIndex + sm.indexCount && i < mesh.indices.size(); ++i) {
                const glm::vec3& p = mesh.vertices[mesh.indices[i]].position;
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            const glm::vec3 centre = sm.indexCount > 0 ? 0.5f * (lo + hi) : glm::vec3(0.0f);
            draws.push_back({sm.firstIndex, sm.indexCount, base + sm.material, centre});
        }
        const bool meshSamplesUv1 =
            std::any_of(mesh.materials.begin(), mesh.materials.end(), [](const Material& m) { return m.samplesUv1(); });
        // The mesh whose buffers this model's copies draw: an earlier model's of the same file (or
        // primitive), else its own first instance's. An animated model's copies each pose their own.
        const std::string shareKey =
            model.geometryKey.empty() || animatedModel ? std::string() : model.geometryKey + (meshSamplesUv1 ? " uv1" : "");
        std::optional<size_t> owner;
        if (auto it = geometryOwners.find(shareKey); !shareKey.empty() && it != geometryOwners.end()) owner = it->second;
        for (size_t instance = 0; instance < model.instanceCount(); ++instance) {
            GpuMesh gm;
            gm.name = model.instances.empty() ? model.name : model.name + "[" + std::to_string(instance) + "]";
            gm.model = model.instanceTransform(instance);
            gm.sourceModel = modelIndex;
            gm.instance = instance;
            gm.boundsMin = mesh.boundsMin;
            gm.boundsMax = mesh.boundsMax;
            gm.draws = draws;
            triangleCount += mesh.indices.size() / 3;
            Pose pose;
            if (!owner || animatedModel) {
                gm.vao = gl::makeVertexArray(model.name);
                std::vector<GpuVertex> vertices(mesh.vertices.size());
                for (size_t i = 0; i < vertices.size(); ++i) std::memcpy(&vertices[i], &mesh.vertices[i], sizeof(GpuVertex));
                gm.animated = animatedModel;
                storedVertices += vertices.size();
                gm.vertices = gl::makeBuffer(GLsizeiptr(vertices.size() * sizeof(GpuVertex)), vertices.data(),
                                             gm.animated ? GL_DYNAMIC_STORAGE_BIT : 0, model.name + ".vertices");
                gm.indices = gl::makeBuffer(GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(), 0,
                                            model.name + ".indices");
                geometryBytes += vertices.size() * sizeof(GpuVertex) + mesh.indices.size() * sizeof(uint32_t);
                if (meshSamplesUv1 && !mesh.vertices.empty()) {
                    std::vector<glm::vec2> uv1(mesh.vertices.size());
                    for (size_t i = 0; i < uv1.size(); ++i) uv1[i] = mesh.vertices[i].uv1;
                    gm.uv1 = gl::makeBuffer(GLsizeiptr(uv1.size() * sizeof(glm::vec2)), uv1.data(), 0, model.name + ".uv1");
                    geometryBytes += uv1.size() * sizeof(glm::vec2);
                }
                for (const Vertex& v : mesh.vertices)
                    if (v.color != glm::vec4(1.0f)) {
                        vertexColors = true;
                        break;
                    }
                const GLuint vao = gm.vao.id();
                glVertexArrayVertexBuffer(vao, 0, gm.vertices.id(), 0, sizeof(GpuVertex));
                glVertexArrayElementBuffer(vao, gm.indices.id());
                auto attrib = [vao](GLuint loc, GLint n, size_t offset) {
                    glEnableVertexArrayAttrib(vao, loc);
                    glVertexArrayAttribFormat(vao, loc, n, GL_FLOAT, GL_FALSE, GLuint(offset));
                    glVertexArrayAttribBinding(vao, loc, 0);
                };
                attrib(0, 3, offsetof(GpuVertex, position));
                attrib(1, 3, offsetof(GpuVertex, normal));
                attrib(2, 2, offsetof(GpuVertex, uv));
                attrib(3, 4, offsetof(GpuVertex, tangent));
                attrib(4, 4, offsetof(GpuVertex, color));
                // Attribute kPreviousPositionAttribute, the previous frame's position (gbuffer.vert's velocity): an animated mesh's own
                // buffer, else the vertex's position.
                if (gm.animated) {
                    std::vector<glm::vec4> previous(vertices.size());
                    for (size_t i = 0; i < previous.size(); ++i) previous[i] = glm::vec4(vertices[i].position, 1.0f);
                    gm.previousPositions = gl::makeBuffer(GLsizeiptr(previous.size() * sizeof(glm::vec4)), previous.data(), GL_DYNAMIC_STORAGE_BIT,
                                                          model.name + ".previous_positions");
                    geometryBytes += previous.size() * sizeof(glm::vec4);
                    glVertexArrayVertexBuffer(vao, 2, gm.previousPositions.id(), 0, sizeof(glm::vec4));
                    pose.vertices = mesh.vertices;
                    pose.previous = std::move(previous);
                    animated = true;
                } else {
                    glVertexArrayVertexBuffer(vao, 2, gm.vertices.id(), 0, sizeof(GpuVertex));
                }
                glEnableVertexArrayAttrib(vao, kPreviousPositionAttribute);
                glVertexArrayAttribFormat(vao, kPreviousPositionAttribute, 3, GL_FLOAT, GL_FALSE, 0);
                glVertexArrayAttribBinding(vao, kPreviousPositionAttribute, 2);
                if (gm.uv1.id() != 0) {  // without it attribute 5 reads (0, 0): no material of the mesh samples it
                    glVertexArrayVertexBuffer(vao, 1, gm.uv1.id(), 0, sizeof(glm::vec2));
                    glEnableVertexArrayAttrib(vao, 5);
                    glVertexArrayAttribFormat(vao, 5, 2, GL_FLOAT, GL_FALSE, 0);
                    glVertexArrayAttribBinding(vao, 5, 1);
                }
                if (!animatedModel) {
                    owner = meshes.size();
                    if (!shareKey.empty()) geometryOwners.emplace(shareKey, *owner);
                }
            } else {
                const GpuMesh& from = meshes[*owner];
                gm.vao = from.vao;
                gm.vertices = from.vertices;
                gm.indices = from.indices;
                gm.uv1 = from.uv1;
            }
            poses_.push_back(std::move(pose));
            meshes.push_back(std::move(gm));
        }
    }
    casterClusters = buildCasterClusters(scene);
}

void SceneGpu::pose(const Scene& scene, double time, double previousTime, SkinningMode mode) {
    animatedMotion = false;
    // Dispatches listed last time that never ran: those meshes' buffers do not hold what their
    // Pose says, so they are posed again in full.
    const bool lostWork = !skinningWork_.empty() && !skinningWorkDone_;
    skinningWork_.clear();
    skinningWorkDone_ = false;
    for (size_t i = 0; i < meshes.size(); ++i) {
        if (!meshes[i].animated || meshes[i].sourceModel >= scene.models.size()) continue;
        const ModelInstance& model = scene.models[meshes[i].sourceModel];
        const NodeAnimation& animation = *model.animation;
        Pose& p = poses_[i];
        NodePose current = animatedPose(animation, model.playingClips, time);
        NodePose previousPose = previousTime == time ? current : animatedPose(animation, model.playingClips, previousTime);
        animatedMotion |= current != previousPose;
        if (p.mode != mode || (lostWork && p.mode == SkinningMode::Gpu)) {
            // The other mode's bookkeeping says nothing about what this one would keep.
            p.current = {};
            p.previousPose = {};
            p.mode = mode;
        }
        if (mode == SkinningMode::Gpu) poseOnGpu(i, model, std::move(current), std::move(previousPose));
        else poseOnCpu(i, model, std::move(current), std::move(previousPose));
    }
    if (skinningWork_.empty()) skinningWorkDone_ = true;
}

void SceneGpu::poseOnCpu(size_t i, const ModelInstance& model, NodePose current, NodePose previousPose) {
    GpuMesh& gm = meshes[i];
    const NodeAnimation& animation = *model.animation;
    Pose& p = poses_[i];
    if (previousPose != p.previousPose) {
        // Playing on, the previous frame's pose is the one the vertex buffer holds: its positions
        // are kept; otherwise (a jump, the first frame) they are posed from the rest pose.
        if (previousPose == p.current) {
            for (const NodeVertexRange& r : animation.ranges)
                for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount; ++k) p.previous[k] = glm::vec4(p.vertices[k].position, 1.0f);
        } else {
            std::vector<Vertex> posed = p.vertices;
            poseVertices(animation, previousPose, posed);
            for (const NodeVertexRange& r : animation.ranges)
                for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount; ++k) p.previous[k] = glm::vec4(posed[k].position, 1.0f);
        }
        glNamedBufferSubData(gm.previousPositions.id(), 0, GLsizeiptr(p.previous.size() * sizeof(glm::vec4)), p.previous.data());
        p.previousPose = std::move(previousPose);
    }
    if (current == p.current) return;
    poseVertices(animation, current, p.vertices);
    // Only the ranges that move are written: the vertices of still nodes are never touched.
    std::vector<GpuVertex> range;
    for (const NodeVertexRange& r : animation.ranges) {
        range.resize(r.vertexCount);
        for (uint32_t k = 0; k < r.vertexCount; ++k) std::memcpy(&range[k], &p.vertices[r.firstVertex + k], sizeof(GpuVertex));
        glNamedBufferSubData(gm.vertices.id(), GLintptr(r.firstVertex * sizeof(GpuVertex)), GLsizeiptr(range.size() * sizeof(GpuVertex)),
                             range.data());
    }
    p.current = std::move(current);
    ++gm.poseVersion;
    // The shadow casters' bounds, the transparent sort's centres and the mesh's bounds, from the posed vertices.
    const MeshData& mesh = model.mesh;
    auto boundsOf = [&](uint32_t first, uint32_t count, glm::vec3& lo, glm::vec3& hi) {
        lo = glm::vec3(std::numeric_limits<float>::max());
        hi = glm::vec3(-std::numeric_limits<float>::max());
        for (uint32_t k = first; k < first + count && k < mesh.indices.size(); ++k) {
            const glm::vec3& v = p.vertices[mesh.indices[k]].position;
            if (!std::isfinite(v.x + v.y + v.z)) continue;
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
    };
    for (CasterCluster& c : casterClusters)
        if (c.model == int(i)) boundsOf(c.firstIndex, c.indexCount, c.boundsMin, c.boundsMax);
    for (GpuDraw& d : gm.draws) {
        glm::vec3 lo, hi;
        boundsOf(d.firstIndex, d.indexCount, lo, hi);
        if (d.indexCount > 0) d.centre = 0.5f * (lo + hi);
    }
    glm::vec3 lo, hi;
    boundsOf(0, uint32_t(mesh.indices.size()), lo, hi);
    if (lo.x <= hi.x) {
        gm.boundsMin = lo;
        gm.boundsMax = hi;
    }
}

void SceneGpu::poseOnGpu(size_t i, const ModelInstance& model, NodePose current, NodePose previousPose) {
    GpuMesh& gm = meshes[i];
    const NodeAnimation& animation = *model.animation;
    const MeshData& mesh = model.mesh;
    Pose& p = poses_[i];
    if (!gm.skinning) {
        // Uploaded once: what the skinning pass reads that no pose changes.
        auto s = std::make_unique<GpuSkinning>();
        s->layout = makeSkinningLayout(animation);
        SkinningLayout& l = s->layout;
        auto upload = [&](const auto& v, const char* what) {
            const size_t bytes = v.size() * sizeof(v[0]);
            geometryBytes += bytes;
            return gl::makeBuffer(GLsizeiptr(std::max<size_t>(bytes, 16)), bytes > 0 ? v.data() : nullptr, 0, model.name + ".skinning." + what);
        };
        s->rest = upload(l.rest, "rest");
        s->joints = upload(l.joints, "joints");
        s->deltas = upload(l.deltas, "deltas");
        s->ranges = upload(l.ranges, "ranges");
        s->workRange = upload(l.workRange, "work_range");
        // Only the ranges and counts stay on the CPU.
        l.rest = {};
        l.joints = {};
        l.deltas = {};
        const std::vector<int> ranges = vertexRanges(animation, mesh.vertices.size());
        auto boundsOf = [&](uint32_t first, uint32_t count) { return makePoseBounds(animation, mesh.vertices, ranges, mesh.indices, first, count); };
        for (size_t c = 0; c < casterClusters.size(); ++c)
            if (casterClusters[c].model == int(i)) s->casterBounds.emplace_back(c, boundsOf(casterClusters[c].firstIndex, casterClusters[c].indexCount));
        for (const GpuDraw& d : gm.draws) s->drawBounds.push_back(boundsOf(d.firstIndex, d.indexCount));
        s->meshBounds = boundsOf(0, uint32_t(mesh.indices.size()));
        gm.skinning = std::move(s);
    }
    GpuSkinning& s = *gm.skinning;
    const bool previousChanges = previousPose != p.previousPose;
    const bool currentChanges = current != p.current;
    if (!previousChanges && !currentChanges) return;
    // Playing on, the positions the vertex buffer holds are the previous frame's: the dispatch that
    // poses this frame keeps them (kSkinningKeepPrevious) instead of posing the previous frame again.
    const bool keep = previousChanges && previousPose == p.current;
    const std::vector<std::vector<glm::mat4>> joints = usedJointMatrices(animation, current);
    std::vector<glm::vec4> packed = packSkinningPose(animation, s.layout, current, joints);
    const uint32_t block = uint32_t(packed.size());
    if (previousChanges && !keep) {
        const std::vector<glm::vec4> earlier = packSkinningPose(animation, s.layout, previousPose, usedJointMatrices(animation, previousPose));
        packed.insert(packed.end(), earlier.begin(), earlier.end());
        skinningWork_.push_back({i, kSkinningPosePrevious, block});
    }
    const unsigned mode = (currentChanges ? kSkinningPoseVertices : 0u) | (keep ? kSkinningKeepPrevious : 0u);
    if (mode != 0) skinningWork_.push_back({i, mode, 0});
    s.pose.fill(packed.data(), packed.size() * sizeof(glm::vec4));
    if (previousChanges) p.previousPose = std::move(previousPose);
    if (!currentChanges) return;
    ++gm.poseVersion;
    // Bounds without the posed vertices: joint-transformed rest boxes (gpu_skinning.hpp).
    for (auto& [c, bounds] : s.casterBounds) poseBoundsBox(bounds, animation, current, joints, casterClusters[c].boundsMin, casterClusters[c].boundsMax);
    for (size_t d = 0; d < gm.draws.size() && d < s.drawBounds.size(); ++d) {
        glm::vec3 lo, hi;
        poseBoundsBox(s.drawBounds[d], animation, current, joints, lo, hi);
        if (gm.draws[d].indexCount > 0 && lo.x <= hi.x) gm.draws[d].centre = 0.5f * (lo + hi);
    }
    glm::vec3 lo, hi;
    poseBoundsBox(s.meshBounds, animation, current, joints, lo, hi);
    if (lo.x <= hi.x) {
        gm.boundsMin = lo;
        gm.boundsMax = hi;
    }
    p.current = std::move(current);
}

void SceneGpu::bounds(const Scene& /*scene: the meshes hold its placements*/, glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(std::numeric_limits<float>::lowest());
    for (size_t m = 0; m < meshes.size(); ++m) {
        const GpuMesh& gm = meshes[m];
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 p((c & 1) ? gm.boundsMax.x : gm.boundsMin.x, (c & 2) ? gm.boundsMax.y : gm.boundsMin.y,
                              (c & 4) ? gm.boundsMax.z : gm.boundsMin.z);
            const glm::vec3 w = glm::vec3(gm.model * glm::vec4(p, 1.0f));  // the instance's placement
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    }
    if (meshes.empty()) lo = hi = glm::vec3(0.0f);
}

}  // namespace lp
