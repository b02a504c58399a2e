#include "passes/local_light_pass.hpp"

#include <algorithm>
#include <memory>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "engine/render/exposure.hpp"
#include "engine/core/error.hpp"
#include "engine/gl/shader.hpp"
#include "engine/core/log.hpp"
#include "engine/gl/state.hpp"
#include "engine/gl/uniforms.hpp"
#include "engine/render/local_lights.hpp"

namespace lp {

namespace {
constexpr int kTileSize = 16;           // local_size of local_light_tiled.comp
// Below this many lights the clustered method (with 16-pixel froxel tiles, the tiled kernel's) shades
// with the tiled kernel: no tile then holds enough lights for its slices to save what they cost. On
// the H100 the clustered kernel took 1.03-1.22x the tiled kernel's time at 1 and 16 lights on every
// scene, and was faster from 256 lights on scenes whose tiles span depth
// (bench/results/lighting/2026-11-24_clustered-kernel-variants/README.md).
constexpr int kClusteredMinLights = 32;
constexpr float kGlobeScale = 0.04f;    // globe radius as a fraction of the light's range
constexpr float kGlobeRadiance = 8.0f;  // flat radiance of a globe (brightest channel)
constexpr float kOverlayRadiance = 3.0f;
constexpr float kHeatMax = 32.0f;       // lights per tile shown as red
constexpr float kClusterHeatMax = 64.0f;  // lights per cluster shown as red
constexpr GLuint kPointShadowBuffer = 5;  // LP_POINT_SHADOW_BUFFER in common/local_light.glsl
constexpr GLuint kPointShadowUnit = 22;   // LP_POINT_SHADOW_UNIT in common/local_light.glsl

int specularMode(const LocalLightSettings& s) {
    if (!s.specular) return 0;                 // LP_LOCAL_SPECULAR_OFF
    return s.specularOutsideRange ? 2 : 1;     // UNRANGED : RANGED
}
bool unbounded(const LocalLightSettings& s) { return s.specular && s.specularOutsideRange; }

void makeMesh(const std::vector<glm::vec3>& tris, const std::string& name, gl::Buffer& buffer, gl::VertexArray& vao,
              int& vertices) {
    buffer = gl::makeBuffer(GLsizeiptr(tris.size() * sizeof(glm::vec3)), tris.data(), 0, name);
    vao = gl::makeVertexArray(name);
    glVertexArrayVertexBuffer(vao.id(), 0, buffer.id(), 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);
    vertices = int(tris.size());
}

// The G-buffer-reading programs' defines: the G-buffer layout, spot and point shadows, and the
// material extensions' targets the G-buffer carries (the state's variant flags).
std::vector<std::string> lightingDefines(const GBufferSettings& layout, bool spotShadows, bool pointShadows,
                                         const LocalLightPass& state) {
    std::vector<std::string> d = gbufferDefines(layout);
    if (spotShadows) d.push_back("LP_SPOT_SHADOWS");
    if (pointShadows) d.push_back("LP_POINT_SHADOWS");
    if (state.fresnelVariant) d.push_back("LP_GBUFFER_FRESNEL");
    if (state.clearcoatVariant) d.push_back("LP_GBUFFER_CLEARCOAT");
    return d;
}

// The fused clustered programs' defines: those and the grid's tile size (their work-group shape).
std::vector<std::string> clusteredDefines(const GBufferSettings& layout, bool spotShadows, bool pointShadows,
                                          int clusterTile, const LocalLightPass& state) {
    std::vector<std::string> d = lightingDefines(layout, spotShadows, pointShadows, state);
    d.push_back("LP_CLUSTER_TILE " + std::to_string(clusterTile));
    return d;
}

void ensureState(LocalLightPass& state, const FrameData& frame, bool spotShadows = false, bool pointShadows = false) {
    // The programs that read the G-buffer follow its layout (recompiled when it changes), and
    // sample spot and point shadow maps only in frames that have one.
    const GBufferSettings& layout = frame.settings->gbuffer;
    // The fused clustered programs are compiled for the grid's tile size (their work-group shape).
    const int clusterTile = frame.settings->localLights.clusterSize;
    const bool fresnel = gbufferCarriesFresnel(frame), clearcoat = gbufferCarriesClearcoat(frame);
    if (!state.fbo || state.layout != layout || state.spotShadowVariant != spotShadows ||
        state.pointShadowVariant != pointShadows || state.clusterTileCompiled != clusterTile ||
        state.fresnelVariant != fresnel || state.clearcoatVariant != clearcoat) {
        state.fresnelVariant = fresnel;
        state.clearcoatVariant = clearcoat;
        std::vector<std::string> defines = lightingDefines(layout, spotShadows, pointShadows, state);
        state.spotShadowVariant = spotShadows;
        state.pointShadowVariant = pointShadows;
        state.fragmentProgram = frame.shaders->graphics("local_light.vert", "local_light.frag", defines);
        state.tiledProgram = frame.shaders->compute("local_light_tiled.comp", defines);
        const std::vector<std::string> clustered = clusteredDefines(layout, spotShadows, pointShadows, clusterTile, state);
        state.clusteredProgram = frame.shaders->compute("local_light_clustered.comp", clustered);
        state.clusteredSupertileProgram = {};  // compiled when first needed (many lights)
        state.clusterTightBuildProgram = frame.shaders->compute("light_clusters_tight.comp", clustered);
        state.clusterTileCompiled = clusterTile;
        defines.push_back("LP_TILE_HEATMAP");
        state.heatmapProgram = frame.shaders->compute("local_light_tiled.comp", defines);
        state.layout = layout;
    }
    if (state.fbo) return;
    state.sanitizeProgram = frame.shaders->compute("local_light_sanitize.comp");
    state.clusterBuildProgram = frame.shaders->compute("light_clusters.comp");
    state.clusterSupertileProgram = frame.shaders->compute("light_cluster_supertiles.comp");
    state.clusterViewProgram = frame.shaders->compute("light_clusters_view.comp");
    state.overlayProgram = frame.shaders->graphics("local_light_overlay.vert", "local_light_overlay.frag");
    makeMesh(circumscribingIcosphere(1), "local_light.volume", state.volumeMesh, state.volumeVao, state.volumeVertices);
    makeMesh(circumscribingIcosphere(2), "local_light.globe", state.globeMesh, state.globeVao, state.globeVertices);
    state.fbo = gl::makeFramebuffer("local_lights");
}

// The frame's lights as GPU records (eye space) into `gpu`. With shadow maps, each shadowed spot's
// record names its atlas tile, each shadowed point light's its cube.
void makeLightRecords(const FrameData& frame, const std::vector<PointLight>& lights, const LocalShadowMaps& shadows,
                      std::vector<GpuLocalLight>& gpu) {
    std::vector<int> layer(lights.size(), -1), cube(lights.size(), -1);
    for (size_t t = 0; t < shadows.spot.light.size(); ++t) layer[size_t(shadows.spot.light[t])] = int(t);
    for (size_t c = 0; c < shadows.point.light.size(); ++c) cube[size_t(shadows.point.light[c])] = int(c);
    gpu.clear();
    gpu.reserve(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) gpu.push_back(gpuLocalLight(lights[i], frame.view, layer[i], cube[i]));
}

constexpr const char* kLightRecordsName = "local_lights.records";

// A uniform of `prog` by name through gl::Uniforms (a name it does not declare: an error in checked builds).
template <typename T>
void setUniform(const FrameData& frame, GLuint prog, const char* name, const T& value) {
    gl::Uniforms(frame.shaders, prog).set(name, value);
}

// Also detaches the pooled textures from the FBO, so it keeps no reference to textures the pool frees.
void unbindAll(const LocalLightPass& state) {
    if (state.fbo) {
        glNamedFramebufferTexture(state.fbo.id(), GL_COLOR_ATTACHMENT0, 0, 0);
        glNamedFramebufferTexture(state.fbo.id(), GL_COLOR_ATTACHMENT1, 0, 0);
        glNamedFramebufferTexture(state.fbo.id(), GL_DEPTH_ATTACHMENT, 0, 0);
    }
    for (GLuint u = 0; u < 6; ++u) glBindTextureUnit(u, 0);
    glBindTextureUnit(kGBufferFresnelUnit, 0);
    glBindTextureUnit(kGBufferClearcoatUnit, 0);
    glBindTextureUnit(kPointShadowUnit, 0);
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    for (GLuint b = 0; b <= kPointShadowBuffer; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glBindVertexArray(0);
    glUseProgram(0);
}

struct LightData {
    GBuffer in;
    fg::ResourceId hdr;
    fg::ResourceId spotShadows;   // the atlas, when some spot casts a shadow
    fg::ResourceId pointShadows;  // the cubes' atlas, when some point light casts a shadow
};

constexpr GLuint kSpotShadowUnit = 5;  // layout(binding = 5) in common/local_light.glsl

// One LpPerspectiveShadow (common/local_light.glsl) per map: a spot's tile or a cube's face.
struct GpuPerspectiveShadow {
    glm::mat4 eyeToClip;
    glm::vec4 tile, depth, bias;
};
GpuPerspectiveShadow gpuPerspectiveShadow(const ShadowSettings& ss, const glm::mat4& worldToClip, const glm::mat4& eyeToWorld,
                                          glm::ivec2 tileOrigin, int tileSize, float texelSlope, float nearPlane, float farPlane) {
    GpuPerspectiveShadow g;
    g.eyeToClip = worldToClip * eyeToWorld;
    g.tile = glm::vec4(float(tileOrigin.x), float(tileOrigin.y), float(tileSize), texelSlope);
    g.depth = glm::vec4(nearPlane, farPlane, float(int(ss.filter)), ss.normalBias);
    g.bias = glm::vec4(ss.depthBias, 0.0f, 0.0f, 0.0f);
    return g;
}

// The spots' maps into the SSBO at binding 4, the atlas at unit 5.
void bindSpotShadows(LocalLightPass& state, const FrameData& frame, const SpotShadowMaps& maps, GLuint atlas) {
    const glm::mat4 eyeToWorld = glm::inverse(frame.view);
    std::vector<GpuPerspectiveShadow> gpu;
    for (size_t t = 0; t < maps.light.size(); ++t)
        gpu.push_back(gpuPerspectiveShadow(frame.settings->shadows, maps.worldToClip[t], eyeToWorld,
                                           glm::ivec2(int(t) % maps.columns, int(t) / maps.columns) * maps.tileSize,
                                           maps.tileSize, maps.texelSlope[t], maps.nearPlane[t], maps.farPlane[t]));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, state.spotShadows.fill(gpu.data(), gpu.size() * sizeof(GpuPerspectiveShadow)));
    glBindTextureUnit(kSpotShadowUnit, atlas);
}

// The point lights' cube faces (six a cube, in face order; cube c is the atlas's row c) into the
// SSBO at kPointShadowBuffer, the atlas at kPointShadowUnit.
void bindPointShadows(LocalLightPass& state, const FrameData& frame, const PointShadowMaps& maps, GLuint atlas) {
    const glm::mat4 eyeToWorld = glm::inverse(frame.view);
    std::vector<GpuPerspectiveShadow> gpu;
    for (size_t c = 0; c < maps.light.size(); ++c)
        for (int f = 0; f < kPointShadowFaces; ++f)
            gpu.push_back(gpuPerspectiveShadow(frame.settings->shadows, maps.worldToClip[c][size_t(f)], eyeToWorld,
                                               glm::ivec2(f, int(c)) * maps.tileSize, maps.tileSize, maps.texelSlope,
                                               maps.nearPlane[c], maps.farPlane[c]));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPointShadowBuffer,
                     state.pointShadows.fill(gpu.data(), gpu.size() * sizeof(GpuPerspectiveShadow)));
    glBindTextureUnit(kPointShadowUnit, atlas);
}

void bindLocalShadows(LocalLightPass& state, const FrameData& frame, const LocalShadowMaps& shadows, LocalShadowAtlases atlases) {
    if (shadows.spot.any()) bindSpotShadows(state, frame, shadows.spot, atlases.spot);
    if (shadows.point.any()) bindPointShadows(state, frame, shadows.point, atlases.point);
}

void setClusterUniforms(const FrameData& frame, GLuint prog, const ClusterGrid& g) {
    setUniform(frame, prog, "uClusterGrid", glm::ivec3(g.tilesX, g.tilesY, g.slices));
    setUniform(frame, prog, "uClusterTileSize", g.tileSize);
    setUniform(frame, prog, "uClusterNear", g.nearPlane);
    setUniform(frame, prog, "uClusterFar", g.farPlane);
}

// The frame's froxel grid (--cluster-size, --cluster-slices, the camera's depth range).
ClusterGrid frameClusterGrid(const FrameData& frame) {
    const LocalLightSettings& s = frame.settings->localLights;
    return makeClusterGrid(frame.width, frame.height, s.clusterSize, s.clusterSlices, frame.nearPlane, frame.farPlane);
}

// Grid g as the last one made (state.clusterGrid, read by the views and the next build's overflow
// warning), counted in the stats.
void recordClusterGrid(LocalLightPass& state, const ClusterGrid& g) {
    state.clusterGrid = g;
    state.stats.clusters = g.count();
}

// Readies the froxel grid for a build from the lights in the SSBO at binding 0 (bindLightRecords): reads
// the newest finished build's overflow count, sizes the buffers, binds the counts (1), lists (2) and
// a cleared overflow counter (3). The caller dispatches a build, then finishClusterBuild.
ClusterGrid beginClusterBuild(LocalLightPass& state, const FrameData& frame) {
    const ClusterGrid g = frameClusterGrid(frame);
    // The newest finished build's overflow count (never waits: see OverflowSlot).
    for (int back = 1; back <= int(state.clusterOverflow.size()); ++back) {
        auto& slot = state.clusterOverflow[size_t((state.nextOverflowSlot - back + 3 * int(state.clusterOverflow.size())) %
                                                  int(state.clusterOverflow.size()))];
        if (!slot.done || !slot.done.signaled()) continue;
        if (slot.read) break;
        const GLuint overflow = *slot.mapped;  // coherent, and the fence says the build is done
        slot.read = true;
        state.stats.clustersOverflowing = int(overflow);
        if (int(overflow) != state.lastOverflowWarned && overflow > 0)
            logWarn("clustered: " + std::to_string(overflow) + " of " + std::to_string(state.clusterGrid.count()) +
                    " clusters touch more than " + std::to_string(kMaxLightsPerCluster) +
                    " lights; their lists (forward shading, the lights-per-cluster view) keep the first " +
                    std::to_string(kMaxLightsPerCluster) + " (lower --cluster-size or raise --cluster-slices)");
        state.lastOverflowWarned = int(overflow);
        break;
    }
    const size_t clusters = size_t(g.count());
    if (clusters > state.clusterCapacity || !state.clusterCounts) {
        state.clusterCapacity = clusters;
        state.clusterCounts = gl::makeBuffer(GLsizeiptr(clusters * sizeof(GLuint)), nullptr, 0, "clusters.counts");
        state.clusterLists = gl::makeBuffer(GLsizeiptr(clusters * kMaxLightsPerCluster * sizeof(GLuint)), nullptr, 0,
                                            "clusters.lights");
    }
    auto& slot = state.clusterOverflow[size_t(state.nextOverflowSlot)];
    if (!slot.count) {
        // Persistently mapped (coherent): the count is read from memory once its fence has signaled,
        // never through glGetBufferSubData, which some drivers serialise with the whole queue. Only
        // read: the GPU copies each build's count in (finishClusterBuild).
        const GLbitfield access = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        slot.count = gl::makeBuffer(sizeof(GLuint), nullptr, access, "clusters.overflow");
        slot.mapped = static_cast<const GLuint*>(glMapNamedBufferRange(slot.count.id(), 0, sizeof(GLuint), access));
        if (!slot.mapped) throw Error("clustered: cannot map the overflow counter (glMapNamedBufferRange failed)");
    }
    // The count starts at zero in GPU memory, in order with the builds (finishClusterBuild copies it
    // into the slot).
    if (!state.clusterOverflowCounter)
        state.clusterOverflowCounter = gl::makeBuffer(sizeof(GLuint), nullptr, 0, "clusters.overflow_counter");
    const GLuint zero = 0;
    glClearNamedBufferData(state.clusterOverflowCounter.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    recordClusterGrid(state, g);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, state.clusterCounts.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, state.clusterLists.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, state.clusterOverflowCounter.id());
    return g;
}

// After the build's dispatch: its lists visible to the next dispatches and draws, its overflow slot
// fenced.
void finishClusterBuild(LocalLightPass& state) {
    auto& slot = state.clusterOverflow[size_t(state.nextOverflowSlot)];
    state.nextOverflowSlot = (state.nextOverflowSlot + 1) % int(state.clusterOverflow.size());
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(state.clusterOverflowCounter.id(), slot.count.id(), 0, 0, sizeof(GLuint));
    slot.done = gl::Fence::insert();
    slot.read = false;
}

// What every program that culls lights per tile of grid g reads (the supertile lists' build, the
// whole and tight froxel builds, the clustered method's fused pass).
void setTileCullUniforms(GLuint prog, const ClusterGrid& g, const FrameData& frame, int lightCount) {
    setClusterUniforms(frame, prog, g);
    setUniform(frame, prog, "uLightCount", lightCount);
    setUniform(frame, prog, "uProjection", frame.projection);
    setUniform(frame, prog, "uImageSize", glm::ivec2(frame.width, frame.height));
}

// One work group per tile of the froxel grid, for the programs that cull per tile.
void dispatchPerClusterTile(GLuint prog, const ClusterGrid& g, const FrameData& frame, int lightCount) {
    setTileCullUniforms(prog, g, frame, lightCount);
    glUseProgram(prog);
    glDispatchCompute(GLuint(g.tilesX), GLuint(g.tilesY), 1);
}

// Supertiles of 8 x 8 froxel tiles (128 px at the default 16): at 16384 lights a 4K frame's 510
// supertiles keep a few hundred lights each, so each tile tests those instead of all 16384. A list
// holds at most 4096 lights (8 MB at 4K); a supertile with more is tested light by light. Up to 256
// lights (one batch of the tile kernel either way) the first level only adds a dispatch: skipped.
constexpr int kSupertileTiles = 8;
constexpr int kSupertileCapacity = 4096;
constexpr int kSupertileMinLights = 257;
// light_cluster_supertiles.comp tests lights in chunks of 256, up to 8 chunks a work group (more
// groups a supertile cost more than they save below ~2000 lights: measured on the H100).
constexpr int kSupertileChunk = 256;
constexpr int kSupertileChunksPerGroup = 8;

// Whether a pass over lightCount lights takes its candidates from supertile lists.
bool useSupertiles(const LocalLightPass& state, int lightCount, bool allowed) {
    return allowed && state.supertileTiles >= 0 && (lightCount >= kSupertileMinLights || state.supertileTiles > 0);
}

// Makes `buffer` hold at least `uints` uints: made anew when it holds fewer (or none), its contents
// then undefined, or zero when `zeroed`; never shrunk.
void reserveUints(gl::Buffer& buffer, size_t& capacity, size_t uints, const char* name, bool zeroed = false) {
    if (buffer && uints <= capacity) return;
    capacity = uints;
    const std::vector<GLuint> zeros(zeroed ? uints : 0, 0u);
    buffer = gl::makeBuffer(GLsizeiptr(uints * sizeof(GLuint)), zeroed ? zeros.data() : nullptr, 0, name);
}

// The first level of a build or of the tiled and clustered shading passes
// (light_cluster_supertiles.comp): each supertile's lights at bindings 6 and 7, for grid g's tiles,
// with uSupertile / uSupertileCapacity set on `readers` (the programs that read the lists; uSupertile
// 0 where the level is skipped: few lights, or not `allowed`, as with unbounded specular, where every
// light reaches every pixel). The caller unbinds 6 and 7 after its dispatch.
void buildSupertiles(LocalLightPass& state, const FrameData& frame, const ClusterGrid& g, int lightCount,
                     std::initializer_list<GLuint> readers, bool allowed = true) {
    const bool supertiles = useSupertiles(state, lightCount, allowed);
    const int side = state.supertileTiles > 0 ? state.supertileTiles : kSupertileTiles;
    const int capacity = std::max(1, std::min(lightCount, state.supertileCapacity > 0 ? state.supertileCapacity : kSupertileCapacity));
    for (const GLuint prog : readers) {
        setUniform(frame, prog, "uSupertile", supertiles ? side : 0);
        setUniform(frame, prog, "uSupertileCapacity", capacity);
    }
    if (!supertiles) return;
    const int stX = (g.tilesX + side - 1) / side, stY = (g.tilesY + side - 1) / side;
    const size_t counts = size_t(stX) * size_t(stY);
    const int bitWords = (lightCount + 31) / 32, chunks = (lightCount + kSupertileChunk - 1) / kSupertileChunk;
    const int groups = (chunks + kSupertileChunksPerGroup - 1) / kSupertileChunksPerGroup;  // per supertile
    reserveUints(state.supertileCounts, state.supertileCountsCapacity, counts, "clusters.supertile_counts");
    reserveUints(state.supertileLists, state.supertileListsCapacity, counts * size_t(capacity), "clusters.supertile_lights");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, state.supertileCounts.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, state.supertileLists.id());
    if (groups > 1) {  // the bits, and the counters of finished groups (zero when made; each build leaves them zero)
        reserveUints(state.supertileBits, state.supertileBitsCapacity, counts * size_t(bitWords), "clusters.supertile_bits");
        reserveUints(state.supertileDone, state.supertileDoneCapacity, counts, "clusters.supertile_done", true);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, state.supertileBits.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, state.supertileDone.id());
    }
    const GLuint prog = state.clusterSupertileProgram.id();
    setTileCullUniforms(prog, g, frame, lightCount);
    setUniform(frame, prog, "uSupertile", side);
    setUniform(frame, prog, "uSupertileCapacity", capacity);
    setUniform(frame, prog, "uBitWords", bitWords);
    glUseProgram(prog);
    glDispatchCompute(GLuint(stX), GLuint(stY), GLuint(groups));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, 0);
}

void unbindSupertiles() {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, 0);
}

// Builds the whole grid's light lists (light_clusters.comp: every froxel whole, for the forward
// passes and transparent surfaces; a work group per tile, an invocation per slice); leaves the counts
// at binding 1 and the lists at binding 2.
void buildClusters(LocalLightPass& state, const FrameData& frame, int lightCount) {
    ++state.clusterBuilds;
    const ClusterGrid g = beginClusterBuild(state, frame);
    const GLuint prog = state.clusterBuildProgram.id();
    buildSupertiles(state, frame, g, lightCount, {prog});
    dispatchPerClusterTile(prog, g, frame, lightCount);
    unbindSupertiles();
    finishClusterBuild(state);
}

// The froxel lists tightened to the G-buffer's depth (light_clusters_tight.comp, a work group per
// tile), for the lights-per-cluster view. The G-buffer is bound by the caller.
void buildTightClusters(LocalLightPass& state, const FrameData& frame, GLuint prog, int lightCount) {
    ++state.clusterBuilds;
    state.wholeListsFor = nullptr;  // the lists are now the tight ones
    const ClusterGrid g = beginClusterBuild(state, frame);
    dispatchPerClusterTile(prog, g, frame, lightCount);
    finishClusterBuild(state);
}

// The clustered method's fused pass (local_light_clustered.comp): a work group per tile culls the
// lights to its froxels tightened to the G-buffer's depth in shared memory and shades its pixels. It
// writes no lists, so the grid's buffers and overflow bookkeeping stay out of the pass; a shading
// program that does write the grid (an older fused kernel, timed through $LIGHTPASS_SHADER_DIR by
// bench/lighting_clustered.sh) gets them as a build. The G-buffer is bound by the caller.
void shadeClustered(LocalLightPass& state, const FrameData& frame, GLuint prog, int lightCount) {
    const bool writesGrid = glGetProgramResourceIndex(prog, GL_SHADER_STORAGE_BLOCK, "ClusterCounts") != GL_INVALID_INDEX;
    if (writesGrid) {
        buildTightClusters(state, frame, prog, lightCount);
        return;
    }
    const ClusterGrid g = frameClusterGrid(frame);
    recordClusterGrid(state, g);
    buildSupertiles(state, frame, g, lightCount, {prog}, !unbounded(frame.settings->localLights));
    dispatchPerClusterTile(prog, g, frame, lightCount);
    unbindSupertiles();
}

// The fullscreen, scissor and volumes methods: additive blending into an FBO holding the HDR texture.
void drawFragmentMethod(LocalLightPass& state, const FrameData& frame, const std::vector<PointLight>& lights,
                        GLuint hdrTexture) {
    const LocalLightSettings& s = frame.settings->localLights;
    const int count = int(lights.size());
    const bool noBounds = unbounded(s);
    const LocalLightMethod method = s.method;
    const bool useScissor = method == LocalLightMethod::Scissor && s.scissor && !noBounds;
    const GLuint prog = state.fragmentProgram.id();
    const GLuint fbo = state.fbo.id();
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, hdrTexture, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    setUniform(frame, prog, "uProjection", frame.projection);

    gl::ScopedRasterState saved;
    gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
    gl::ScopedEnable blend(GL_BLEND, true);
    // Volumes: back faces only, no depth test. A back face of the circumscribing icosphere covers
    // every pixel whose surface lies in the light's sphere, whether the camera is outside it, inside
    // it, or the sphere crosses the near plane; depth clamping keeps back faces past the far plane
    // or before the near plane from being clipped. Pixels the volume covers but the light does not
    // reach add exactly 0 (the window is 0 at and past the range).
    gl::ScopedEnable depthTest(GL_DEPTH_TEST, false);
    gl::ScopedEnable depthClamp(GL_DEPTH_CLAMP, true);
    gl::ScopedEnable cull(GL_CULL_FACE, method == LocalLightMethod::Volumes && !noBounds);
    gl::ScopedEnable scissor(GL_SCISSOR_TEST, useScissor);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    glCullFace(GL_FRONT);
    glDepthMask(GL_FALSE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glUseProgram(prog);
    glBindVertexArray(state.volumeVao.id());

    LocalLightStats& st = state.stats;
    if (method == LocalLightMethod::Volumes) {
        setUniform(frame, prog, "uFirstLight", 0);
        setUniform(frame, prog, "uMode", noBounds ? 0 : 1);
        glDrawArraysInstanced(GL_TRIANGLES, 0, noBounds ? 3 : state.volumeVertices, count);
        st.drawn = count;
    } else {
        setUniform(frame, prog, "uMode", 0);
        const GLint locFirst = gl::Uniforms(frame.shaders, prog).location("uFirstLight");
        for (int i = 0; i < count; ++i) {
            if (useScissor) {
                const BoundingSphere b = localLightBounds(lights[size_t(i)]);
                const glm::vec3 eye = glm::vec3(frame.view * glm::vec4(b.center, 1.0f));
                ScissorRect r = sphereScissorRect(eye, b.radius, frame.projection, frame.nearPlane, frame.width,
                                                  frame.height);
                if (r.empty()) {
                    ++st.offscreen;
                    continue;
                }
                if (r.fullScreen) ++st.fullScreen;
                glScissor(r.x, r.y, r.width, r.height);
            }
            glProgramUniform1i(prog, locFirst, i);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            ++st.drawn;
        }
    }
}
}  // namespace

LocalLightRecords importLocalLightRecords(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                          const LocalShadowMaps& shadows) {
    LocalLightRecords r;
    // CPU work inside a pass's execute would sit inside its GPU timing window (the GPU idles there
    // whenever it has caught up with the CPU: bench/results/lighting/2026-11-24_cpu-in-pass-timing), so made here.
    auto records = std::make_shared<std::vector<GpuLocalLight>>();
    makeLightRecords(frame, *frameLocalLights(frame), shadows, *records);
    r.records = std::move(records);
    r.buffer = graph.importBuffer(kLightRecordsName, [&state] { return state.lights.current(); });
    return r;
}

namespace {
// A new buffer when the GPU may still read the last one (gl::StreamBuffer): the previous frame's
// lighting must not see this frame's lights. Once a frame: later callers find them filled.
void fillLightRecords(LocalLightPass& state, const LocalLightRecords& records) {
    if (state.filledRecords == records.records) return;
    state.lights.fill(records.records->data(), records.records->size() * sizeof(GpuLocalLight));
    state.filledRecords = records.records;
    ++state.recordFills;
}
}  // namespace

void writeLightRecords(fg::PassBuilder& b, LocalLightPass& state, const LocalLightRecords& records) {
    b.write(records.buffer, fg::Usage::Transfer);
    // Uploaded before the frame's first pass: inside the pass the upload (1.3 MB at 16384 lights)
    // would sit in its GPU timing window.
    b.beforeFrame([&state, records] { fillLightRecords(state, records); });
}

void readLightRecords(fg::PassBuilder& b) { b.read(kLightRecordsName, fg::Usage::StorageBuffer); }

void bindLightRecords(LocalLightPass& state, const LocalLightRecords& records, const fg::PassResources& res) {
    // Filled before the frame by the writer; here only when the writer is disabled (--disable-pass).
    fillLightRecords(state, records);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, res.buffer(records.buffer));
}

// The whole-froxel lists of this frame's records at bindings 1 and 2: built by the first reader of
// the frame, bound as they are for the others (the lists depend only on the lights and the grid,
// both fixed within a frame).
void bindWholeClusters(LocalLightPass& state, const FrameData& frame, const LocalLightRecords& records) {
    if (state.wholeListsFor != records.records || !state.clusterCounts) {
        buildClusters(state, frame, int(records.records->size()));
        state.wholeListsFor = records.records;
        return;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, state.clusterCounts.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, state.clusterLists.id());
}

int bindClusteredLightLists(LocalLightPass& state, GLuint prog, const FrameData& frame, const LocalLightRecords& records,
                            const fg::PassResources& res, const LocalShadowMaps& shadows, LocalShadowAtlases atlases) {
    ensureState(state, frame, shadows.spot.any(), shadows.point.any());
    const LocalLightSettings& s = frame.settings->localLights;
    bindLightRecords(state, records, res);
    const int count = int(records.records->size());
    bindLocalShadows(state, frame, shadows, atlases);
    bindWholeClusters(state, frame, records);
    setClusterUniforms(frame, prog, state.clusterGrid);
    setUniform(frame, prog, "uLocalLightCount", count);
    setUniform(frame, prog, "uUnbounded", unbounded(s));
    setUniform(frame, prog, "uSpecularMode", specularMode(s));
    setBrdfUniforms(prog, frame);
    return count;
}

void unbindClusteredLightLists() {
    for (GLuint b = 0; b <= kPointShadowBuffer; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, 0);
    glBindTextureUnit(kSpotShadowUnit, 0);
    glBindTextureUnit(kPointShadowUnit, 0);
}

namespace {
// What the clustered race's time depends on besides the view: a change begins a new round.
std::uint64_t clusteredRaceKey(const FrameData& frame, bool lightingOnly, int shadowVariant, int lightCount) {
    const LocalLightSettings& s = frame.settings->localLights;
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the values
    for (const std::int64_t v : {std::int64_t(lightCount), std::int64_t(frame.width), std::int64_t(frame.height),
                                 std::int64_t(s.clusterSlices), std::int64_t(specularMode(s)), std::int64_t(lightingOnly),
                                 std::int64_t(frame.settings->brdf), std::int64_t(frame.settings->specularMasking),
                                 std::int64_t(shadowVariant), std::int64_t(frame.settings->gbuffer.mode)}) {
        h ^= std::uint64_t(v);
        h *= 1099511628211ull;
    }
    return h;
}

// Reads the race's timestamps the GPU has passed; the others stay pending.
void collectRaceTimings(LocalLightPass& state) {
    for (LocalLightPass::RaceTiming& t : state.raceTimings) {
        if (!t.pending) continue;
        GLint available = 0;
        glGetQueryObjectiv(t.end.id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) continue;
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(t.begin.id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(t.end.id(), GL_QUERY_RESULT, &t1);
        t.pending = false;
        const bool wasRacing = state.clusteredRace.racing;
        kernelRaceRecord(state.clusteredRace, t.key, t.kernel, t1 >= t0 ? double(t1 - t0) * 1e-6 : 0.0);
        if (wasRacing && !state.clusteredRace.racing) {
            const std::array<double, 2>& m = state.clusteredRace.lastMedians;
            logDebug("clustered: froxels kernel " + std::to_string(m[0]) + " ms, tiles kernel " + std::to_string(m[1]) +
                     " ms at this view: " + (state.clusteredRace.choice == 0 ? "froxels" : "tiles") + " shade");
        }
    }
}

struct ClusteredChoice {
    bool tiles = false;  // the tiled kernel shades (else the clustered kernel)
    LocalLightPass::RaceTiming* timing = nullptr;  // where to time it (a race round), else null
};

// Which kernel shades the clustered method this frame. Other tile sizes than the tiled kernel's: the
// clustered kernel. 16-pixel tiles: --clustered-kernel froxels or tiles as asked; auto: the tiled
// kernel below kClusteredMinLights, else the race's pick for the view (kernel 1 is the tiled one).
ClusteredChoice chooseClusteredKernel(LocalLightPass& state, const FrameData& frame, bool lightingOnly,
                                      int shadowVariant, int lightCount) {
    const LocalLightSettings& s = frame.settings->localLights;
    ClusteredChoice c;
    if (s.clusterSize != kTileSize || s.clusteredKernel == ClusteredKernel::Froxels) return c;
    if (s.clusteredKernel == ClusteredKernel::Tiles || lightCount < kClusteredMinLights) {
        c.tiles = true;
        return c;
    }
    collectRaceTimings(state);
    const std::uint64_t key = clusteredRaceKey(frame, lightingOnly, shadowVariant, lightCount);
    bool timed = false;
    const int kernel = kernelRaceNext(state.clusteredRace, key, timed);
    c.tiles = kernel == 1;
    state.stats.kernelRacing = timed;
    state.stats.froxelKernelMs = state.clusteredRace.lastMedians[0];
    state.stats.tileKernelMs = state.clusteredRace.lastMedians[1];
    if (!timed) return c;
    for (LocalLightPass::RaceTiming& t : state.raceTimings) {
        if (t.pending) continue;
        if (!t.begin) {
            t.begin = gl::makeQuery(GL_TIMESTAMP);
            t.end = gl::makeQuery(GL_TIMESTAMP);
        }
        t.kernel = kernel;
        t.key = key;
        c.timing = &t;
        break;
    }
    return c;  // every slot still in flight: this frame goes untimed
}
}  // namespace

fg::ResourceId addLocalLightPass(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                 const GBuffer& gbuffer, fg::ResourceId hdr, bool lightingOnly,
                                 const LocalShadowMaps& shadows, const LocalLightRecords& records) {
    // Tiled and clustered: compute adding into the HDR buffer in place. The other methods blend light
    // geometry into it, then clamp it in place (image load/store).
    const bool tiled = frame.settings->localLights.method == LocalLightMethod::Tiled ||
                       frame.settings->localLights.method == LocalLightMethod::Clustered;
    const LightData& d = graph.addPass<LightData>(
        "local_lights", tiled ? fg::PassKind::Compute : fg::PassKind::Raster,
        [&](fg::PassBuilder& b, LightData& data) {
            data.in = gbuffer;
            readGBuffer(b, gbuffer, !lightingOnly, true);
            data.hdr = b.write(hdr, tiled ? fg::Usage::ImageLoadStore : fg::Usage::Blend | fg::Usage::ImageLoadStore);
            if (shadows.spot.any()) data.spotShadows = b.read(shadows.spot.depth, fg::Usage::Sampled);
            if (shadows.point.any()) data.pointShadows = b.read(shadows.point.depth, fg::Usage::Sampled);
            writeLightRecords(b, state, records);
        },
        [&state, frame, lightingOnly, shadows, records](const LightData& data, const fg::PassResources& res) {
            ensureState(state, frame, shadows.spot.any(), shadows.point.any());
            const LocalLightSettings& s = frame.settings->localLights;
            state.stats = LocalLightStats{};
            state.stats.method = s.method;
            const std::shared_ptr<const std::vector<PointLight>> lights = frameLocalLights(frame);
            bindLightRecords(state, records, res);
            bindLocalShadows(state, frame, shadows,
                             {shadows.spot.any() ? res.texture(data.spotShadows) : 0,
                              shadows.point.any() ? res.texture(data.pointShadows) : 0});
            state.stats.requested = int(lights->size());
            const GLuint hdrTexture = res.texture(data.hdr);
            const bool clustered = s.method == LocalLightMethod::Clustered;
            const ClusteredChoice choice =
                clustered ? chooseClusteredKernel(state, frame, lightingOnly,
                                                  int(shadows.spot.any()) + 2 * int(shadows.point.any()), int(lights->size()))
                          : ClusteredChoice{};
            const bool clusteredAsTiled = clustered && choice.tiles;
            state.stats.slicesShaded = clustered && !choice.tiles;
            if (clusteredAsTiled) recordClusterGrid(state, frameClusterGrid(frame));  // what its tiles stand for
            LocalLightPass::RaceTiming* timing = choice.timing;
            if (timing) glQueryCounter(timing->begin.id(), GL_TIMESTAMP);
            if (s.method == LocalLightMethod::Tiled || clusteredAsTiled) {
                const GLuint prog = state.tiledProgram.id();
                bindGBuffer(prog, res, data.in, frame, !lightingOnly, true);
                setUniform(frame, prog, "uLightCount", int(lights->size()));
                setUniform(frame, prog, "uProjection", frame.projection);
                setUniform(frame, prog, "uUnbounded", unbounded(s));
                setUniform(frame, prog, "uLightingOnly", lightingOnly);
                setUniform(frame, prog, "uSpecularMode", specularMode(s));
                setBrdfUniforms(prog, frame);
                buildSupertiles(state, frame,
                                makeClusterGrid(frame.width, frame.height, kTileSize, 1, frame.nearPlane, frame.farPlane),
                                int(lights->size()), {prog}, !unbounded(s));
                glBindImageTexture(0, hdrTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
                glUseProgram(prog);
                gl::dispatch2D(frame.width, frame.height, kTileSize);
                unbindSupertiles();
                state.stats.drawn = int(lights->size());
            } else if (s.method == LocalLightMethod::Clustered) {
                // With many lights the variant that reads the supertile lists (LP_SUPERTILES).
                const bool supertiles = useSupertiles(state, int(lights->size()), !unbounded(s));
                if (supertiles && !state.clusteredSupertileProgram) {
                    std::vector<std::string> d = clusteredDefines(state.layout, state.spotShadowVariant, state.pointShadowVariant,
                                                                  state.clusterTileCompiled, state);
                    d.push_back("LP_SUPERTILES");
                    state.clusteredSupertileProgram = frame.shaders->compute("local_light_clustered.comp", d);
                }
                const GLuint prog = supertiles ? state.clusteredSupertileProgram.id() : state.clusteredProgram.id();
                bindGBuffer(prog, res, data.in, frame, !lightingOnly, true);
                setUniform(frame, prog, "uUnbounded", unbounded(s));
                setUniform(frame, prog, "uLightingOnly", lightingOnly);
                setUniform(frame, prog, "uSpecularMode", specularMode(s));
                setBrdfUniforms(prog, frame);
                glBindImageTexture(0, hdrTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
                shadeClustered(state, frame, prog, int(lights->size()));
                state.stats.drawn = int(lights->size());
            }
            if (timing) {
                glQueryCounter(timing->end.id(), GL_TIMESTAMP);
                timing->pending = true;
            }
            if (s.method != LocalLightMethod::Tiled && s.method != LocalLightMethod::Clustered) {
                const GLuint prog = state.fragmentProgram.id();
                bindGBuffer(prog, res, data.in, frame, !lightingOnly, true);
                setUniform(frame, prog, "uLightingOnly", lightingOnly);
                setUniform(frame, prog, "uSpecularMode", specularMode(s));
                setBrdfUniforms(prog, frame);
                drawFragmentMethod(state, frame, *lights, hdrTexture);
                // Blending can overflow fp16 to +Inf: clamp like every other HDR write.
                glBindImageTexture(0, hdrTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
                glUseProgram(state.sanitizeProgram.id());
                gl::dispatch2D(frame.width, frame.height);
            }
            unbindAll(state);
        });
    return d.hdr;
}

namespace {
struct OverlayData {
    GBuffer in;
    fg::ResourceId hdr;
    fg::ResourceId velocity;  // the globes' motion over gbuffer.velocity; invalid without the target
};

// Each light's world-space centre at the frame's time and at the previous frame's time (the orbit
// function of time gives both; without a previous frame previousTime = time) into binding 1.
void uploadGlobeMotion(LocalLightPass& state, const FrameData& frame) {
    const LocalLightSettings& s = frame.settings->localLights;
    const std::shared_ptr<const std::vector<PointLight>> frameLights = frameLocalLights(frame);
    const std::vector<PointLight>& now = *frameLights;
    const std::vector<PointLight> before = localLightsForFrame(*frame.scene, s, frame.previousTime);
    std::vector<glm::vec4> motion;
    motion.reserve(2 * now.size());
    for (size_t i = 0; i < now.size(); ++i) {
        motion.emplace_back(now[i].position, 1.0f);
        motion.emplace_back(i < before.size() ? before[i].position : now[i].position, 1.0f);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, state.globeMotion.fill(motion.data(), motion.size() * sizeof(glm::vec4)));
}

// The globes into the HDR buffer and, when velocityTexture is not 0, their motion vectors into it,
// under the same depth test.
void drawGlobes(LocalLightPass& state, const FrameData& frame, int count, GLuint hdrTexture, GLuint depthTexture,
                GLuint velocityTexture) {
    const bool velocity = velocityTexture != 0;
    if (velocity && !state.globeVelocityProgram)
        state.globeVelocityProgram =
            frame.shaders->graphics("local_light_overlay.vert", "local_light_overlay.frag",
                                    std::vector<std::string>{"LP_GLOBE_VELOCITY"});
    const GLuint prog = velocity ? state.globeVelocityProgram.id() : state.overlayProgram.id();
    const GLuint fbo = state.fbo.id();
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, hdrTexture, 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, velocityTexture, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depthTexture, 0);  // read only: depth mask off
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, velocity ? 2 : 1, buffers);
    if (velocity) {
        uploadGlobeMotion(state, frame);
        // Unjittered, like the G-buffer's: the same product, so a still light under a still camera gives 0.
        setUniform(frame, prog, "uViewProjection", frame.unjitteredProjection * frame.view);
        setUniform(frame, prog, "uPreviousViewProjection", frame.previousViewProjection);
        const glm::mat3 worldFromEye = glm::transpose(glm::mat3(frame.view));
        glProgramUniformMatrix3fv(prog, gl::Uniforms(frame.shaders, prog).location("uWorldFromEyeRotation"), 1, GL_FALSE,
                                  glm::value_ptr(worldFromEye));
    }
    gl::ScopedRasterState saved;
    gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
    gl::ScopedEnable blend(GL_BLEND, false);
    gl::ScopedEnable depthTest(GL_DEPTH_TEST, true);  // hidden behind the scene's surfaces
    gl::ScopedEnable cull(GL_CULL_FACE, true);
    gl::ScopedEnable scissor(GL_SCISSOR_TEST, false);
    // The G-buffer's depth convention: GL_LESS, or under reversed-Z clip control 0..1 and GL_GREATER
    // with the reversed projection below, so globes stay hidden by nearer surfaces in every mode.
    setGBufferDepthTest(frame.settings->gbuffer);
    glDepthMask(GL_FALSE);
    glCullFace(GL_BACK);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glUseProgram(prog);
    setUniform(frame, prog, "uMode", 1);
    setUniform(frame, prog, "uGlobeScale", kGlobeScale);
    setUniform(frame, prog, "uRadiance", kGlobeRadiance);
    setUniform(frame, prog, "uProjection", gbufferDepthProjection(frame));
    glBindVertexArray(state.globeVao.id());
    glDrawArraysInstanced(GL_TRIANGLES, 0, state.globeVertices, count);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
}

// The light-ranges view: the volumes method's icospheres as wireframes, every other method's
// scissor rectangles as outlines (the tight screen bounds of each light's sphere).
void drawRanges(LocalLightPass& state, const FrameData& frame, const std::vector<PointLight>& lights, GLuint hdrTexture) {
    const GLuint prog = state.overlayProgram.id();
    const GLuint fbo = state.fbo.id();
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, hdrTexture, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, 0, 0);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    gl::ScopedRasterState saved;
    gl::ScopedFramebuffer bind(fbo, frame.width, frame.height);
    gl::ScopedEnable blend(GL_BLEND, false);
    gl::ScopedEnable depthTest(GL_DEPTH_TEST, false);
    gl::ScopedEnable depthClamp(GL_DEPTH_CLAMP, true);
    gl::ScopedEnable cull(GL_CULL_FACE, false);
    gl::ScopedEnable scissor(GL_SCISSOR_TEST, false);
    glUseProgram(prog);
    setUniform(frame, prog, "uRadiance", kOverlayRadiance);
    setUniform(frame, prog, "uProjection", frame.projection);
    glBindVertexArray(state.volumeVao.id());
    if (frame.settings->localLights.method == LocalLightMethod::Volumes) {
        setUniform(frame, prog, "uMode", 0);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glDrawArraysInstanced(GL_TRIANGLES, 0, state.volumeVertices, int(lights.size()));
        return;
    }
    setUniform(frame, prog, "uMode", 2);
    const gl::Uniforms overlay(frame.shaders, prog);
    const GLint locRect = overlay.location("uRectNdc");
    const GLint locLight = overlay.location("uLightIndex");
    const float w = float(frame.width), h = float(frame.height);
    for (size_t i = 0; i < lights.size(); ++i) {
        const BoundingSphere b = localLightBounds(lights[i]);
        const glm::vec3 eye = glm::vec3(frame.view * glm::vec4(b.center, 1.0f));
        ScissorRect r = sphereScissorRect(eye, b.radius, frame.projection, frame.nearPlane, frame.width, frame.height);
        if (r.empty()) continue;
        // Through the centres of the rectangle's outermost pixels, so every edge is visible.
        glProgramUniform4f(prog, locRect, (float(r.x) + 0.5f) / w * 2.0f - 1.0f, (float(r.y) + 0.5f) / h * 2.0f - 1.0f,
                           (float(r.x + r.width) - 0.5f) / w * 2.0f - 1.0f,
                           (float(r.y + r.height) - 0.5f) / h * 2.0f - 1.0f);
        glProgramUniform1i(prog, locLight, int(i));
        glDrawArrays(GL_LINE_LOOP, 0, 4);
    }
}
}  // namespace

fg::ResourceId addLocalLightOverlayPasses(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                          GBuffer& gbuffer, fg::ResourceId hdr, const LocalLightRecords& records) {
    const RenderSettings& s = *frame.settings;
    if (s.localLights.globes.value_or(frame.scene->lightGlobes)) {
        const OverlayData& globes = graph.addPass<OverlayData>(
            "light_globes", fg::PassKind::Raster,
            [&](fg::PassBuilder& b, OverlayData& data) {
                data.in = gbuffer;
                b.read(gbuffer.depth, fg::Usage::DepthTest);
                data.hdr = b.write(hdr, fg::Usage::ColorAttachment);
                // Only when a later pass reads motion (the G-buffer made the target for it).
                if (gbuffer.velocity.valid()) data.velocity = b.write(gbuffer.velocity, fg::Usage::ColorAttachment);
                readLightRecords(b);
            },
            [&state, frame, records](const OverlayData& data, const fg::PassResources& res) {
                ensureState(state, frame, state.spotShadowVariant, state.pointShadowVariant);
                bindLightRecords(state, records, res);
                const GLuint velocity = data.velocity.valid() ? res.texture(data.velocity) : 0;
                drawGlobes(state, frame, int(records.records->size()), res.texture(data.hdr), res.texture(data.in.depth),
                           velocity);
                unbindAll(state);
            });
        hdr = globes.hdr;
        if (globes.velocity.valid()) gbuffer.velocity = globes.velocity;
    }
    if (s.view == DebugView::LightRanges) {
        hdr = graph.addPass<OverlayData>(
                       "light_ranges", fg::PassKind::Raster,
                       [&](fg::PassBuilder& b, OverlayData& data) {
                           data.hdr = b.write(hdr, fg::Usage::ColorAttachment);
                           readLightRecords(b);
                       },
                       [&state, frame, records](const OverlayData& data, const fg::PassResources& res) {
                           ensureState(state, frame, state.spotShadowVariant, state.pointShadowVariant);
                           bindLightRecords(state, records, res);
                           drawRanges(state, frame, *frameLocalLights(frame), res.texture(data.hdr));
                           unbindAll(state);
                       })
                  .hdr;
    }
    if (s.view == DebugView::LightsPerTile) {
        hdr = graph.addPass<OverlayData>(
                       "lights_per_tile", fg::PassKind::Compute,
                       [&](fg::PassBuilder& b, OverlayData& data) {
                           data.in = gbuffer;
                           readGBuffer(b, gbuffer, true);  // the diffuse target's alpha marks flat-lit pixels
                           data.hdr = b.write(hdr, fg::Usage::ImageLoadStore);
                           readLightRecords(b);
                       },
                       [&state, frame, records](const OverlayData& data, const fg::PassResources& res) {
                           ensureState(state, frame, state.spotShadowVariant, state.pointShadowVariant);
                           bindLightRecords(state, records, res);
                           const LocalLightSettings& ls = frame.settings->localLights;
                           const GLuint prog = state.heatmapProgram.id();
                           setUniform(frame, prog, "uLightingOnly", 0);
                           setUniform(frame, prog, "uLightCount", int(records.records->size()));
                           setUniform(frame, prog, "uProjection", frame.projection);
                           setUniform(frame, prog, "uUnbounded", unbounded(ls));
                           setUniform(frame, prog, "uHeatMax", kHeatMax);
                           setUniform(frame, prog, "uExposure", exposureEvBase(*frame.settings, *frame.scene));
                           bindGBuffer(prog, res, data.in, frame, true);
                           glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
                           glUseProgram(prog);
                           gl::dispatch2D(frame.width, frame.height, kTileSize);
                           unbindAll(state);
                       })
                  .hdr;
    }
    if (s.view == DebugView::LightsPerCluster) {
        const bool tightClusters =
            s.renderPath == RenderPath::Deferred && s.localLights.method == LocalLightMethod::Clustered;
        hdr = graph.addPass<OverlayData>(
                       "lights_per_cluster", fg::PassKind::Compute,
                       [&](fg::PassBuilder& b, OverlayData& data) {
                           if (tightClusters) {
                               data.in = gbuffer;
                               readGBuffer(b, gbuffer, true);  // the diffuse target's alpha marks flat-lit pixels
                           }
                           data.hdr = b.write(hdr, fg::Usage::ImageLoadStore);
                           readLightRecords(b);
                       },
                       [&state, frame, tightClusters, records](const OverlayData& data, const fg::PassResources& res) {
                           ensureState(state, frame, state.spotShadowVariant, state.pointShadowVariant);
                           // Built here from this frame's lights as the frame's opaque surfaces used
                           // them: tightened to the G-buffer's depth for the deferred clustered
                           // method, whole froxels otherwise (the forward passes' lists).
                           bindLightRecords(state, records, res);
                           const int count = int(records.records->size());
                           if (tightClusters) {
                               const GLuint build = state.clusterTightBuildProgram.id();
                               bindGBuffer(build, res, data.in, frame, true);
                               setUniform(frame, build, "uLightingOnly", 0);
                               buildTightClusters(state, frame, build, count);
                           } else {
                               bindWholeClusters(state, frame, records);
                           }
                           const GLuint prog = state.clusterViewProgram.id();
                           setClusterUniforms(frame, prog, state.clusterGrid);
                           setUniform(frame, prog, "uSlice", frame.settings->localLights.clusterSlice);
                           setUniform(frame, prog, "uHeatMax", kClusterHeatMax);
                           setUniform(frame, prog, "uExposure", exposureEvBase(*frame.settings, *frame.scene));
                           glBindImageTexture(0, res.texture(data.hdr), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
                           glUseProgram(prog);
                           gl::dispatch2D(frame.width, frame.height);
                           unbindAll(state);
                       })
                  .hdr;
    }
    return hdr;
}

}  // namespace lp
