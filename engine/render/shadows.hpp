#pragma once
// Cascaded shadow maps for directional lights: which lights get one, and the light-space
// orthographic frusta (CPU math, no GL, so unit tests and 'lightpass graph' can use it).
//
// Each cascade covers one slice [splitNear, splitFar] of the camera's view depth, itself clipped to
// the depth range the scene's bounds occupy. Cascades are dropped (fewer than asked for) where the
// slice holds no part of the scene visible in the frustum, and after a cascade whose square already
// spans the whole scene (a small scene gets one). Its square is the slice's bounding sphere (so its
// size, hence its texel size, does not change as the camera turns or moves: no shimmering), shrunk
// to the scene's light-space extent when the scene is smaller, kept inside the scene's extent, and
// grown by ShadowSettings::originStep so that its origin can sit on a grid of that step (whole
// texels): the square moves only when the camera's slice leaves it, and not at all when it is
// pinned against the scene's edge or wider than the scene. Depth spans the whole scene bounds along
// the light, so casters outside the view still cast and depth values do not depend on the camera.
// The matrices change only when the square moves, the split grid steps (see below) or the scene
// or light does: what the shadow cache (passes/shadow_map_pass.hpp) relies on. Everything is computed in double precision from bounds
// clamped to +-kMaxShadowCoordinate, so huge scenes give finite matrices (Filament PR #6314).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/frame_data.hpp"

namespace lp {

constexpr int kMaxShadowCascades = 4;
constexpr int kMaxShadowedLights = 4;  // shadow maps the global-light shader binds
constexpr double kMaxShadowCoordinate = 1e18;
constexpr float kMaxShadowOriginStep = 0.25f;  // of the tile: the square then is 4/3 of what it needs
// --shadow-size-hold: a square keeps last frame's side while that is at most this much larger than
// what its slice needs (two steps of the side's 2^(1/8) grid).
constexpr double kShadowSizeHoldRatio = 1.189207115002721;  // 2^(1/4)

struct ShadowCascade {
    glm::mat4 worldToClip{1.0f};  // light orthographic projection * light view
    glm::mat4 eyeToClip{1.0f};    // the same from the camera's eye space (what the shader uses)
    float splitNear = 0.0f;       // view-axis distances (positive) the cascade serves
    float splitFar = 0.0f;
    float texelWorld = 0.0f;      // world-space size of one shadow texel
    float depthRange = 0.0f;      // world-space distance that window depth 0..1 spans
    double side = 0.0;            // world-space side of the square less the origin's room (2^(1/8) grid)
    // Atlas tile (column tile % columns, row tile / columns): the cascade's index among those asked
    // for, so a tile keeps its square (and --shadow-cache its content) when nearer cascades are
    // dropped or come back as the camera moves.
    int tile = 0;
};

struct ShadowFrustum {
    glm::dvec3 lightDirection{0.0, -1.0, 0.0};  // normalised travel direction
    glm::mat3 eyeToLight{1.0f};  // rotation from camera eye space to light view space (+z towards the light)
    std::vector<ShadowCascade> cascades;
    // Tile layout of the atlas: cascade c at column cascades[c].tile % columns, row tile / columns;
    // the grid holds tiles 0 .. the last cascade's (dropped near cascades leave theirs unused).
    int columns = 1, rows = 1;
    int tileSize = 0;
    double visibleNear = 0.0, visibleFar = 0.0;  // view depths of the scene's bounds inside the frustum
    std::vector<std::string> dropped;            // why each cascade not made was dropped
};

// Indices into frameDirectionalLights(frame) of the lights that get a shadow map this frame: those with
// castsShadows, when settings.shadows.enabled, at most kMaxShadowedLights (the first ones).
std::vector<int> shadowCastingLights(const FrameData& frame);

// The cascades for `lightDirection` (travel direction, need not be unit) and `frame`'s camera.
// Throws lp::Error for a zero or non-finite direction or out-of-range settings. With
// settings.shadows.sizeHold and `previous` (last frame's cascades of the same light), each square
// keeps its previous side while that still holds its slice and is at most kShadowSizeHoldRatio
// larger than needed: a camera that zooms or moves its split points back and forth then scrolls the
// cached tiles instead of redrawing them (the frusta then depend on the frames before).
ShadowFrustum fitShadowFrustum(const FrameData& frame, glm::vec3 lightDirection, const ShadowFrustum* previous = nullptr);

// Why fitShadowFrustum made fewer cascades than `requested` (empty when it did not): for the
// frame graph's skipped list ('lightpass graph --explain').
std::string droppedCascadesReason(const ShadowFrustum& frustum, int requested);

// View depths [min, max] of the part of box [lo, hi] inside the camera's frustum (eye space from
// `view`, symmetric perspective of half-angle tangents tanX, tanY), clamped to [near, far]; none
// when no part of the box is in view.
std::optional<glm::dvec2> visibleDepthRange(glm::dvec3 lo, glm::dvec3 hi, const glm::dmat4& view, double nearPlane,
                                            double farPlane, double tanX, double tanY);

// Camera view-depth split distances (cascades + 1 values, first = near, last = far) by the
// practical scheme: lambda * logarithmic + (1 - lambda) * linear.
std::vector<double> practicalSplits(double nearDist, double farDist, int cascades, double lambda);

// Atlas tile grid for `cascades` tiles: 1 -> 1x1, 2 -> 2x1, 3..4 -> 2x2.
glm::ivec2 shadowAtlasGrid(int cascades);

// The grid step of a cascade's origin in texels: --shadow-origin-step of the tile, at least 1.
int originStepTexels(const ShadowSettings& settings);

}  // namespace lp
