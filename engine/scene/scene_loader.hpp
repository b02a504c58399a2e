#pragma once
// Scene files (JSON, documented in the README). Parsing is strict: an unknown field, a wrong type,
// a non-finite number or a missing file is an lp::Error naming the file and the field path.
#include <filesystem>
#include <string>

#include "engine/scene/scene.hpp"

namespace lp {

// Parses the file and loads every model it names (OBJ or primitive).
Scene loadScene(const std::filesystem::path& file);
// Parses JSON text; `origin` names the file in errors and anchors relative paths.
Scene parseScene(const std::string& json, const std::filesystem::path& origin, bool loadMeshes = true);
// A camera path file (--camera-path): the scene file's "cameraPath" object alone. Errors name the
// file and the key ("p.json: cameraPath.keys[2].time: ...").
CameraPath loadCameraPath(const std::filesystem::path& file);
CameraPath parseCameraPathFile(const std::string& json, const std::filesystem::path& origin);
// A model-viewer scene: the OBJ, a camera framed on its bounds, a key and a fill light.
Scene sceneForModel(const std::filesystem::path& obj);
// Places the camera so the bounds fill the view (looking from +Z, slightly above).
void frameCamera(Scene& scene);

}  // namespace lp
