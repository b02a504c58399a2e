#pragma once
// A scene as the scene file describes it: camera, models, lights, environment and effects.
// Units: metres for lengths; a directional light's intensity is its irradiance at normal incidence;
// a point light's intensity is its radiant intensity (irradiance = intensity / d^2 before the window).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/animation.hpp"
#include "engine/scene/camera_path.hpp"
#include "engine/scene/mesh.hpp"

namespace lp {

struct Camera {
    glm::vec3 position{0.0f, 1.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDegrees = 45.0f;
    float nearPlane = 0.05f;
    float farPlane = 100.0f;

    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
};

struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // the way light travels (world space)
    glm::vec3 color{1.0f};
    float intensity = 3.0f;
    bool castsShadows = true;
    // "turn": the direction turns about `turnAxis` (unit) at `turnSpeed` radians per second of scene
    // time: a moving sun, so that no shadow cache holds. 0: a still sun.
    glm::vec3 turnAxis{0.0f, 1.0f, 0.0f};
    float turnSpeed = 0.0f;
    // The direction at `time` seconds on the scene's clock (`direction` at time 0).
    glm::vec3 directionAt(float time) const;
};

// The cone of a spot light: the point light's shading times a falloff that is 1 within innerDegrees
// of the axis and 0 past outerDegrees (common/local_light.glsl's lpSpotFalloff).
struct SpotCone {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit, world space: where the spot points
    float innerDegrees = 20.0f;              // half-angles from the axis, 0 <= inner <= outer < 90
    float outerDegrees = 30.0f;
};

// A local light: a ranged point light, or a spot when `spot` is set.
struct PointLight {
    glm::vec3 position{0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 1.0f;  // brightness reaches exactly zero here
    // Demo animation: orbit around `orbitCenter` about +Y at `orbitSpeed` radians per second.
    glm::vec3 orbitCenter{0.0f};
    float orbitSpeed = 0.0f;
    std::optional<SpotCone> spot;
    // "castsShadow": a spot gets one perspective shadow map (passes/spot_shadow_pass), a point light a
    // cube of six (passes/point_shadow_pass).
    bool castsShadow = false;
};

struct Environment {
    std::filesystem::path map;  // equirectangular .hdr/.exr; empty: plain colour
    glm::vec3 color{0.02f, 0.02f, 0.025f};
    float intensity = 1.0f;
    float rotationDegrees = 0.0f;  // about +Y
    bool ibl = false;              // light the scene with the map (IBL) instead of a constant ambient
};

struct BloomEffect {
    bool enabled = false;
    float threshold = 1.0f;
    float knee = 0.5f;
    float strength = 0.1f;
    int kernelSize = 25;
};

struct ToonEffect {
    bool enabled = false;
    int levels = 4;
    float edgeThreshold = 0.1f;  // depth steps of more than this over the farther depth are outlined
};

struct Effects {
    BloomEffect bloom;
    ToonEffect toon;
};

// One placed model: a mesh loaded from OBJ or glTF, or made by a primitive generator.
struct ModelInstance {
    std::string name;
    std::filesystem::path obj;   // empty for primitives and glTF
    std::filesystem::path gltf;  // .gltf / .glb; empty for primitives and OBJ
    std::string primitive;      // "plane" | "sphere" | "cube" | ""
    glm::mat4 transform{1.0f};
    // "instances": the places its one mesh is drawn at, each world-from-mesh (the instance's own
    // placement times `transform`); empty: drawn once, at `transform`. The mesh is stored once.
    std::vector<glm::mat4> instances;
    size_t instanceCount() const { return instances.empty() ? 1 : instances.size(); }
    const glm::mat4& instanceTransform(size_t k) const { return instances.empty() ? transform : instances[k]; }
    std::optional<glm::vec3> diffuseOverride;
    std::optional<glm::vec3> specularOverride;
    std::optional<float> shininessOverride;
    std::optional<bool> flatOverride;  // "material": {"flat": true}: every material of the model flat-lit
    // "material": {"opacity": a}: every material's opacity; below 1 it is alpha-blended (transparent pass)
    std::optional<float> opacityOverride;
    // "lightShadows": castsShadow of every point and spot light of the glTF (KHR_lights_punctual has
    // no shadow flag); unset: they cast none.
    std::optional<bool> lightShadows;
    MeshData mesh;  // filled by the loader (a glTF's rest pose)
    // Which vertices `mesh` holds: the canonical path of its file, or the primitive ("primitive:cube");
    // empty: its own. Models of one key draw one copy on the GPU (each with its own materials).
    std::string geometryKey;
    // A glTF's animations (null: none) and the clips that play on the scene's clock (--animation;
    // by default the first clip), indices into animation->clips.
    std::shared_ptr<const NodeAnimation> animation;
    std::vector<int> playingClips;
    // "materialVariant": the KHR_materials_variants variant its glTF draws ("": the file's own materials).
    std::string materialVariant;
    // "spin": the model turns about `spinAxis` (unit, through the mesh's own origin) at `spinSpeed`
    // radians per second of scene time: a moving object, played as a one-clip animation (spinAnimation).
    std::optional<glm::vec3> spinAxis;
    float spinSpeed = 0.0f;
    // Whether the model's playing clips put some vertex elsewhere at time t1 than at t0.
    bool movesBetween(double t0, double t1) const;
};

// Lights a scene shades with instead of its own directional lights and ambient on a frame that IBL
// does not light (no environment map, or IBL off): a bare --model is lit by its environment, and by
// this key and fill light when the environment goes (--env none, --brdf-only, the viewer's "plain
// colour"), so it is never left dark, nor lit twice over.
struct LightsWithoutIbl {
    std::vector<DirectionalLight> directionalLights;
    glm::vec3 ambient{0.0f};
};

struct Scene {
    std::filesystem::path file;  // where it came from (empty for generated scenes)
    Camera camera;
    std::vector<ModelInstance> models;
    std::vector<DirectionalLight> directionalLights;
    std::vector<PointLight> pointLights;  // the local lights, points and spots, in file order
    Environment environment;
    // "exposure": a fixed exposure in EV (stops) before the tone map; unset: auto exposure meters
    // each frame (engine/render/exposure.hpp).
    std::optional<float> exposure;
    glm::vec3 ambient{0.03f};  // constant ambient radiance in BRDF mode
    bool lightGlobes = false;  // "lightGlobes": draw each point light as a small flat-lit globe (seed 003)
    std::optional<LightsWithoutIbl> lightsWithoutIbl;  // unset: the lights above, whatever the IBL
    Effects effects;
    // "cameraPath" / --camera-path: when set, frames at time t use cameraAt(t) instead of `camera`
    // (up, near and far stay the camera's). --camera removes it.
    std::optional<CameraPath> cameraPath;

    // The camera of a frame at `time`: the path's position, target and fov there, or `camera`.
    Camera cameraAt(double time) const;

    // World-space bounds of every model (after transforms).
    void bounds(glm::vec3& lo, glm::vec3& hi) const;
};

// --animation CHOICE: the clips every animated model plays ("" the first, "none", "all", an index or
// a name; chooseClips). Throws lp::Error naming the choice and the clips there are when no model has
// the index or name asked for.
void playAnimations(Scene& scene, const std::string& choice);

// --material-variant NAME: every model whose glTF has a KHR_materials_variants variant of that name
// draws it ("": each file's own materials). Throws lp::Error naming the choice and the variants there
// are when no model has it.
void chooseMaterialVariant(Scene& scene, const std::string& variant);

}  // namespace lp
