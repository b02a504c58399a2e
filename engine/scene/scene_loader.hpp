#pragma once
// Scene files (JSON, documented in the README). Parsing is strict: an unknown field, a wrong type,
// a non-finite number or a missing file is an lp::Error naming the file and the field path.
#include <filesystem>
#include <string>

#include "engine/scene/scene.hpp"

namespace lp {

// Parses the file and loads every model it names (OBJ, glTF or primitive); a glTF's lights join the
// scene's lights, placed by the model's transform.
Scene loadScene(const std::filesystem::path& file);
// Parses JSON text; `origin` names the file in errors and anchors relative paths.
Scene parseScene(const std::string& json, const std::filesystem::path& origin, bool loadMeshes = true);
// A camera path file (--camera-path): the scene file's "cameraPath" object alone. Errors name the
// file and the key ("p.json: cameraPath.keys[2].time: ...").
CameraPath loadCameraPath(const std::filesystem::path& file);
CameraPath parseCameraPathFile(const std::string& json, const std::filesystem::path& origin);
// A model-viewer scene: the OBJ or glTF (by extension), a camera framed on its bounds (or the glTF's
// first camera). A glTF with KHR_lights_punctual brings its own lights; any other model is lit by
// the bundled studio environment with IBL on (studioEnvironmentPath()), its lightsWithoutIbl a key
// and a fill light (without the file: those lights alone, with a warning).
// zUp: the file is Z-up and is turned to Y-up (a -90 degree rotation about +X).
Scene sceneForModel(const std::filesystem::path& file, bool zUp = false);
// hdr/studio.exr under the data root (scripts/make_studio.py writes it).
std::filesystem::path studioEnvironmentPath();
// --env: `map` becomes the scene's environment, its sky and, with IBL on, its indirect light, at
// intensity 1 and rotation 0; an empty path removes the map and IBL (the plain colour stays the
// background, and a bare model's key and fill light take over).
void replaceEnvironment(Scene& scene, const std::filesystem::path& map);
// The rotation that turns a Z-up model Y-up: (x, y, z) -> (x, z, -y).
glm::mat4 zUpToYUp();
// A model file sceneForModel opens (.obj, .gltf, .glb, any case), not a scene file.
bool isModelPath(const std::filesystem::path& file);
// Places the camera so the bounds fill the view (looking from +Z, slightly above).
void frameCamera(Scene& scene);

}  // namespace lp
