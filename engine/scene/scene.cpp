#include "engine/scene/scene.hpp"

#include <limits>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.hpp"
#include "engine/scene/mesh_ops.hpp"

namespace lp {

glm::mat4 Camera::view() const {
    glm::vec3 forward = target - position;
    glm::vec3 upv = up;
    if (glm::length(glm::cross(forward, upv)) < 1e-6f * glm::length(forward))
        upv = std::abs(forward.y) > 0.0f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);  // looking along up
    return glm::lookAt(position, target, upv);
}

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane);
}

glm::vec3 DirectionalLight::directionAt(float time) const {
    if (turnSpeed == 0.0f) return direction;
    return glm::normalize(glm::vec3(glm::rotate(glm::mat4(1.0f), turnSpeed * time, turnAxis) * glm::vec4(direction, 0.0f)));
}

Camera Scene::cameraAt(double time) const {
    Camera c = camera;
    if (!cameraPath) return c;
    const CameraKey k = cameraPathAt(*cameraPath, time);
    c.position = k.position;
    c.target = k.target;
    c.fovYDegrees = k.fovYDegrees;
    return c;
}

void Scene::bounds(glm::vec3& lo, glm::vec3& hi) const {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(std::numeric_limits<float>::lowest());
    for (const auto& m : models) {
        for (size_t k = 0; k < m.instanceCount(); ++k)
            for (int c = 0; c < 8; ++c) {
                glm::vec3 p((c & 1) ? m.mesh.boundsMax.x : m.mesh.boundsMin.x, (c & 2) ? m.mesh.boundsMax.y : m.mesh.boundsMin.y,
                            (c & 4) ? m.mesh.boundsMax.z : m.mesh.boundsMin.z);
                glm::vec3 w = glm::vec3(m.instanceTransform(k) * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
    }
    if (models.empty()) lo = hi = glm::vec3(0.0f);
}

bool ModelInstance::movesBetween(double t0, double t1) const {
    if (!animation || playingClips.empty() || animation->ranges.empty() || t0 == t1) return false;
    return animatedPose(*animation, playingClips, t0) != animatedPose(*animation, playingClips, t1);
}

void playAnimations(Scene& scene, const std::string& choice) {
    bool found = choice.empty() || choice == "none" || choice == "all";
    std::string clips;  // what there is, for the error
    for (ModelInstance& m : scene.models) {
        if (!m.animation) continue;
        m.playingClips = chooseClips(*m.animation, choice);
        found |= !m.playingClips.empty();
        for (size_t c = 0; c < m.animation->clips.size() && clips.size() < 300; ++c)
            clips += (clips.empty() ? "" : ", ") + std::to_string(c) + " " + quoteUserText(m.animation->clips[c].name);
    }
    if (!found)
        throw Error("--animation " + choice + ": no model has an animation of that " +
                    (choice.find_first_not_of("0123456789") == std::string::npos ? "index" : "name") +
                    (clips.empty() ? std::string(" (the scene has no animations)") : " (animations: " + clips + ")"));
}

void chooseMaterialVariant(Scene& scene, const std::string& variant) {
    bool found = variant.empty();
    std::string variants;  // what there is, for the error
    for (ModelInstance& m : scene.models) {
        if (selectMaterialVariant(m.mesh, variant) && !m.mesh.materialVariants.empty()) {
            m.materialVariant = variant;
            found = true;
        }
        const std::string list = materialVariantList(m.mesh);
        if (!list.empty() && variants.size() < 300) variants += (variants.empty() ? "" : "; ") + m.name + ": " + list;
    }
    if (!found)
        throw Error("--material-variant " + quoteUserText(variant) + ": no model has a material variant of that name" +
                    (variants.empty() ? std::string(" (the scene's models have none)") : " (" + variants + ")"));
}

}  // namespace lp
