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

std::vector<float> sampleWeights(const AnimationSampler& sampler, float time) {
    const std::vector<float>& t = sampler.times;
    const size_t n = sampler.weightCount;
    const bool cubic = sampler.interpolation == AnimationInterpolation::CubicSpline;
    // Weight i of key k's value (the middle third of a cubic key), in-tangent and out-tangent.
    auto value = [&](size_t k, size_t i) { return sampler.weights[(cubic ? 3 * k + 1 : k) * n + i]; };
    auto inTangent = [&](size_t k, size_t i) { return sampler.weights[3 * k * n + i]; };
    auto outTangent = [&](size_t k, size_t i) { return sampler.weights[(3 * k + 2) * n + i]; };
    std::vector<float> out(n, 0.0f);
    if (t.empty() || sampler.weights.size() < t.size() * n * (cubic ? 3 : 1)) return out;
    size_t held = t.size();  // a key whose value holds, or t.size() when interpolating
    if (!(time > t.front())) held = 0;
    else if (time >= t.back()) held = t.size() - 1;
    if (held < t.size()) {
        for (size_t i = 0; i < n; ++i) out[i] = value(held, i);
        return out;
    }
    const size_t k = size_t(std::upper_bound(t.begin(), t.end(), time) - t.begin()) - 1;
    const float d = t[k + 1] - t[k];
    const float s = (time - t[k]) / d;
    const float s2 = s * s, s3 = s2 * s;
    for (size_t i = 0; i < n; ++i) {
        switch (sampler.interpolation) {
            case AnimationInterpolation::Step: out[i] = value(k, i); break;
            case AnimationInterpolation::Linear: out[i] = value(k, i) + (value(k + 1, i) - value(k, i)) * s; break;
            case AnimationInterpolation::CubicSpline:
                out[i] = (2 * s3 - 3 * s2 + 1) * value(k, i) + (s3 - 2 * s2 + s) * d * outTangent(k, i) +
                         (-2 * s3 + 3 * s2) * value(k + 1, i) + (s3 - s2) * d * inTangent(k + 1, i);
                break;
        }
    }
    return out;
}

float clipTime(const AnimationClip& clip, double time) {
    if (!(clip.duration > 0.0f)) return 0.0f;
    const double d = clip.duration;
    const double wrapped = time - std::floor(time / d) * d;
    return float(std::min(std::max(wrapped, 0.0), std::nextafter(d, 0.0)));
}

NodePose animatedPose(const NodeAnimation& animation, const std::vector<int>& playing, double time) {
    struct Trs {
        glm::vec3 t, s;
        glm::vec4 r;  // x, y, z, w
    };
    NodePose pose;
    std::vector<Trs> local(animation.nodes.size());
    pose.weights.resize(animation.nodes.size());
    for (size_t n = 0; n < local.size(); ++n) {
        const AnimatedNode& node = animation.nodes[n];
        local[n] = {node.translation, node.scale, glm::vec4(node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w)};
        pose.weights[n] = node.weights;
    }
    for (int c : playing) {
        const AnimationClip& clip = animation.clips[size_t(c)];
        const float t = clipTime(clip, time);
        for (const AnimationChannel& ch : clip.channels) {
            const AnimationSampler& sampler = clip.samplers[size_t(ch.sampler)];
            if (ch.path == AnimationPath::Weights) {
                std::vector<float>& w = pose.weights[size_t(ch.node)];
                const std::vector<float> v = sampleWeights(sampler, t);
                for (size_t i = 0; i < w.size() && i < v.size(); ++i) w[i] = v[i];
                continue;
            }
            const glm::vec4 v = sampleAnimation(sampler, ch.path, t);
            Trs& trs = local[size_t(ch.node)];
            if (ch.path == AnimationPath::Translation) trs.t = glm::vec3(v);
            else if (ch.path == AnimationPath::Scale) trs.s = glm::vec3(v);
            else trs.r = v;
        }
    }
    pose.worlds.assign(animation.nodes.size(), glm::mat4(1.0f));
    std::vector<glm::mat4>& worlds = pose.worlds;
    for (int n : animation.order) {
        const AnimatedNode& node = animation.nodes[size_t(n)];
        const Trs& trs = local[size_t(n)];
        const glm::mat4 own = node.hasMatrix ? node.matrix
                                             : glm::translate(glm::mat4(1.0f), trs.t) *
                                                   glm::mat4_cast(glm::quat(trs.r.w, trs.r.x, trs.r.y, trs.r.z)) *
                                                   glm::scale(glm::mat4(1.0f), trs.s);
        worlds[size_t(n)] = node.parent >= 0 ? worlds[size_t(node.parent)] * own : own;
    }
    return pose;
}

std::vector<glm::mat4> animatedNodeWorlds(const NodeAnimation& animation, const std::vector<int>& playing, double time) {
    return animatedPose(animation, playing, time).worlds;
}

std::vector<glm::mat4> jointMatrices(const Skin& skin, const std::vector<glm::mat4>& worlds) {
    std::vector<glm::mat4> m(skin.joints.size());
    for (size_t j = 0; j < m.size(); ++j) {
        const int node = skin.joints[j];
        const glm::mat4 world = node >= 0 && size_t(node) < worlds.size() ? worlds[size_t(node)] : glm::mat4(1.0f);
        m[j] = world * (j < skin.inverseBind.size() ? skin.inverseBind[j] : glm::mat4(1.0f));
    }
    return m;
}

namespace {
// The cofactor matrix of m: its inverse transpose times its determinant, defined also where m is
// singular. With the sign of the determinant it turns normals as the inverse transpose does.
glm::mat3 cofactor(const glm::mat3& m) { return glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1])); }
}  // namespace

void poseVertices(const NodeAnimation& animation, const NodePose& pose, std::vector<Vertex>& vertices) {
    const std::vector<glm::mat4>& worlds = pose.worlds;
    std::vector<std::vector<glm::mat4>> joints(animation.skins.size());
    for (size_t s = 0; s < joints.size(); ++s)
        if (std::any_of(animation.ranges.begin(), animation.ranges.end(), [&](const NodeVertexRange& r) { return r.skin == int(s); }))
            joints[s] = jointMatrices(animation.skins[s], worlds);
    for (const NodeVertexRange& range : animation.ranges) {
        const glm::mat4& world = worlds[size_t(range.node)];
        const glm::mat3 linear(world);
        // A pose that scales the node to nothing has no normal: the rest normal's direction stands in.
        const float det = glm::determinant(linear);
        const glm::mat3 normalMatrix = det != 0.0f && std::isfinite(det) ? glm::inverseTranspose(linear) : glm::mat3(1.0f);
        const std::vector<float>& weights = pose.weights[size_t(range.node)];
        const uint32_t targets = std::min(range.morphTargets, uint32_t(weights.size()));
        const float hand = range.mirrored ? -1.0f : 1.0f;
        for (uint32_t i = 0; i < range.vertexCount; ++i) {
            Vertex local = animation.restLocal[range.firstLocal + i];
            for (uint32_t t = 0; t < targets; ++t) {
                const float w = weights[t];
                if (w == 0.0f) continue;
                const MorphDelta& d = animation.morphDeltas[range.firstDelta + size_t(t) * range.vertexCount + i];
                local.position += w * d.position;
                local.normal += w * d.normal;
                local.tangent += glm::vec4(w * d.tangent, 0.0f);
            }
            Vertex& v = vertices[range.firstVertex + i];
            glm::vec3 n, t;
            if (range.skin >= 0) {
                const VertexJoints& vj = animation.vertexJoints[range.firstJoints + i];
                const std::vector<glm::mat4>& jm = joints[size_t(range.skin)];
                glm::mat4 m(0.0f);
                float sum = 0.0f;
                for (int k = 0; k < 8; ++k)
                    if (vj.weight[k] != 0.0f) {
                        m += vj.weight[k] * jm[vj.joint[k]];
                        sum += vj.weight[k];
                    }
                if (sum == 0.0f) m = glm::mat4(1.0f);
                const glm::mat3 ml(m);
                const float md = glm::determinant(ml);
                v.position = glm::vec3(m * glm::vec4(local.position, 1.0f));
                n = (md < 0.0f ? -1.0f : 1.0f) * (cofactor(ml) * local.normal);
                if (!(glm::length(n) > 0.0f)) n = ml * local.normal;  // a joint matrix scaling a plane to a line
                t = ml * glm::vec3(local.tangent);
            } else {
                v.position = glm::vec3(world * glm::vec4(local.position, 1.0f));
                n = normalMatrix * local.normal;
                t = linear * glm::vec3(local.tangent);
            }
            const float nl = glm::length(n);
            if (nl > 0.0f && std::isfinite(nl)) v.normal = n / nl;
            const float tl = glm::length(t);
            if (tl > 0.0f && std::isfinite(tl)) v.tangent = glm::vec4(t / tl, local.tangent.w * hand);
        }
    }
}

void poseVertices(const NodeAnimation& animation, const std::vector<glm::mat4>& worlds, std::vector<Vertex>& vertices) {
    NodePose pose;
    pose.worlds = worlds;
    pose.weights.resize(animation.nodes.size());
    for (size_t n = 0; n < animation.nodes.size(); ++n) pose.weights[n] = animation.nodes[n].weights;
    poseVertices(animation, pose, vertices);
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
