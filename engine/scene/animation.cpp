#include "engine/scene/animation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace lp {

glm::vec4 slerpUnit(glm::vec4 a, glm::vec4 b, float s) {
    double d = double(glm::dot(a, b));
    glm::dvec4 qa(a), qb(b);
    if (d < 0.0) {  // q and -q are one rotation: take the shorter arc
        qb = -qb;
        d = -d;
    }
    glm::dvec4 q;
    if (d > 0.9995) {
        q = glm::mix(qa, qb, double(s));  // nearly parallel: the arc is a line, and sin(angle) ~ 0
    } else {
        const double angle = std::acos(std::min(d, 1.0));
        const double sinAngle = std::sin(angle);
        q = (std::sin((1.0 - s) * angle) * qa + std::sin(double(s) * angle) * qb) / sinAngle;
    }
    const double len = glm::length(q);
    return len > 0.0 ? glm::vec4(q / len) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

glm::vec4 sampleAnimation(const AnimationSampler& sampler, AnimationPath path, float time) {
    const std::vector<float>& t = sampler.times;
    const bool cubic = sampler.interpolation == AnimationInterpolation::CubicSpline;
    // The value of key k (the middle of a cubic key's three).
    auto value = [&](size_t k) { return sampler.values[cubic ? 3 * k + 1 : k]; };
    auto unit = [&](glm::vec4 v) {
        if (path != AnimationPath::Rotation) return v;
        const float len = glm::length(v);
        return len > 0.0f ? v / len : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    };
    if (t.empty()) return path == AnimationPath::Scale ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, path == AnimationPath::Rotation);
    if (!(time > t.front())) return unit(value(0));
    if (time >= t.back()) return unit(value(t.size() - 1));
    // The key interval [t_k, t_k+1) holding `time`.
    const size_t k = size_t(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
    const float d = t[k + 1] - t[k];
    const float s = (time - t[k]) / d;
    switch (sampler.interpolation) {
        case AnimationInterpolation::Step: return unit(value(k));
        case AnimationInterpolation::Linear:
            if (path == AnimationPath::Rotation) return slerpUnit(unit(value(k)), unit(value(k + 1)), s);
            return glm::mix(value(k), value(k + 1), s);
        case AnimationInterpolation::CubicSpline: {
            const glm::vec4 vk = value(k), vk1 = value(k + 1);
            const glm::vec4 outTangent = sampler.values[3 * k + 2], inTangent = sampler.values[3 * (k + 1)];
            const float s2 = s * s, s3 = s2 * s;
            return unit((2 * s3 - 3 * s2 + 1) * vk + (s3 - 2 * s2 + s) * d * outTangent + (-2 * s3 + 3 * s2) * vk1 +
                        (s3 - s2) * d * inTangent);
        }
    }
    return unit(value(k));
}

float clipTime(const AnimationClip& clip, double time) {
    if (!(clip.duration > 0.0f)) return 0.0f;
    const double d = clip.duration;
    const double wrapped = time - std::floor(time / d) * d;
    return float(std::min(std::max(wrapped, 0.0), std::nextafter(d, 0.0)));
}

std::vector<glm::mat4> animatedNodeWorlds(const NodeAnimation& animation, const std::vector<int>& playing, double time) {
    struct Trs {
        glm::vec3 t, s;
        glm::vec4 r;  // x, y, z, w
    };
    std::vector<Trs> local(animation.nodes.size());
    for (size_t n = 0; n < local.size(); ++n) {
        const AnimatedNode& node = animation.nodes[n];
        local[n] = {node.translation, node.scale, glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w)};
    }
    for (int c : playing) {
        const AnimationClip& clip = animation.clips[size_t(c)];
        const float t = clipTime(clip, time);
        for (const AnimationChannel& ch : clip.channels) {
            const glm::vec4 v = sampleAnimation(clip.samplers[size_t(ch.sampler)], ch.path, t);
            Trs& trs = local[size_t(ch.node)];
            if (ch.path == AnimationPath::Translation) trs.t = glm::vec3(v);
            else if (ch.path == AnimationPath::Scale) trs.s = glm::vec3(v);
            else trs.r = v;
        }
    }
    std::vector<glm::mat4> worlds(animation.nodes.size(), glm::mat4(1.0f));
    for (int n : animation.order) {
        const AnimatedNode& node = animation.nodes[size_t(n)];
        const Trs& trs = local[size_t(n)];
        const glm::mat4 own = node.hasMatrix ? node.matrix
                                             : glm::translate(glm::mat4(1.0f), trs.t) *
                                                   glm::mat4_cast(glm::quat(trs.r.w, trs.r.x, trs.r.y, trs.r.z)) *
                                                   glm::scale(glm::mat4(1.0f), trs.s);
        worlds[size_t(n)] = node.parent >= 0 ? worlds[size_t(node.parent)] * own : own;
    }
    return worlds;
}

void poseVertices(const NodeAnimation& animation, const std::vector<glm::mat4>& worlds, std::vector<Vertex>& vertices) {
    for (const NodeVertexRange& range : animation.ranges) {
        const glm::mat4& world = worlds[size_t(range.node)];
        const glm::mat3 linear(world);
        // A pose that scales the node to nothing has no normal: the rest normal's direction stands in.
        const float det = glm::determinant(linear);
        const glm::mat3 normalMatrix = det != 0.0f && std::isfinite(det) ? glm::inverseTranspose(linear) : glm::mat3(1.0f);
        for (uint32_t i = 0; i < range.vertexCount; ++i) {
            const Vertex& rest = animation.restLocal[range.firstLocal + i];
            Vertex& v = vertices[range.firstVertex + i];
            v.position = glm::vec3(world * glm::vec4(rest.position, 1.0f));
            const glm::vec3 n = normalMatrix * rest.normal;
            const float nl = glm::length(n);
            if (nl > 0.0f) v.normal = n / nl;
            const glm::vec3 t = linear * glm::vec3(rest.tangent);
            const float tl = glm::length(t);
            if (tl > 0.0f) v.tangent = glm::vec4(t / tl, rest.tangent.w * (range.mirrored ? -1.0f : 1.0f));
        }
    }
}

std::vector<int> chooseClips(const NodeAnimation& animation, const std::string& choice) {
    std::vector<int> clips;
    const int count = int(animation.clips.size());
    if (choice.empty()) {
        if (count > 0) clips.push_back(0);
    } else if (choice == "all") {
        for (int c = 0; c < count; ++c) clips.push_back(c);
    } else if (choice != "none") {
        const bool number = std::all_of(choice.begin(), choice.end(), [](char ch) { return ch >= '0' && ch <= '9'; }) && choice.size() < 9;
        if (number) {
            const int index = std::atoi(choice.c_str());
            if (index < count) clips.push_back(index);
        } else {
            for (int c = 0; c < count; ++c)
                if (animation.clips[size_t(c)].name == choice) clips.push_back(c);
        }
    }
    return clips;
}

}  // namespace lp
