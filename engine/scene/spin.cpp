#include "engine/scene/spin.hpp"

#include <cmath>

#include <glm/gtc/quaternion.hpp>

namespace lp {

NodeAnimation spinAnimation(const MeshData& mesh, glm::vec3 axis, float speed) {
    NodeAnimation a;
    a.nodes.resize(1);
    a.order = {0};
    const float period = 2.0f * float(M_PI) / std::abs(speed);
    AnimationSampler sampler;
    sampler.interpolation = AnimationInterpolation::Linear;
    // Quarter turns: slerp takes the shorter arc, so each key is 90 degrees from the next.
    for (int k = 0; k <= 4; ++k) {
        sampler.times.push_back(period * float(k) / 4.0f);
        const glm::quat q = glm::angleAxis((speed > 0.0f ? 1.0f : -1.0f) * float(M_PI) * 0.5f * float(k), axis);
        sampler.values.emplace_back(q.x, q.y, q.z, q.w);
    }
    AnimationClip clip;
    clip.name = "spin";
    clip.samplers.push_back(std::move(sampler));
    clip.channels.push_back({0, AnimationPath::Rotation, 0});
    clip.duration = period;
    a.clips.push_back(std::move(clip));
    NodeVertexRange range;
    range.vertexCount = uint32_t(mesh.vertices.size());
    a.ranges.push_back(range);
    a.restLocal = mesh.vertices;
    return a;
}

}  // namespace lp
