#pragma once
// Local lights (ranged points and spots) added into the HDR buffer, by one of five methods that give
// the same image (settings.localLights.method): fullscreen, scissor, volumes, tiled, clustered. Plus
// the overlays: light globes, the light-ranges view and the lights-per-tile and lights-per-cluster
// heat maps. The clustered method culls to froxels tightened to the G-buffer's depth in shared memory
// and shades from them in one dispatch (local_light_clustered.comp); the lights-per-cluster view
// builds the same tight froxels' lists (light_clusters_tight.comp) and the forward passes whole
// froxels (light_clusters.comp) into the grid buffers.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/gl/stream_buffer.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/kernel_race.hpp"
#include "engine/render/light_clusters.hpp"
#include "engine/render/local_lights.hpp"
#include "passes/gbuffer_pass.hpp"
#include "passes/point_shadow_pass.hpp"
#include "passes/spot_shadow_pass.hpp"

namespace lp {

// The local lights' shadow maps of a frame: the shadowed spots' atlas and the shadowed point lights'
// cubes (each absent when no such light casts).
struct LocalShadowMaps {
    SpotShadowMaps spot;
    PointShadowMaps point;
};
// Their atlases' textures in a pass's execute (0: absent).
struct LocalShadowAtlases {
    GLuint spot = 0, point = 0;
};

// What the last executed local-light pass did, for tests and the UI.
struct LocalLightStats {
    LocalLightMethod method = LocalLightMethod::Tiled;
    int requested = 0;   // lights in the SSBO this frame
    int drawn = 0;       // lights the method shaded: draw calls, instances, or lights the tiles binned from
    int offscreen = 0;   // scissor method: lights skipped because their rectangle was empty
    int fullScreen = 0;  // scissor method: lights drawn full screen (camera inside / near plane crossed)
    int clusters = 0;    // clustered method: froxels in the grid
    bool slicesShaded = false;  // clustered method: its kernel ran (false: the tiled kernel on its tiles)
    // clustered method under --clustered-kernel auto: whether a race round ran this frame, and the
    // last finished round's median ms of the clustered kernel and of the tiled kernel (-1: none yet).
    bool kernelRacing = false;
    double froxelKernelMs = -1.0, tileKernelMs = -1.0;
    // clustered method: froxels of the previous grid build that held more than kMaxLightsPerCluster
    // lights (read back one build late, so the frame does not wait for the GPU); -1 before any.
    int clustersOverflowing = -1;
};

struct LocalLightPass {
    gl::Program fragmentProgram;  // local_light.vert/.frag: fullscreen, scissor, volumes
    gl::Program tiledProgram;     // local_light_tiled.comp
    gl::Program heatmapProgram;   // local_light_tiled.comp with LP_TILE_HEATMAP
    gl::Program sanitizeProgram;  // local_light_sanitize.comp
    gl::Program overlayProgram;   // local_light_overlay.vert/.frag: globes, volumes, rectangles
    gl::Program clusterBuildProgram;  // light_clusters.comp
    gl::Program clusteredProgram;     // local_light_clustered.comp: tight froxels in shared memory and shading, fused
    gl::Program clusteredSupertileProgram;  // the same with LP_SUPERTILES: candidates from supertile lists (many lights)
    // --clustered-kernel auto: the race between the clustered kernel (0) and the tiled kernel (1) for
    // the view (engine/render/kernel_race.hpp), and the timestamps around the kernels it timed, read
    // once the GPU has passed them (never waited for).
    KernelRace clusteredRace;
    struct RaceTiming {
        gl::Query begin, end;
        int kernel = 0;
        std::uint64_t key = 0;
        bool pending = false;
    };
    std::array<RaceTiming, 8> raceTimings;
    gl::Program clusterTightBuildProgram;  // light_clusters_tight.comp: the tight lists (lights-per-cluster view)
    int clusterTileCompiled = 0;      // the tile size (--cluster-size) those two were compiled for
    gl::Program clusterViewProgram;   // light_clusters_view.comp
    ClusterGrid clusterGrid;          // the grid the last build made
    gl::Buffer clusterCounts;         // uint per cluster: lights touching it (uncapped)
    gl::Buffer clusterLists;          // kMaxLightsPerCluster uints per cluster: light indices
    // The whole build's first level (light_cluster_supertiles.comp): per supertile of
    // supertileTiles x supertileTiles froxel tiles, its light count and up to supertileCapacity
    // light indices, made from a bit per light (supertileBits) by the last of its work groups to
    // finish (supertileDone counts them). The two sizes are settable for tests (0: the defaults; a
    // supertile size set here also makes the first level run below its light count; a negative one
    // turns it off).
    gl::Program clusterSupertileProgram;
    gl::Buffer supertileCounts, supertileLists, supertileBits, supertileDone;
    size_t supertileCountsCapacity = 0, supertileListsCapacity = 0;  // uints the buffers hold
    size_t supertileBitsCapacity = 0, supertileDoneCapacity = 0;
    int supertileTiles = 0, supertileCapacity = 0;
    // One uint per build: clusters past the cap. A ring, each slot read back only once its fence
    // has signaled, so the warning never makes the CPU (or the pass's GPU timer) wait on a build.
    // The builds count into clusterOverflowCounter, in GPU memory, and each build's count is then
    // copied into its slot: an atomic on the mapped slot itself (host memory) crosses the bus (~0.6 us
    // each, measured with one a work group on an H100).
    gl::Buffer clusterOverflowCounter;
    struct OverflowSlot {
        gl::Buffer count;
        const GLuint* mapped = nullptr;  // `count`, persistently mapped: read without a GL call
        gl::Fence done;     // after the build that wrote `count`
        bool read = false;  // its count is in stats already
    };
    std::array<OverflowSlot, 8> clusterOverflow;  // up to three builds a frame (forward, transparent, view)
    int nextOverflowSlot = 0;
    size_t clusterCapacity = 0;       // clusters the buffers hold
    int lastOverflowWarned = 0;
    gl::Program globeVelocityProgram;  // the same with LP_GLOBE_VELOCITY: globes and their motion vectors
    GBufferSettings layout;       // the G-buffer layout the fragment, tiled and heatmap programs were compiled for
    bool spotShadowVariant = false;  // ... and whether with LP_SPOT_SHADOWS (only frames with a shadowed spot)
    // ... and with the material extensions' targets the G-buffer carries (LP_GBUFFER_FRESNEL,
    // LP_GBUFFER_CLEARCOAT: gbufferCarriesFresnel, gbufferCarriesClearcoat)
    bool fresnelVariant = false, clearcoatVariant = false;
    bool pointShadowVariant = false;  // ... and with LP_POINT_SHADOWS (only frames with a shadowed point light)
    gl::StreamBuffer spotShadows{"spot_shadows.ssbo"};  // LpPerspectiveShadow per atlas tile (binding 4)
    gl::StreamBuffer pointShadows{"point_shadows.ssbo"};  // LpPerspectiveShadow per cube face (LP_POINT_SHADOW_BUFFER)
    gl::Framebuffer fbo;
    // GpuLocalLight per light (binding 0): the frame's "local_lights.records", filled once a frame
    // (LocalLightRecords).
    gl::StreamBuffer lights{"local_lights.ssbo"};
    std::shared_ptr<const std::vector<GpuLocalLight>> filledRecords;  // what `lights` holds now
    int recordFills = 0;  // fills of `lights` since the state was made (tests: one a frame)
    // The records whose whole-froxel lists clusterCounts / clusterLists hold (null after a tight
    // build, which overwrites them): forward_opaque, transparent and the lights-per-cluster view read
    // one build a frame.
    std::shared_ptr<const std::vector<GpuLocalLight>> wholeListsFor;
    int clusterBuilds = 0;  // grid builds, whole or tight, since the state was made (tests)
    gl::StreamBuffer globeMotion{"light_globes.motion"};  // each light's world centre now and at the previous frame's time
    gl::Buffer volumeMesh, globeMesh;
    gl::VertexArray volumeVao, globeVao;
    int volumeVertices = 0, globeVertices = 0;
    LocalLightStats stats;
};

// The frame's local lights as GPU records (eye space; a shadowed spot's record names its atlas
// tile, a shadowed point light's its cube), made when the graph is built (outside every pass's timing window) and uploaded once a
// frame into LocalLightPass::lights, the graph's buffer "local_lights.records": the pass that shades
// the lights first (local_lights; forward_opaque on the forward+ path) writes it (an upload), the
// transparent pass and the overlays read it.
struct LocalLightRecords {
    fg::ResourceId buffer;  // "local_lights.records" as imported; writers write this version
    std::shared_ptr<const std::vector<GpuLocalLight>> records;
};
LocalLightRecords importLocalLightRecords(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                          const LocalShadowMaps& shadows);
// In a pass's setup: it fills the records (uploaded before the frame's first pass, outside every
// pass's timing window), or reads what the frame's filling pass uploaded (the last version of
// "local_lights.records", whichever pass wrote it).
void writeLightRecords(fg::PassBuilder& b, LocalLightPass& state, const LocalLightRecords& records);
void readLightRecords(fg::PassBuilder& b);
// In a pass's execute: the records into SSBO 0. Uploaded here only if `lights` does not hold this
// frame's records yet: when the filling pass did not run (disabled), by the first reader; every
// later pass binds the same buffer.
void bindLightRecords(LocalLightPass& state, const LocalLightRecords& records, const fg::PassResources& res);

// Adds the "local_lights" pass (read-modify-write of hdr; fills `records`). Whether the frame needs it
// (lights on, some in view) is the frame builder's decision. With shadows.spot.any() or
// shadows.point.any() it also samples their atlases.
fg::ResourceId addLocalLightPass(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                 const GBuffer& gbuffer, fg::ResourceId hdr, bool lightingOnly,
                                 const LocalShadowMaps& shadows, const LocalLightRecords& records);

// For the forward passes (passes/forward_pass, passes/transparent_pass), inside their execute: binds
// the frame's light records (SSBO 0, bindLightRecords), builds the clustered method's froxel grid from
// them (counts SSBO 1, lists SSBO 2; the same build and buffers as the clustered local_lights pass)
// and, when a spot casts a shadow, binds their shadow records (SSBO 4) and `atlases.spot` (unit 5), when a
// point light does, its cubes' records (SSBO 5) and `atlases.point` (unit 18). Sets
// `prog`'s cluster uniforms and uLocalLightCount, uUnbounded, uSpecularMode. Returns the number of lights.
int bindClusteredLightLists(LocalLightPass& state, GLuint prog, const FrameData& frame, const LocalLightRecords& records,
                            const fg::PassResources& res, const LocalShadowMaps& shadows, LocalShadowAtlases atlases);
void unbindClusteredLightLists();

// After the sky: "light_globes" (settings.localLights.globes, else the scene's lightGlobes) and the overlay views
// ("light_ranges", "lights_per_tile", "lights_per_cluster") over the finished HDR image, from the
// frame's light records. When the frame has gbuffer.velocity, the globes also write their motion into
// it (their lights orbit): gbuffer.velocity becomes that new version, for the passes that read motion
// after them.
fg::ResourceId addLocalLightOverlayPasses(fg::FrameGraph& graph, LocalLightPass& state, const FrameData& frame,
                                          GBuffer& gbuffer, fg::ResourceId hdr, const LocalLightRecords& records);

}  // namespace lp
