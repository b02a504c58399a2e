#pragma once
// One depth-only raster pass per shadow-casting directional light ("shadow_map_<i>",
// i = the light's index in the scene). Each creates a D32F atlas "shadow_map_<i>.depth" holding its
// cascades as square tiles (see engine/render/shadows.hpp), drawn with slope-scaled depth bias.
// Each cascade draws only the caster clusters that can reach its tile (--shadow-culling, counts in
// 'lightpass graph --explain'), conservatively grown, plain, or by the compute rasteriser
// (--shadow-raster compute: shadow_raster.comp writes an R32UI image private to this pass, which a
// full-atlas draw turns into the D32F atlas; triangles whose window box exceeds
// kComputeRasterMaxTexels in x or y are drawn by the hardware plain path after it), or auto: the
// fastest of the four on this GPU, measured once on the first frame and cached per GPU.
// Conservative and split grow casters by GL_NV_conservative_raster where the GPU has it (and
// GL_NV_fragment_shader_barycentric), else by a geometry shader (--shadow-conservative).
// No shadow-casting light, or shadows switched off: no pass at all.
//
// --shadow-cache on (the default): each light's atlas is a persistent texture of ShadowMapPass,
// imported into every frame's graph (as TAA's history is), and a cascade's tile is redrawn only when
// what it would hold changed: its key (ShadowTileKey: the light's world-to-clip matrix bit for bit,
// which carries the sun direction, the texel-snapped square and the depth range; the tile's place
// and size; the resolved raster and, for conservative and split, whether hardware or the geometry
// shader grew the casters; the slope bias; culling) or the casters (casterSignature: the scene
// on the GPU, every mesh's model matrix and which materials cast). A kept tile is exactly what a
// redraw would write: nothing a tile's depth depends on is outside its key. 'lightpass graph
// --explain' and the pass notes say per cascade "redrawn (why)" or "kept"; render and bench count
// them (ShadowCacheStats). --shadow-cache off: a transient atlas, every cascade drawn every frame.
//
// --shadow-scroll on (the default, with the cache): a tile whose key differs from the kept one only
// in the square's origin (same light rotation, size and depth range, so the same depth for every
// caster point; the same casters, raster and bias) is scrolled instead of redrawn: the part of the
// old tile the new square still covers is moved by the whole-texel offset (shadowTileScroll) by
// glCopyImageSubData within the tile, and only the strips outside it
// (shadowScrollRegions: the newly covered texels plus kShadowScrollMargin texels of the old tile's
// edge) are cleared and drawn, scissored, with the casters that can reach each strip. The move is
// a memmove in bands as wide as the shift (kShadowScrollMaxBands), else through the scratch tile. The moved
// texels were rasterised with the old matrix, whose translation differs from the new one by the
// offset up to float rounding: at a caster's silhouette a texel whose centre lies within that
// rounding of an edge may be covered in one and not the other, and the depth planes round
// differently. The tests bound it (kShadowScrollDepthTolerance everywhere but
// kShadowScrollMaxDifferingFraction of a tile's texels, each next to a depth edge); kept tiles stay
// bit-exact. The compute raster (which draws whole tiles) redraws moved tiles whole.
//
// --shadow-redraw-budget N (default 2, with the cache; 0: no limit): a cascade whose square changed
// in a way its kept tile cannot follow by scrolling, but whose kept tile is still a valid map of its
// previous square (ShadowTileChange::SquareResized, or a move too large to scroll: the same sun,
// depth range, casters, raster, bias), lags: it keeps serving from its previous square (matrix and
// texel size in ShadowAtlasCache::squares; the eye-space matrix redone from this frame's camera)
// while its new square is drawn a quarter tile at a time (at most N quarters a frame, all suns
// together) into the spare atlas at the tile's own place, then copied over the tile. One square is
// pending at a time (ShadowMapPass::pending). The lighting takes, from a pixel's depth split on, the
// first cascade whose square holds it, so what a lagging square misses is shaded from the next
// cascade. The last cascade never lags. With the camera still the squares catch up and every tile is
// what an unbudgeted pass draws, bit for bit.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"
#include "engine/gl/stream_buffer.hpp"
#include "engine/gl/raster_probe.hpp"
#include "engine/graph/frame_graph.hpp"
#include "engine/render/frame_data.hpp"
#include "engine/render/shadow_casters.hpp"
#include "engine/render/shadows.hpp"

namespace lp {

constexpr float kComputeRasterMaxTexels = 64.0f;

// Whether this GPU can grow shadow casters in hardware: GL_NV_conservative_raster for the coverage and
// GL_NV_fragment_shader_barycentric for the triangle's vertices in the fragment shader (its depth
// plane and range). `reason` says what is missing when `hardware` is false.
struct ConservativeRasterSupport {
    bool hardware = false;
    std::string reason;
};
ConservativeRasterSupport queryConservativeRasterSupport();  // needs a current context
// Whether --shadow-conservative `setting` takes the hardware path on a GPU with `support` (auto and
// hardware do where it exists; hardware without it falls back to the geometry shader with a warning).
bool usesHardwareConservative(ShadowSettings::ConservativeRaster setting, const ConservativeRasterSupport& support);
const char* conservativeRasterLabel(bool hardware);  // "hardware" / "geometry shader"

// What one atlas tile holds: equal keys (and equal casters) give bit-identical depth.
struct ShadowTileKey {
    glm::mat4 worldToClip{1.0f};
    int tileSize = 0, column = 0, row = 0;
    int tile = 0;  // index of the atlas tile (row * columns + column), where ShadowAtlasCache keeps it
    ShadowSettings::Raster raster = ShadowSettings::Raster::Conservative;  // resolved (never Auto)
    // Conservative and split only: grown by GL_NV_conservative_raster (true) or the geometry shader;
    // the two give slightly different depth (the hardware's nearest-over-texel vs the GS's clamp).
    bool hardwareConservative = false;
    float slopeBias = 0.0f;
    bool cullCasters = true;
    bool operator==(const ShadowTileKey& o) const;
};

// --shadow-redraw-budget: a cascade's new square drawn a quarter of the tile at a time into the spare
// atlas (at the tile's own place: the same window coordinates rasterise the same depth bit for bit)
// while the cascade keeps serving from its previous square; copied over the atlas tile when all four
// quarters are drawn. One at a time, for all suns.
struct ShadowPendingTile {
    int light = -1;         // whose atlas
    int tile = -1;          // the atlas tile it replaces
    ShadowTileKey key;      // what the new square holds once drawn
    ShadowCascade cascade;  // its matrices and texel size (eyeToClip is redone from each frame's camera)
    unsigned quartersDrawn = 0;  // bit q: quarter q (shadowTileQuarter) is in the spare tile
};

// One light's kept atlas and what each of its tiles holds (none: unknown, e.g. never drawn).
struct ShadowAtlasCache {
    int light = -1;
    gl::Texture depth;  // D32F, width x height
    int width = 0, height = 0;
    uint64_t casters = 0;  // casterSignature the tiles were drawn with
    std::vector<std::optional<ShadowTileKey>> tiles;  // by atlas tile
    // The square each tile holds (matrices, texel size): what a cascade lagging behind its new
    // square (--shadow-redraw-budget) serves from meanwhile.
    std::vector<std::optional<ShadowCascade>> squares;  // by atlas tile
};

// Cascade tiles drawn whole, kept and scrolled (--shadow-scroll: moved, strips drawn) since the
// counters were last reset (render and bench report them); with --shadow-redraw-budget, tiles whose
// new square was completed in the spare tile and copied over (completed), cascades that served from
// their previous square (lagging, counted as kept too), and the quarters of new squares drawn, with
// the most drawn in one frame (all suns together).
struct ShadowCacheStats {
    uint64_t drawn = 0, kept = 0, scrolled = 0, completed = 0, lagging = 0;  // lagging ones are kept too
    uint64_t drawnPerCascade[kMaxShadowCascades] = {}, keptPerCascade[kMaxShadowCascades] = {},
             scrolledPerCascade[kMaxShadowCascades] = {}, completedPerCascade[kMaxShadowCascades] = {},
             laggingPerCascade[kMaxShadowCascades] = {};
    // Quarters drawn; the most budget units (quarters and budgeted scrolls) spent in one frame.
    uint64_t quarters = 0, mostBudgetUnitsInAFrame = 0, frames = 0;
};

// Why a cascade's tile is drawn this frame (shadowTilesToDraw); None: the kept tile holds it.
enum class ShadowTileChange {
    None,
    CacheOff,
    AutoFirstFrame,
    NothingKept,
    AtlasResized,
    CastersChanged,
    TileNotDrawn,
    RasterChanged,
    ConservativeRasterChanged,
    SlopeBiasChanged,
    CullingChanged,
    TileSizeChanged,
    SquareMoved,    // only the square's texel-snapped origin: --shadow-scroll can move the tile
    SquareResized,  // the same sun and depth range, another square: the kept tile stays a valid map of its own square
    LightChanged,   // the sun turned or the depth range changed: the kept tile is no use
};
struct ShadowTileReason {
    ShadowTileChange change = ShadowTileChange::None;
    std::string text;  // what --explain says ("square moved", ...); empty for None
    bool kept() const { return change == ShadowTileChange::None; }
};

// Texels of the old tile's edge redrawn with a scrolled tile's strips: its outermost texels were
// rasterised at the tile's border (where a driver may clip the grown casters and a 2x2 quad's
// derivatives straddle it), so they are not trusted inside the new square.
constexpr int kShadowScrollMargin = 2;
// A scrolled tile's kept part moves in place in bands as wide as the shift (one pass) when that
// takes at most this many copies, else through a scratch tile (two passes).
constexpr int kShadowScrollMaxBands = 16;
// The bound the tests hold a scrolled tile to against a fresh redraw of the same frame: every texel
// within kShadowScrollDepthTolerance of window depth (the moved texels' depth planes were evaluated
// from vertices rounded differently: a few ulps, up to ~1e-5 where the geometry shader's
// derivatives straddle other 2x2 quads), but for at most kShadowScrollMaxDifferingFraction of its
// texels, each next to a depth edge of the fresh tile (a silhouette whose coverage that rounding
// decided).
constexpr float kShadowScrollDepthTolerance = 1e-5f;
constexpr double kShadowScrollMaxDifferingFraction = 1e-3;

// A rectangle of a tile, in texels from the tile's corner.
struct TileRect {
    int x = 0, y = 0, width = 0, height = 0;
};
// Quarter q (0..3: x half q % 2, y half q / 2) of a tile of `tileSize`: the unit of --shadow-redraw-budget.
TileRect shadowTileQuarter(int q, int tileSize);

// The whole-texel offset by which a tile drawn with key `old` moves to be the tile of key `now`
// (content at texel p of the old tile belongs at p + offset), when the two differ only in the
// square's origin by whole texels (within 1/100 texel) and the new square still overlaps enough of
// the old one; none otherwise (the tile is redrawn whole).
std::optional<glm::ivec2> shadowTileScroll(const ShadowTileKey& old, const ShadowTileKey& now);
// The regions of a tile of `tileSize` scrolled by `offset` that are cleared and drawn: every texel
// not covered by the moved old tile less its kShadowScrollMargin edge texels (at most 4 strips).
std::vector<TileRect> shadowScrollRegions(glm::ivec2 offset, int tileSize);
// The part of the new tile the moved old content fills (the complement of shadowScrollRegions).
TileRect shadowScrollKeptRect(glm::ivec2 offset, int tileSize);

// One scissored region of a cascade's tile drawn this frame and the casters that can reach it.
struct ShadowTileRegion {
    TileRect rect;
    CasterList casters;
};
// What a cascade's tile gets this frame: no regions: kept as it is; else each region cleared and
// drawn, after the old content was moved by `offset` where `scrolled`.
struct ShadowTileWork {
    bool scrolled = false;
    glm::ivec2 offset{0};
    std::vector<ShadowTileRegion> regions;
    bool fromSpare = false;  // the pending square, completed in the spare tile, is copied over it
    bool drawn() const { return !regions.empty() || fromSpare; }
};

struct ShadowMapPass {
    gl::Program program;       // conservative casters (shadow_depth.geom)
    // Hardware conservative casters (GL_CONSERVATIVE_RASTERIZATION_NV, no geometry shader): the faces
    // towards the light (conservative only) and the faces away from it (conservative and split).
    gl::Program hardwareTowardProgram;
    gl::Program hardwareAwayProgram;
    std::optional<ConservativeRasterSupport> conservativeSupport;  // asked of the GPU on the first frame
    bool hardwareConservative = false;  // this frame's conservative raster (set when its passes are added)
    bool warnedNoHardware = false;
    gl::Program plainProgram;  // --shadow-raster plain, and split's faces towards the light
    gl::Program awayProgram;   // --shadow-raster split: conservative, faces away from the light only
    // The alpha-tested twins of the five programs above (LP_SHADOW_ALPHA_TEST: the MASK and BLEND
    // casters' draws, CasterList::alphaDraws), made when a frame first has such casters; the compute
    // raster draws its alpha-tested casters with plainAlphaProgram.
    gl::Program alphaProgram, hardwareTowardAlphaProgram, hardwareAwayAlphaProgram, plainAlphaProgram, awayAlphaProgram;
    gl::Framebuffer fbo;
    gl::Texture scrollScratch;  // D32F, one tile: --shadow-scroll moves through it what would take too many bands
    // --shadow-raster compute
    gl::Program rasterProgram;   // shadow_raster.comp
    gl::Program resolveProgram;  // R32UI bits -> D32F atlas
    gl::Program largeProgram;    // the large triangles, plainly
    gl::VertexArray emptyVao;
    gl::Texture depthBits;       // R32UI, the atlas's size
    gl::Buffer largeVertices;    // clip-space vertices of the large triangles, one region per cascade
    size_t largeCapacity = 0;    // vertices
    gl::StreamBuffer largeDraws{"shadow_map.large_draws"};       // one DrawArraysIndirectCommand per cascade
    std::optional<gl::RasterInterpolation> rasterModel;  // probed on the first compute raster
    // --shadow-raster auto: resolved on the first frame drawn (from the cache, or measured)
    bool autoResolved = false;
    ShadowSettings::Raster autoRaster = ShadowSettings::Raster::Conservative;
    std::string autoReport;  // the line logged: the choice, the measured times or "cached", the file
    // Whether the atlases' depths are marked (atlasIsMarked of the raster they were drawn with): set
    // by the shadow passes when they run (auto resolves there), read by the passes that sample the
    // atlases after them in the same frame (LightShadowMap::marked).
    bool atlasMarked = false;
    // --shadow-cache on: one kept atlas per shadowed light
    std::map<int, ShadowAtlasCache> atlases;  // by light index
    // --shadow-redraw-budget: the new square being drawn a quarter at a time, and where (D32F, an
    // atlas's size; made when first needed)
    std::optional<ShadowPendingTile> pending;
    gl::Texture spareAtlas;
    std::map<int, int> nearestLagging;  // by light: its nearest lagging tile when last planned (none: not lagging)
    // --shadow-size-hold: each shadowed light's cascades of the last frame (fitShadowFrustum's `previous`)
    std::map<int, ShadowFrustum> previousFrusta;
    ShadowCacheStats cacheStats;
    size_t cacheBytes() const;  // GPU bytes of the kept atlases and the spare one
};

// A hash of what every cascade's casters are: the SceneGpu, each mesh's model matrix and buffers,
// every material's alpha inputs (mode, cutoff, opacity, base colour map and its uv set) and the
// caster clusters with their CasterAlpha.
uint64_t casterSignature(const FrameData& frame);

// Per cascade of `frustum`: why its tile must be drawn this frame, or None when `cache` already
// holds exactly what it would draw (keys from shadowTileKeys).
std::vector<ShadowTileReason> shadowTilesToDraw(const ShadowAtlasCache* cache, int width, int height, uint64_t casters,
                                           const std::vector<ShadowTileKey>& keys);
// hardwareConservative: this frame grows conservative and split casters by GL_NV_conservative_raster
// (ShadowMapPass::hardwareConservative); the keys record it for those two rasters only.
std::vector<ShadowTileKey> shadowTileKeys(const ShadowFrustum& frustum, const ShadowSettings& settings,
                                          ShadowSettings::Raster resolvedRaster, bool hardwareConservative);
// Whether `resolvedRaster` grows its casters by GL_NV_conservative_raster (conservative and split only).
bool growsCastersInHardware(ShadowSettings::Raster resolvedRaster, bool hardwareConservative);
// Whether an atlas drawn with `resolvedRaster` is marked: each depth's lowest bit says whether a face
// towards the light covers its texel's centre (shaders/common/shadow_caster_depth.glsl). Conservative,
// which draws every caster through that file; split draws the faces towards the light plainly, plain
// and compute all of them: their rasterised depths' lowest bits say nothing.
bool atlasIsMarked(ShadowSettings::Raster resolvedRaster);

// --shadow-raster auto's choice per GPU, the section "shadow_raster" of the measurement cache
// (engine/core/measured_cache.hpp): "<GL_VENDOR / GL_RENDERER / GL_VERSION>": "<raster>".
std::string shadowRasterCacheKey();

struct LightShadowMap {
    int light = -1;          // index into frameDirectionalLights(frame)
    fg::ResourceId depth;    // the atlas
    ShadowFrustum frustum;   // cascades, matrices, tile layout
    const bool* marked = nullptr;  // ShadowMapPass::atlasMarked, known once the pass has run this frame
    // Why the light has fewer cascades than --shadow-cascades asks for ("": all of them); the frame
    // builder records it as the skip "shadow_map_<light> cascades".
    std::string droppedCascades;
};
using ShadowMaps = std::vector<LightShadowMap>;

// Why the frame has no sun shadow pass, or fewer than its shadow-casting suns ("": one a sun); the
// frame builder records it for "shadow_map".
std::string sunShadowSkipReason(const FrameData& frame);
ShadowMaps addShadowMapPasses(fg::FrameGraph& graph, ShadowMapPass& state, const FrameData& frame);

// Draws the opaque draws of a caster list (engine/render/shadow_casters.hpp) with `prog` (bound),
// its uniform `locMvp` set to worldToClip x model.
void drawCasterList(const FrameData& frame, GLuint prog, GLint locMvp, const glm::mat4& worldToClip, const CasterList& casters);
// Draws the alpha-tested draws of a caster list with `prog` (bound; an LP_SHADOW_ALPHA_TEST program
// of shadow_depth.frag), each with its material's alpha inputs (common/shadow_alpha.glsl) and base
// colour map on unit 0, which it leaves unbound.
void drawAlphaCasterList(const FrameData& frame, GLuint prog, const glm::mat4& worldToClip, const CasterList& casters);
// Both: the opaque draws with `opaque`, then the alpha-tested ones with `alphaTested` (its
// alpha-tested twin; 0 where the list has none), each program bound for its draws. The caster loop
// the sun cascades and the spot shadow maps share.
void drawCasters(const FrameData& frame, GLuint opaque, GLuint alphaTested, const glm::mat4& worldToClip,
                 const CasterList& casters);

}  // namespace lp
