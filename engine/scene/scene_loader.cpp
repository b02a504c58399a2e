#include "engine/scene/scene_loader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/core/log.hpp"
#include "engine/core/paths.hpp"
#include "engine/io/file_check.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/io/obj_loader.hpp"
#include "engine/scene/mesh_ops.hpp"
#include "engine/scene/primitives.hpp"
#include "engine/scene/spin.hpp"

namespace lp {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Sane bounds, checked at load time so that a value the renderer cannot use fails here, naming the
// file and field, instead of later in the shadow code (or as a blank image).
constexpr float kMaxCoordinate = 1e7f;        // metres from the origin: 10,000 km
constexpr float kMaxScale = 1e6f;             // per-axis model scale magnitude, and 1 / its minimum
constexpr float kMaxIntensity = 1e9f;         // light intensity (and colour components)
constexpr float kMinNear = 1e-6f;             // camera near plane, metres
constexpr float kMaxFar = 1e7f;               // camera far plane, metres
constexpr float kMaxDepthRatio = 1e6f;        // far / near: beyond it depth precision is gone
constexpr size_t kMaxInstances = size_t(1) << 20;  // placements of one model (a million copies)

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

struct Reader {
    std::string file;

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw Error(file + ": " + where + ": " + what);
    }
    void onlyKnown(const json& obj, const std::string& where, const std::set<std::string>& known) const {
        if (!obj.is_object()) fail(where, "expected an object");
        for (auto it = obj.begin(); it != obj.end(); ++it) {
            if (!known.count(it.key())) {
                std::string list;
                for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
                fail(where.empty() ? it.key() : where + "." + it.key(), "unknown field (known: " + list + ")");
            }
        }
    }
    float number(const json& v, const std::string& where) const {
        if (!v.is_number()) fail(where, "expected a number");
        double d = v.get<double>();
        if (!std::isfinite(d) || std::abs(d) > 3.0e38) fail(where, "not a finite number");
        return float(d);
    }
    float number(const json& obj, const char* key, const std::string& where, float fallback) const {
        return obj.contains(key) ? number(obj[key], where + "." + key) : fallback;
    }
    float positive(const json& obj, const char* key, const std::string& where, float fallback, bool allowZero) const {
        float v = number(obj, key, where, fallback);
        if (v < 0.0f || (!allowZero && v == 0.0f)) fail(where + "." + key, allowZero ? "must be >= 0" : "must be > 0");
        return v;
    }
    glm::vec3 vec3(const json& v, const std::string& where) const {
        if (v.is_number()) {
            float s = number(v, where);
            return glm::vec3(s);
        }
        if (!v.is_array() || v.size() != 3) fail(where, "expected an array of 3 numbers");
        return {number(v[0], where + "[0]"), number(v[1], where + "[1]"), number(v[2], where + "[2]")};
    }
    glm::vec3 vec3(const json& obj, const char* key, const std::string& where, glm::vec3 fallback) const {
        return obj.contains(key) ? vec3(obj[key], where + "." + key) : fallback;
    }
    glm::vec3 color(const json& obj, const char* key, const std::string& where, glm::vec3 fallback) const {
        glm::vec3 c = vec3(obj, key, where, fallback);
        if (c.x < 0 || c.y < 0 || c.z < 0) fail(where + "." + key, "colour components must be >= 0");
        if (c.x > kMaxIntensity || c.y > kMaxIntensity || c.z > kMaxIntensity)
            fail(where + "." + key, "colour components must be <= " + formatNumber(kMaxIntensity));
        return c;
    }
    // A position in metres, each coordinate within +-kMaxCoordinate.
    glm::vec3 point(const json& obj, const char* key, const std::string& where, glm::vec3 fallback) const {
        glm::vec3 p = vec3(obj, key, where, fallback);
        for (int i = 0; i < 3; ++i)
            if (std::abs(p[i]) > kMaxCoordinate)
                fail(where + "." + key, formatNumber(p[i]) + " is too far from the origin (limit +-" + formatNumber(kMaxCoordinate) + " m)");
        return p;
    }
    // Normalised in double: in float, the length of [1e38, 1e38, 1e38] is Inf and of [1e-40, 0, 0] is 0,
    // and either would reach the shadow code as NaN.
    glm::vec3 unit(glm::vec3 v, const std::string& where) const {
        const glm::dvec3 d(v);
        const double length = glm::length(d);
        if (!(length > 0.0)) fail(where, "is the zero vector");
        return glm::vec3(d / length);
    }
    float bounded(const json& obj, const char* key, const std::string& where, float fallback, float lo, float hi) const {
        float v = number(obj, key, where, fallback);
        if (v < lo || v > hi)
            fail(where + "." + key, formatNumber(v) + " is outside [" + formatNumber(lo) + ", " + formatNumber(hi) + "]");
        return v;
    }
    bool boolean(const json& obj, const char* key, const std::string& where, bool fallback) const {
        if (!obj.contains(key)) return fallback;
        if (!obj[key].is_boolean()) fail(where + "." + key, "expected true or false");
        return obj[key].get<bool>();
    }
    std::string string(const json& obj, const char* key, const std::string& where) const {
        if (!obj.contains(key)) return {};
        if (!obj[key].is_string()) fail(where + "." + key, "expected a string");
        return obj[key].get<std::string>();
    }
    int integer(const json& obj, const char* key, const std::string& where, int fallback, int lo, int hi) const {
        if (!obj.contains(key)) return fallback;
        const json& v = obj[key];
        if (!v.is_number_integer()) fail(where + "." + key, "expected a whole number");
        long long x = v.get<long long>();
        if (x < lo || x > hi)
            fail(where + "." + key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return int(x);
    }
};

json parseJson(const std::string& text, const fs::path& origin) {
    try {
        return json::parse(text);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for numbers such as 1e400
        std::string what = e.what();
        auto pos = what.find("parse error");
        if (pos == std::string::npos && what.find("] ") != std::string::npos) pos = what.find("] ") + 2;
        throw Error(origin.string() + ": invalid JSON: " + (pos == std::string::npos ? what : what.substr(pos)));
    }
}

fs::path resolve(const fs::path& base, const std::string& p) {
    fs::path path(p);
    return path.is_absolute() ? path : (base / path).lexically_normal();
}

void parseCamera(const Reader& r, const json& j, Camera& cam) {
    const std::string w = "camera";
    r.onlyKnown(j, w, {"position", "target", "up", "fov", "near", "far"});
    cam.position = r.point(j, "position", w, cam.position);
    cam.target = r.point(j, "target", w, cam.target);
    cam.up = r.vec3(j, "up", w, cam.up);
    cam.fovYDegrees = r.number(j, "fov", w, cam.fovYDegrees);
    cam.nearPlane = r.positive(j, "near", w, cam.nearPlane, false);
    cam.farPlane = r.positive(j, "far", w, cam.farPlane, false);
    if (cam.fovYDegrees <= 0.5f || cam.fovYDegrees >= 179.0f) r.fail(w + ".fov", "must be in (0.5, 179) degrees");
    if (cam.farPlane <= cam.nearPlane) r.fail(w + ".far", "must be greater than near");
    if (cam.nearPlane < kMinNear) r.fail(w + ".near", formatNumber(cam.nearPlane) + " is below the " + formatNumber(kMinNear) + " m minimum");
    if (cam.farPlane > kMaxFar) r.fail(w + ".far", formatNumber(cam.farPlane) + " is beyond the " + formatNumber(kMaxFar) + " m maximum");
    if (double(cam.farPlane) > double(kMaxDepthRatio) * cam.nearPlane)
        r.fail(w + ".far", "far / near is " + formatNumber(double(cam.farPlane) / cam.nearPlane) + ", over " +
                               formatNumber(kMaxDepthRatio) + " (the depth buffer cannot resolve it)");
    if (glm::length(cam.target - cam.position) <= 0.0f) r.fail(w + ".target", "equals the position");
    cam.up = r.unit(cam.up, w + ".up");
}

// "cameraPath": {"keys": [{"time", "position", "target", "fov"}, ...], "loop": false}; `w` names it.
CameraPath parseCameraPath(const Reader& r, const json& j, const std::string& w) {
    r.onlyKnown(j, w, {"keys", "loop"});
    if (!j.contains("keys")) r.fail(w + ".keys", "missing (an array of at least two keys)");
    const json& keys = j["keys"];
    if (!keys.is_array()) r.fail(w + ".keys", "expected an array of at least two keys");
    if (keys.size() < 2) r.fail(w + ".keys", "has " + std::to_string(keys.size()) + " key(s); a path needs at least two");
    CameraPath path;
    path.loop = r.boolean(j, "loop", w, false);
    for (size_t i = 0; i < keys.size(); ++i) {
        const std::string wk = w + ".keys[" + std::to_string(i) + "]";
        const json& k = keys[i];
        r.onlyKnown(k, wk, {"time", "position", "target", "fov"});
        for (const char* field : {"time", "position", "target", "fov"})
            if (!k.contains(field)) r.fail(wk + "." + field, "missing");
        CameraKey key;
        key.time = r.number(k["time"], wk + ".time");
        if (std::abs(key.time) > 1e9) r.fail(wk + ".time", formatNumber(key.time) + " is outside [-1e9, 1e9] s");
        key.position = r.point(k, "position", wk, key.position);
        key.target = r.point(k, "target", wk, key.target);
        key.fovYDegrees = r.number(k["fov"], wk + ".fov");
        if (!(key.fovYDegrees > 0.0f && key.fovYDegrees < 180.0f))
            r.fail(wk + ".fov", formatNumber(key.fovYDegrees) + " is outside (0, 180) degrees");
        if (!(glm::length(glm::dvec3(key.target) - glm::dvec3(key.position)) > 0.0)) r.fail(wk + ".target", "equals the position");
        if (i > 0 && !(key.time > path.keys.back().time))
            r.fail(wk + ".time", formatNumber(key.time) + " is not after keys[" + std::to_string(i - 1) + "].time (" +
                                     formatNumber(path.keys.back().time) + "): key times must increase");
        path.keys.push_back(key);
    }
    return path;
}

// "translate", "rotate" (degrees, applied Y, then X, then Z) and "scale" of a model or an instance.
glm::mat4 placementOf(const Reader& r, const json& j, const std::string& w) {
    glm::vec3 t = r.point(j, "translate", w, glm::vec3(0.0f));
    glm::vec3 rot = r.vec3(j, "rotate", w, glm::vec3(0.0f));
    glm::vec3 s = r.vec3(j, "scale", w, glm::vec3(1.0f));
    if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) r.fail(w + ".scale", "must not be zero");
    for (int i = 0; i < 3; ++i)
        if (std::abs(s[i]) > kMaxScale || std::abs(s[i]) < 1.0f / kMaxScale)
            r.fail(w + ".scale", formatNumber(s[i]) + ": magnitude must be in [" + formatNumber(1.0f / kMaxScale) + ", " +
                                     formatNumber(kMaxScale) + "]");
    for (int i = 0; i < 3; ++i)
        if (std::abs(rot[i]) > 1e6f) r.fail(w + ".rotate", formatNumber(rot[i]) + " degrees: magnitude must be <= 1e6");
    glm::mat4 x = glm::translate(glm::mat4(1.0f), t);
    x = glm::rotate(x, glm::radians(rot.y), glm::vec3(0, 1, 0));
    x = glm::rotate(x, glm::radians(rot.x), glm::vec3(1, 0, 0));
    x = glm::rotate(x, glm::radians(rot.z), glm::vec3(0, 0, 1));
    return glm::scale(x, s);
}

void parseModel(const Reader& r, const json& j, const std::string& w, const fs::path& base, ModelInstance& m) {
    r.onlyKnown(j, w, {"name", "obj", "gltf", "primitive", "translate", "rotate", "scale", "up", "material", "materialVariant",
                       "lightShadows", "spin", "instances"});
    m.name = r.string(j, "name", w);
    std::string obj = r.string(j, "obj", w);
    std::string gltf = r.string(j, "gltf", w);
    m.primitive = r.string(j, "primitive", w);
    if (int(!obj.empty()) + int(!gltf.empty()) + int(!m.primitive.empty()) != 1)
        r.fail(w, "needs exactly one of \"obj\", \"gltf\" or \"primitive\"");
    if (!m.primitive.empty() && m.primitive != "plane" && m.primitive != "sphere" && m.primitive != "cube")
        r.fail(w + ".primitive", "unknown primitive " + quoteUserText(m.primitive) + " (plane, sphere, cube)");
    if (!obj.empty()) {
        m.obj = resolve(base, obj);
        // Read as OBJ text a glTF has no "v" or "f" line: "no triangles" would hide the mix-up.
        if (isGltfPath(m.obj)) r.fail(w + ".obj", obj + ": is a glTF file; name it under \"gltf\"");
    }
    if (!gltf.empty()) {
        m.gltf = resolve(base, gltf);
        if (!isGltfPath(m.gltf)) r.fail(w + ".gltf", gltf + ": expected a .gltf or .glb file");
    }
    if (j.contains("materialVariant")) {
        if (gltf.empty()) r.fail(w + ".materialVariant", "only a glTF model has material variants (KHR_materials_variants)");
        m.materialVariant = r.string(j, "materialVariant", w);
    }
    if (j.contains("lightShadows")) {
        if (gltf.empty()) r.fail(w + ".lightShadows", "only a glTF model has lights (KHR_lights_punctual)");
        m.lightShadows = r.boolean(j, "lightShadows", w, false);
    }
    if (j.contains("spin")) {
        const std::string sw = w + ".spin";
        r.onlyKnown(j["spin"], sw, {"axis", "speed"});
        m.spinAxis = r.unit(r.vec3(j["spin"], "axis", sw, glm::vec3(0.0f, 1.0f, 0.0f)), sw + ".axis");
        m.spinSpeed = r.bounded(j["spin"], "speed", sw, 0.5f, -1e3f, 1e3f);
        if (m.spinSpeed == 0.0f) m.spinAxis.reset();  // a spin of speed 0 stands still
    }
    if (m.name.empty()) m.name = !obj.empty() ? fs::path(obj).stem().string() : !gltf.empty() ? fs::path(gltf).stem().string() : m.primitive;
    m.transform = placementOf(r, j, w);
    const std::string up = r.string(j, "up", w);
    if (!up.empty() && up != "y" && up != "z") r.fail(w + ".up", quoteUserText(up) + ": expected \"y\" or \"z\"");
    if (up == "z") m.transform = m.transform * zUpToYUp();  // turned Y-up first, then placed
    if (j.contains("instances")) {
        // The mesh is loaded once and drawn at each instance: its own placement after the model's.
        const json& list = j["instances"];
        const std::string wi = w + ".instances";
        if (!list.is_array()) r.fail(wi, "expected an array of placements ({\"translate\", \"rotate\", \"scale\"})");
        if (list.empty()) r.fail(wi, "is empty; give at least one placement, or leave \"instances\" out to draw the model once");
        if (list.size() > kMaxInstances)
            r.fail(wi, "has " + std::to_string(list.size()) + " placements, over the limit of " + std::to_string(kMaxInstances));
        for (size_t k = 0; k < list.size(); ++k) {
            const std::string wk = wi + "[" + std::to_string(k) + "]";
            r.onlyKnown(list[k], wk, {"translate", "rotate", "scale"});
            m.instances.push_back(placementOf(r, list[k], wk) * m.transform);
        }
    }
    if (j.contains("material")) {
        const json& mat = j["material"];
        const std::string mw = w + ".material";
        r.onlyKnown(mat, mw, {"diffuse", "specular", "shininess", "roughness", "flat", "opacity"});
        if (mat.contains("flat")) m.flatOverride = r.boolean(mat, "flat", mw, false);
        if (mat.contains("diffuse")) m.diffuseOverride = r.color(mat, "diffuse", mw, glm::vec3(0.0f));
        if (mat.contains("specular")) m.specularOverride = r.color(mat, "specular", mw, glm::vec3(0.0f));
        // Reflectances: above 1 a surface gives back more light than reaches it. A flat material's
        // colour is shown as it is (unlit), so it may be brighter.
        auto reflectance = [&](const char* key, const std::optional<glm::vec3>& value) {
            if (value && glm::any(glm::greaterThan(*value, glm::vec3(1.0f))))
                r.fail(mw + "." + key, "reflectance components must be <= 1 (a flat material's diffuse colour may be brighter)");
        };
        if (!m.flatOverride.value_or(false)) reflectance("diffuse", m.diffuseOverride);
        reflectance("specular", m.specularOverride);
        if (mat.contains("shininess")) {
            float n = r.number(mat["shininess"], mw + ".shininess");
            if (n < 0.0f || n > 10000.0f) r.fail(mw + ".shininess", "must be in [0, 10000]");
            m.shininessOverride = n;
        }
        if (mat.contains("roughness")) {
            if (mat.contains("shininess")) r.fail(mw + ".roughness", "give either roughness or shininess, not both");
            const float rough = r.number(mat["roughness"], mw + ".roughness");
            if (!(rough >= kMinRoughness && rough <= 1.0f))
                r.fail(mw + ".roughness", formatNumber(rough) + ": must be in [" + formatNumber(kMinRoughness) + ", 1]");
            m.shininessOverride = shininessFromRoughness(rough);
        }
        if (mat.contains("opacity")) {
            float a = r.number(mat["opacity"], mw + ".opacity");
            if (!(a >= 0.0f && a <= 1.0f)) r.fail(mw + ".opacity", "must be in [0, 1]");
            m.opacityOverride = a;
        }
    }
}

void parseLight(const Reader& r, const json& j, const std::string& w, Scene& scene) {
    std::string type = r.string(j, "type", w);
    if (type == "directional") {
        r.onlyKnown(j, w, {"type", "direction", "color", "intensity", "shadows", "turn"});
        DirectionalLight l;
        l.direction = r.vec3(j, "direction", w, l.direction);
        l.direction = r.unit(l.direction, w + ".direction");
        if (j.contains("turn")) {
            const std::string tw = w + ".turn";
            r.onlyKnown(j["turn"], tw, {"axis", "speed"});
            l.turnAxis = r.unit(r.vec3(j["turn"], "axis", tw, l.turnAxis), tw + ".axis");
            l.turnSpeed = r.bounded(j["turn"], "speed", tw, 0.1f, -1e6f, 1e6f);
        }
        l.color = r.color(j, "color", w, l.color);
        l.intensity = r.bounded(j, "intensity", w, l.intensity, 0.0f, kMaxIntensity);
        l.castsShadows = r.boolean(j, "shadows", w, l.castsShadows);
        scene.directionalLights.push_back(l);
    } else if (type == "point" || type == "spot") {
        const bool spot = type == "spot";
        if (spot)
            r.onlyKnown(j, w, {"type", "position", "direction", "color", "intensity", "range", "innerAngle",
                               "outerAngle", "castsShadow", "orbit"});
        else
            r.onlyKnown(j, w, {"type", "position", "color", "intensity", "range", "castsShadow", "orbit"});
        PointLight l;
        l.position = r.point(j, "position", w, l.position);
        l.color = r.color(j, "color", w, l.color);
        l.intensity = r.bounded(j, "intensity", w, l.intensity, 0.0f, kMaxIntensity);
        l.range = r.positive(j, "range", w, l.range, false);  // any finite range: the shading clamps it
        if (j.contains("orbit")) {
            const std::string ow = w + ".orbit";
            r.onlyKnown(j["orbit"], ow, {"center", "speed"});
            l.orbitCenter = r.point(j["orbit"], "center", ow, l.position);
            l.orbitSpeed = r.bounded(j["orbit"], "speed", ow, 0.5f, -1e6f, 1e6f);
        }
        if (spot) {
            SpotCone c;
            c.direction = r.unit(r.vec3(j, "direction", w, c.direction), w + ".direction");
            c.innerDegrees = r.number(j, "innerAngle", w, c.innerDegrees);
            c.outerDegrees = r.number(j, "outerAngle", w, c.outerDegrees);
            if (c.innerDegrees < 0.0f) r.fail(w + ".innerAngle", formatNumber(c.innerDegrees) + " degrees: must be >= 0");
            if (!(c.outerDegrees > 0.0f && c.outerDegrees < 90.0f))
                r.fail(w + ".outerAngle", formatNumber(c.outerDegrees) + " degrees: must be in (0, 90)");
            if (c.outerDegrees < c.innerDegrees)
                r.fail(w + ".outerAngle", formatNumber(c.outerDegrees) + " degrees is less than innerAngle " +
                                              formatNumber(c.innerDegrees));
            l.spot = c;
        }
        l.castsShadow = r.boolean(j, "castsShadow", w, l.castsShadow);
        scene.pointLights.push_back(l);
    } else {
        r.fail(w + ".type", type.empty() ? "missing (directional, point or spot)"
                                         : "unknown light type " + quoteUserText(type) + " (directional, point, spot)");
    }
}

// The glTF's lights join the scene's, placed by the model's transform; its point and spot lights
// cast shadows where the model says so ("lightShadows").
void addGltfLights(const GltfContent& g, const glm::mat4& transform, std::optional<bool> lightShadows, Scene& scene) {
    for (DirectionalLight d : g.directionalLights) {
        const glm::vec3 dir = glm::mat3(transform) * d.direction;
        if (!(glm::length(dir) > 0.0f)) continue;
        d.direction = glm::normalize(dir);
        scene.directionalLights.push_back(d);
    }
    for (PointLight p : g.pointLights) {
        p.position = glm::vec3(transform * glm::vec4(p.position, 1.0f));
        p.orbitCenter = p.position;
        if (lightShadows) p.castsShadow = *lightShadows;
        if (p.spot) {
            const glm::vec3 dir = glm::mat3(transform) * p.spot->direction;
            if (!(glm::length(dir) > 0.0f)) continue;
            p.spot->direction = glm::normalize(dir);
        }
        scene.pointLights.push_back(p);
    }
}

// The files a scene's models name, each parsed once: a scene listing the same model N times parsed
// it N times (0.23 s per copy of the gallery's models) and repeated its warnings N times. Keyed by
// the canonical path alone: what else a model entry says (material overrides, a material variant,
// the placement) is applied to its copy after the parse. Its vertices are the same for every entry
// of the file, so those share one copy on the GPU (ModelInstance::geometryKey).
struct ParsedFiles {
    std::map<fs::path, MeshData> obj;
    std::map<fs::path, GltfContent> gltf;
    static fs::path key(const fs::path& file) {
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(file, ec);
        return ec ? file : canonical;
    }
};

// A model entry's "material" overrides, on one of its meshes.
void applyMaterialOverrides(const ModelInstance& m, MeshData& mesh) {
    for (auto& mat : mesh.materials) {
        if (m.diffuseOverride) {
            mat.diffuse = *m.diffuseOverride;
            mat.diffuseMap.clear();
        }
        if (m.specularOverride) mat.specular = *m.specularOverride;
        if (m.shininessOverride) mat.shininess = *m.shininessOverride;
        if (m.flatOverride) mat.flat = *m.flatOverride;
        if (m.opacityOverride) {
            mat.opacity = *m.opacityOverride;
            mat.alphaMode = mat.opacity < 1.0f ? AlphaMode::Blend : AlphaMode::Opaque;
        }
    }
}

// A glTF's meshes that several still nodes draw (GltfContent::instancedMeshes) as models of their
// own: each stored once and drawn at every node that draws it, under every placement of the model
// entry `m` (its "instances" included), with m's material variant and overrides. `m` keeps the
// file's other primitives or, where there are none, becomes the first of those models.
void addReusedGltfMeshes(const GltfContent& g, ModelInstance& m, const std::string& fileKey, std::vector<ModelInstance>& extra) {
    std::vector<ModelInstance> made;
    for (const GltfInstancedMesh& im : g.instancedMeshes) {
        ModelInstance reused = m;
        reused.mesh = im.mesh;
        reused.animation = nullptr;
        reused.playingClips.clear();
        reused.name = m.name + "/meshes[" + std::to_string(im.meshIndex) + "]";
        reused.geometryKey = fileKey + "#meshes[" + std::to_string(im.meshIndex) + "]";
        reused.instances.clear();
        for (size_t k = 0; k < m.instanceCount(); ++k)
            for (const glm::mat4& node : im.transforms) reused.instances.push_back(m.instanceTransform(k) * node);
        selectMaterialVariant(reused.mesh, m.materialVariant);  // m's variant was checked against the file's list
        applyMaterialOverrides(m, reused.mesh);
        made.push_back(std::move(reused));
    }
    if (m.mesh.indices.empty() && !made.empty()) {
        const std::string name = m.name;
        m = std::move(made.front());
        m.name = name;
        made.erase(made.begin());
    }
    for (ModelInstance& x : made) extra.push_back(std::move(x));
}

void loadMesh(const Reader& r, ModelInstance& m, const std::string& where, Scene& scene, ParsedFiles& parsed,
              std::vector<ModelInstance>& extra) {
    if (!m.primitive.empty()) {
        if (m.primitive == "plane") m.mesh = makePlane(1.0f, 8);
        else if (m.primitive == "sphere") m.mesh = makeSphere(0.5f, 64, 32);
        else m.mesh = makeCube(1.0f);
        m.geometryKey = "primitive:" + m.primitive;
    } else if (!m.gltf.empty()) {
        if (!fs::exists(m.gltf)) r.fail(where + ".gltf", m.gltf.string() + ": file not found");
        try {
            // A spinning model turns as one mesh about its origin: its meshes that several nodes draw
            // stay in it instead of becoming models of their own.
            const bool split = !m.spinAxis;
            const fs::path key = split ? ParsedFiles::key(m.gltf) : fs::path(ParsedFiles::key(m.gltf).string() + "#whole");
            auto it = parsed.gltf.find(key);
            if (it == parsed.gltf.end()) it = parsed.gltf.emplace(key, loadGltf(m.gltf, nullptr, split)).first;
            m.mesh = it->second.mesh;
            m.geometryKey = "gltf:" + key.string();  // a material variant changes materials, not vertices
            if (!selectMaterialVariant(m.mesh, m.materialVariant))
                r.fail(where + ".materialVariant", quoteUserText(m.materialVariant) + " is not a material variant of " +
                                                       m.gltf.filename().string() +
                                                       (m.mesh.materialVariants.empty() ? std::string(" (it has none)")
                                                                                        : " (" + materialVariantList(m.mesh) + ")"));
            m.animation = it->second.animation;
            if (m.animation) m.playingClips = chooseClips(*m.animation, "");  // the first clip, as glTF viewers play
            for (size_t k = 0; k < m.instanceCount(); ++k)  // each instance brings the file's lights
                addGltfLights(it->second, m.instanceTransform(k), m.lightShadows, scene);
            if (split) addReusedGltfMeshes(it->second, m, m.geometryKey, extra);
        } catch (const Error& e) {  // "<scene>: models[i].gltf: <gltf>: <element>: <what>"
            r.fail(where + ".gltf", e.what());
        }
    } else {
        if (!fs::exists(m.obj)) r.fail(where + ".obj", m.obj.string() + ": file not found");
        try {
            const fs::path key = ParsedFiles::key(m.obj);
            auto it = parsed.obj.find(key);
            if (it == parsed.obj.end()) it = parsed.obj.emplace(key, loadObj(m.obj)).first;
            m.mesh = it->second;
            m.geometryKey = "obj:" + key.string();
        } catch (const Error& e) {  // "<scene>: models[i].obj: <obj>: <what>"
            r.fail(where + ".obj", e.what());
        }
    }
    if (m.spinAxis) {
        if (m.animation) r.fail(where + ".spin", m.gltf.filename().string() + " has animations of its own; a model spins or plays them");
        m.animation = std::make_shared<const NodeAnimation>(spinAnimation(m.mesh, *m.spinAxis, m.spinSpeed));
        m.playingClips = {0};
    }
    applyMaterialOverrides(m, m.mesh);
}

// The model as placed (its mesh bounds through its transform, in double) must stay within +-1e18 m,
// where squared lengths still fit a float: beyond, camera framing and shadow fitting overflow.
void requirePlacedWithinRange(const Reader& r, const ModelInstance& m, const std::string& where) {
    constexpr double kMaxWorldCoordinate = 1e18;
    for (size_t k = 0; k < m.instanceCount(); ++k) {
        const glm::dmat4 transform(m.instanceTransform(k));
        const std::string place = m.instances.empty() ? where : where + ".instances[" + std::to_string(k) + "]";
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 p((c & 1) ? m.mesh.boundsMax.x : m.mesh.boundsMin.x, (c & 2) ? m.mesh.boundsMax.y : m.mesh.boundsMin.y,
                               (c & 4) ? m.mesh.boundsMax.z : m.mesh.boundsMin.z);
            const glm::dvec3 w(transform * glm::dvec4(p, 1.0));
            for (int i = 0; i < 3; ++i)
                if (!(std::abs(w[i]) <= kMaxWorldCoordinate))
                    r.fail(place, "placed up to " + formatNumber(std::abs(w[i])) + " m from the origin, beyond the 1e+18 m limit");
        }
    }
}

}  // namespace

Scene parseScene(const std::string& text, const fs::path& origin, bool loadMeshes) {
    Reader r{origin.string()};
    const json root = parseJson(text, origin);
    r.onlyKnown(root, "", {"camera", "cameraPath", "models", "lights", "environment", "ambient", "effects", "description",
                           "lightGlobes", "exposure"});
    if (root.contains("description") && !root["description"].is_string()) r.fail("description", "expected a string");
    Scene scene;
    scene.file = origin;
    const fs::path base = origin.has_parent_path() ? origin.parent_path() : fs::path(".");
    bool hasCamera = root.contains("camera");
    if (hasCamera) parseCamera(r, root["camera"], scene.camera);
    if (root.contains("cameraPath")) scene.cameraPath = parseCameraPath(r, root["cameraPath"], "cameraPath");
    if (root.contains("models")) {
        if (!root["models"].is_array()) r.fail("models", "expected an array");
        for (size_t i = 0; i < root["models"].size(); ++i) {
            ModelInstance m;
            parseModel(r, root["models"][i], "models[" + std::to_string(i) + "]", base, m);
            scene.models.push_back(std::move(m));
        }
    }
    if (root.contains("lights")) {
        if (!root["lights"].is_array()) r.fail("lights", "expected an array");
        for (size_t i = 0; i < root["lights"].size(); ++i)
            parseLight(r, root["lights"][i], "lights[" + std::to_string(i) + "]", scene);
    }
    if (root.contains("environment")) {
        const json& e = root["environment"];
        r.onlyKnown(e, "environment", {"map", "color", "intensity", "rotation", "ibl"});
        std::string map = r.string(e, "map", "environment");
        if (!map.empty()) scene.environment.map = resolve(base, map);
        scene.environment.color = r.color(e, "color", "environment", scene.environment.color);
        scene.environment.intensity = r.bounded(e, "intensity", "environment", 1.0f, 0.0f, kMaxIntensity);
        scene.environment.rotationDegrees = r.bounded(e, "rotation", "environment", 0.0f, -1e6f, 1e6f);
        scene.environment.ibl = r.boolean(e, "ibl", "environment", false);
        if (scene.environment.ibl && scene.environment.map.empty()) r.fail("environment.ibl", "true needs environment.map (an .hdr or .exr)");
    }
    if (root.contains("exposure")) scene.exposure = r.bounded(root, "exposure", "", 0.0f, -16.0f, 16.0f);
    if (root.contains("ambient")) scene.ambient = r.color(root, "ambient", "", scene.ambient);
    scene.lightGlobes = r.boolean(root, "lightGlobes", "", scene.lightGlobes);
    if (root.contains("effects")) {
        const json& fx = root["effects"];
        r.onlyKnown(fx, "effects", {"bloom", "toon"});
        if (fx.contains("bloom")) {
            const json& b = fx["bloom"];
            const std::string w = "effects.bloom";
            r.onlyKnown(b, w, {"enabled", "threshold", "knee", "strength", "kernel"});
            auto& bl = scene.effects.bloom;
            bl.enabled = r.boolean(b, "enabled", w, true);
            bl.threshold = r.positive(b, "threshold", w, bl.threshold, true);
            bl.knee = r.positive(b, "knee", w, bl.knee, true);
            bl.strength = r.positive(b, "strength", w, bl.strength, true);
            bl.kernelSize = r.integer(b, "kernel", w, bl.kernelSize, 1, 101);
        }
        if (fx.contains("toon")) {
            const json& t = fx["toon"];
            const std::string w = "effects.toon";
            r.onlyKnown(t, w, {"enabled", "levels", "edge"});
            auto& tn = scene.effects.toon;
            tn.enabled = r.boolean(t, "enabled", w, true);
            tn.levels = r.integer(t, "levels", w, tn.levels, 1, 64);
            tn.edgeThreshold = r.positive(t, "edge", w, tn.edgeThreshold, true);
        }
    }
    if (loadMeshes) {
        // Each model is its own copy of its mesh (its instances share it): a 3 MB scene naming 100000
        // spheres asked for 15 GB. The vertices and indices of all models together are bounded
        // (2^26, up to ~3 GB), as are a glTF's instanced ones.
        constexpr size_t kMaxSceneElements = size_t(1) << 26;
        size_t sceneElements = 0;
        ParsedFiles parsed;
        std::vector<ModelInstance> extra;  // glTF meshes several nodes draw, as models of their own
        const size_t listed = scene.models.size();
        for (size_t i = 0; i < listed; ++i) {
            try {
                const size_t before = extra.size();
                loadMesh(r, scene.models[i], "models[" + std::to_string(i) + "]", scene, parsed, extra);
                for (size_t e = before; e < extra.size(); ++e) {
                    requirePlacedWithinRange(r, extra[e], "models[" + std::to_string(i) + "] (" + extra[e].name + ")");
                    sceneElements += extra[e].mesh.vertices.size() + extra[e].mesh.indices.size();
                }
                requirePlacedWithinRange(r, scene.models[i], "models[" + std::to_string(i) + "]");
                sceneElements += scene.models[i].mesh.vertices.size() + scene.models[i].mesh.indices.size();
                if (sceneElements > kMaxSceneElements)
                    r.fail("models[" + std::to_string(i) + "]", "the models so far add up to " + std::to_string(sceneElements) +
                                                              " vertices and indices, over the scene's limit of " + std::to_string(kMaxSceneElements));
            } catch (const Error& e) {
                std::string msg = e.what();
                if (msg.rfind(r.file, 0) == 0) throw;
                throw Error(r.file + ": models[" + std::to_string(i) + "]: " + msg);
            }
        }
        for (ModelInstance& e : extra) scene.models.push_back(std::move(e));
        if (!hasCamera) frameCamera(scene);
    }
    return scene;
}

CameraPath parseCameraPathFile(const std::string& text, const fs::path& origin) {
    Reader r{origin.string()};
    return parseCameraPath(r, parseJson(text, origin), "cameraPath");
}

CameraPath loadCameraPath(const fs::path& file) {
    return parseCameraPathFile(readFileChecked(file, kMaxTextFileBytes, "a camera path file", true), file);
}

Scene loadScene(const fs::path& file) {
    return parseScene(readFileChecked(file, kMaxTextFileBytes, "a scene file", true), file, true);
}

void frameCamera(Scene& scene) {
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    glm::vec3 center = 0.5f * (lo + hi);
    // The camera is framed on at least 0.1 mm (its near plane stays well above zero): a smaller model
    // covers less than a pixel, which would otherwise be an empty image without a word.
    constexpr float kMinFramedRadius = 1e-4f;
    const float modelRadius = 0.5f * glm::length(hi - lo);
    if (modelRadius < kMinFramedRadius && !scene.models.empty()) {
        std::ostringstream msg;
        msg << scene.file.string() << ": the models are only " << 2.0f * modelRadius << " m across; the camera frames 0.0002 m, so they may cover"
            << " less than a pixel (scale them up with a scene file's models[].scale)";
        logWarn(msg.str());
    }
    float radius = std::max(modelRadius, kMinFramedRadius);
    float fov = glm::radians(scene.camera.fovYDegrees);
    float distance = radius / std::sin(0.5f * fov) * 1.05f;
    // Look at the model's largest face: from +Z (slightly above) unless the model is flat across X or
    // Y, where that view would see it edge-on.
    const glm::vec3 extent = hi - lo;
    const float largest = std::max({extent.x, extent.y, extent.z});
    glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));
    if (extent.x < 0.05f * largest && extent.x <= extent.y && extent.x <= extent.z)
        dir = glm::normalize(glm::vec3(1.0f, 0.35f, 0.0f));
    else if (extent.y < 0.05f * largest && extent.y <= extent.z)
        dir = glm::normalize(glm::vec3(0.0f, 1.0f, 0.35f));
    scene.camera.position = center + dir * distance;
    scene.camera.target = center;
    scene.camera.up = glm::vec3(0, 1, 0);
    scene.camera.nearPlane = std::max(distance - radius * 1.5f, distance * 1e-3f);
    scene.camera.farPlane = distance + radius * 3.0f;
}

bool isModelPath(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".obj" || isGltfPath(file);
}

glm::mat4 zUpToYUp() { return glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0)); }

fs::path studioEnvironmentPath() { return dataRoot() / "hdr" / "studio.exr"; }

Scene sceneForModel(const fs::path& file, bool zUp) {
    Scene scene;
    scene.file = file;
    ModelInstance m;
    m.name = file.stem().string();
    if (zUp) m.transform = zUpToYUp();
    if (!fs::exists(file)) throw Error(file.string() + ": file not found");
    std::optional<Camera> fileCamera;
    bool fileLights = false;
    std::vector<ModelInstance> reused;  // its meshes several nodes draw
    if (isGltfPath(file)) {
        m.gltf = file;
        GltfContent g = loadGltf(file, nullptr, true);
        m.mesh = std::move(g.mesh);
        m.geometryKey = "gltf:" + ParsedFiles::key(file).string();
        m.animation = g.animation;
        if (m.animation) m.playingClips = chooseClips(*m.animation, "");  // the first clip, as glTF viewers play
        addGltfLights(g, m.transform, std::nullopt, scene);
        fileLights = !g.directionalLights.empty() || !g.pointLights.empty();
        if (!g.cameras.empty()) fileCamera = g.cameras.front();
        addReusedGltfMeshes(g, m, m.geometryKey, reused);
    } else {
        m.obj = file;
        m.mesh = loadObj(file);
    }
    scene.models.push_back(std::move(m));
    for (ModelInstance& x : reused) scene.models.push_back(std::move(x));
    frameCamera(scene);
    if (fileCamera) scene.camera = *fileCamera;  // a glTF's first camera
    if (fileLights) {  // a glTF's KHR_lights_punctual: its own lighting, no environment added
        scene.ambient = glm::vec3(0.05f);
        return scene;
    }
    // A bare model: lit by the bundled studio environment (IBL), as model viewers light one; the key
    // and fill light (a camera-side key from above left, a dimmer cool fill from the right) take
    // over on a frame without IBL.
    LightsWithoutIbl rig;
    DirectionalLight key;
    key.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
    key.intensity = 3.0f;
    DirectionalLight fill;
    fill.direction = glm::normalize(glm::vec3(0.6f, -0.3f, 0.5f));
    fill.intensity = 0.8f;
    fill.color = glm::vec3(0.8f, 0.9f, 1.0f);
    fill.castsShadows = false;
    rig.directionalLights = {key, fill};
    rig.ambient = glm::vec3(0.05f);
    scene.lightsWithoutIbl = rig;
    scene.ambient = glm::vec3(0.0f);  // the environment is the indirect light
    const fs::path studio = studioEnvironmentPath();
    std::error_code ec;
    if (fs::is_regular_file(studio, ec)) {
        scene.environment.map = studio;
        scene.environment.ibl = true;
    } else {
        logWarn(studio.string() + ": not found; " + file.filename().string() +
                " is lit by a key and a fill light instead of the bundled studio environment");
    }
    return scene;
}

void replaceEnvironment(Scene& scene, const fs::path& map) {
    Environment& e = scene.environment;
    e.map = map;
    e.ibl = !map.empty();
    e.intensity = 1.0f;
    e.rotationDegrees = 0.0f;
}

}  // namespace lp
