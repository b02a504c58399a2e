#pragma once
// CPU side of ranged point lights: which lights a frame draws (the scene's, the first
// N, or generated demo lights), their orbit animation, the exact screen rectangle of a light's
// sphere (scissor method, light-ranges view) and the icosphere that circumscribes it (volumes).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/render/settings.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

struct FrameData;


// One light as the shaders' SSBO holds it (std430, common/local_light.glsl's LpLocalLight).
struct GpuLocalLight {
    glm::vec4 positionRange;  // eye-space position, range
    glm::vec4 intensity;      // rgb colour x radiant intensity, w cos(inner angle) (a point light: -1.5)
    glm::vec4 directionCos;   // eye-space spot axis, w cos(outer angle) (a point light: -2, so no falloff)
    glm::vec4 bound;          // eye-space bounding sphere of all the light reaches: centre, radius
    glm::vec4 shadow;         // x: layer of the spot shadow map array, -1 none; y: point shadow cube, -1 none; zw unused
};
static_assert(sizeof(GpuLocalLight) == 80, "std430 layout of LpLocalLight");

// A sphere holding every point a light reaches. A point light: its range sphere. A spot: the bounding
// sphere of its spherical sector (Wronski, "Cull that cone", 2017): for an outer angle a <= 45 deg the
// sphere through the apex and the cap's rim, centre R / (2 cos a) along the axis; above, the sphere
// about the rim's centre R cos a along the axis, radius R sin a. Either is at most R.
struct BoundingSphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
};
BoundingSphere localLightBounds(const PointLight& light);

// The light as the shaders read it: eye space under `view`; shadowLayer: its spot shadow tile,
// pointShadowCube: its point shadow cube (passes/point_shadow_pass), each -1 when it has none.
GpuLocalLight gpuLocalLight(const PointLight& light, const glm::mat4& view, int shadowLayer, int pointShadowCube = -1);

// `count` deterministic demo lights spread through the box [lo, hi] (position and colour seeded by the
// index): ranges shrink as count grows so that about 8 lights overlap a point of the box.
std::vector<PointLight> generateDemoLights(glm::vec3 lo, glm::vec3 hi, int count);

// The lights a frame draws, in world space at `time` (orbits applied), before any culling:
// nothing when disabled; the scene's lights when lightCount < 0; else the first lightCount of them,
// followed by generated demo lights (in the scene's bounds) when the scene has fewer.
std::vector<PointLight> localLightsForFrame(const Scene& scene, const LocalLightSettings& settings, float time);
// The lights `frame` draws at frame.time: frame.localLights, or, in a frame made without them,
// localLightsForFrame's now.
std::shared_ptr<const std::vector<PointLight>> frameLocalLights(const FrameData& frame);
// How many lights localLightsForFrame returns, without building them (for the graph's setup).
int localLightCount(const Scene& scene, const LocalLightSettings& settings);

// Position of a light at `time`: rotated about +Y through orbitCenter by orbitSpeed * time radians.
glm::vec3 orbitPosition(const PointLight& light, float time);

// Pixel rectangle (GL convention: origin bottom-left) that holds the projection of a sphere.
struct ScissorRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool fullScreen = false;  // the camera is inside the sphere or the sphere crosses the near plane
    bool empty() const { return width <= 0 || height <= 0; }
};
// The exact bounding rectangle of the perspective projection of the sphere (centre in eye space,
// camera looking down -Z), from the tangent planes through the eye, rounded outwards to whole
// pixels and clipped to the viewport. Full screen when the sphere reaches the near plane; empty when
// the sphere is wholly behind the near plane or off screen.
ScissorRect sphereScissorRect(glm::vec3 centerEye, float radius, const glm::mat4& projection, float nearPlane, int width,
                              int height);

// Triangle list (3 vertices per face) of an icosphere with `subdivisions` levels whose every face lies
// at distance >= 1 from the origin: it circumscribes the unit sphere, so scaled by a light's range it
// covers every point the light reaches.
std::vector<glm::vec3> circumscribingIcosphere(int subdivisions);

}  // namespace lp
