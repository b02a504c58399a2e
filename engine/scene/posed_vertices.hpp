#pragma once
// A model's vertices where its playing glTF clips put them at a time, on the CPU (the reference
// posing: morphed, skinned, placed by their nodes), for the consumers that read geometry off the GPU:
// the path tracer's scene and the sweep's surface mask.
#include <vector>

#include "engine/scene/animation.hpp"
#include "engine/scene/scene.hpp"

namespace lp {

// model.mesh.vertices posed at `time` into `storage`; a model that plays nothing: mesh.vertices itself.
inline const std::vector<Vertex>& posedVertices(const ModelInstance& model, double time, std::vector<Vertex>& storage) {
    if (!model.animation || model.playingClips.empty()) return model.mesh.vertices;
    storage = model.mesh.vertices;
    poseVertices(*model.animation, animatedPose(*model.animation, model.playingClips, time), storage);
    return storage;
}

}  // namespace lp
