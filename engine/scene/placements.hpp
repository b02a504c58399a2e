#pragma once
// The drawn copies of a scene's models: each model once per instance (ModelInstance::instances),
// in model then instance order. SceneGpu::meshes, CasterCluster::model and the visibility buffer's
// mesh records count in this order; a scene without "instances" has one placement per model.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/scene.hpp"

namespace lp {

struct Placement {
    size_t model = 0;     // index into Scene::models
    size_t instance = 0;  // index into its instances (0 for a model drawn once)
    glm::mat4 transform{1.0f};  // world from mesh space
};

std::vector<Placement> placements(const Scene& scene);

// What a scene stores and what it draws ('lightpass graph --explain', the report): meshes are
// stored once per model and drawn once per instance.
struct SceneCounts {
    size_t models = 0;
    size_t instances = 0;         // drawn copies, every model's
    size_t storedVertices = 0;    // vertices of the meshes as stored (each file's or primitive's once)
    size_t storedTriangles = 0;
    size_t drawnTriangles = 0;    // every instance's
};
SceneCounts sceneCounts(const Scene& scene);
// "3 models, 66 instances drawn; 40800 vertices and 80000 triangles stored, 1280000 triangles drawn"
std::string sceneCountsText(const SceneCounts& counts);

}  // namespace lp
