#include "engine/render/gpu_skinning.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <glm/gtc/matrix_inverse.hpp>

namespace lp {

SkinningLayout makeSkinningLayout(const NodeAnimation& animation) {
    SkinningLayout layout;
    layout.skinFirstMatrix.assign(animation.skins.size(), 0);
    std::vector<char> skinUsed(animation.skins.size(), 0);
    for (const NodeVertexRange& r : animation.ranges)
        if (r.skin >= 0 && size_t(r.skin) < skinUsed.size()) skinUsed[size_t(r.skin)] = 1;
    for (size_t s = 0; s < animation.skins.size(); ++s)
        if (skinUsed[s]) {
            layout.skinFirstMatrix[s] = layout.matrixCount;
            layout.matrixCount += uint32_t(animation.skins[s].joints.size());
        }
    for (size_t ri = 0; ri < animation.ranges.size(); ++ri) {
        const NodeVertexRange& r = animation.ranges[ri];
        SkinningRange g;
        g.firstVertex = r.firstVertex;
        g.vertexCount = r.vertexCount;
        g.firstWork = layout.workCount();
        g.firstDelta = r.firstDelta;
        // poseVertices morphs by the targets both the primitive and the node's weights have.
        g.morphTargets = std::min(r.morphTargets, uint32_t(animation.nodes[size_t(r.node)].weights.size()));
        g.firstWeight = layout.weightCount;
        layout.weightCount += g.morphTargets;
        const bool skinned = r.skin >= 0;
        if (skinned) {
            g.firstMatrix = layout.skinFirstMatrix[size_t(r.skin)];
        } else {
            g.firstMatrix = layout.matrixCount;
            layout.matrixCount += 2;  // the node's world matrix and its normal matrix
        }
        g.flags = (skinned ? kSkinningRangeSkinned : 0u) | (r.mirrored ? kSkinningRangeMirrored : 0u);
        layout.ranges.push_back(g);
        for (uint32_t i = 0; i < r.vertexCount; ++i) {
            const Vertex& v = animation.restLocal[r.firstLocal + i];
            layout.workRange.push_back(uint32_t(ri));
            layout.rest.push_back({glm::vec4(v.position, 1.0f), glm::vec4(v.normal, 0.0f), v.tangent});
            SkinningVertexJoints j{};
            if (skinned) {
                const VertexJoints& vj = animation.vertexJoints[r.firstJoints + i];
                j.joint0 = glm::uvec4(vj.joint[0], vj.joint[1], vj.joint[2], vj.joint[3]);
                j.joint1 = glm::uvec4(vj.joint[4], vj.joint[5], vj.joint[6], vj.joint[7]);
                j.weight0 = glm::vec4(vj.weight[0], vj.weight[1], vj.weight[2], vj.weight[3]);
                j.weight1 = glm::vec4(vj.weight[4], vj.weight[5], vj.weight[6], vj.weight[7]);
            }
            layout.joints.push_back(j);
        }
    }
    layout.deltas.reserve(animation.morphDeltas.size());
    for (const MorphDelta& d : animation.morphDeltas)
        layout.deltas.push_back({glm::vec4(d.position, 0.0f), glm::vec4(d.normal, 0.0f), glm::vec4(d.tangent, 0.0f)});
    return layout;
}

std::vector<std::vector<glm::mat4>> usedJointMatrices(const NodeAnimation& animation, const NodePose& pose) {
    std::vector<std::vector<glm::mat4>> joints(animation.skins.size());
    for (size_t s = 0; s < joints.size(); ++s)
        if (std::any_of(animation.ranges.begin(), animation.ranges.end(), [&](const NodeVertexRange& r) { return r.skin == int(s); }))
            joints[s] = jointMatrices(animation.skins[s], pose.worlds);
    return joints;
}

std::vector<glm::vec4> packSkinningPose(const NodeAnimation& animation, const SkinningLayout& layout, const NodePose& pose,
                                        const std::vector<std::vector<glm::mat4>>& jointMatrices) {
    std::vector<glm::vec4> packed(size_t(layout.matrixCount) * 4 + (size_t(layout.weightCount) + 3) / 4, glm::vec4(0.0f));
    auto putMatrix = [&](uint32_t slot, const glm::mat4& m) {
        for (int c = 0; c < 4; ++c) packed[size_t(slot) * 4 + size_t(c)] = m[c];
    };
    for (size_t s = 0; s < animation.skins.size() && s < jointMatrices.size(); ++s)
        for (size_t j = 0; j < jointMatrices[s].size(); ++j) putMatrix(layout.skinFirstMatrix[s] + uint32_t(j), jointMatrices[s][j]);
    float* weights = &packed[size_t(layout.matrixCount) * 4].x;
    for (size_t ri = 0; ri < animation.ranges.size(); ++ri) {
        const NodeVertexRange& r = animation.ranges[ri];
        const SkinningRange& g = layout.ranges[ri];
        if (r.skin < 0) {
            // poseVertices' normal matrix: a pose that scales the node to nothing keeps the rest normal's direction.
            const glm::mat4& world = pose.worlds[size_t(r.node)];
            const glm::mat3 linear(world);
            const float det = glm::determinant(linear);
            const glm::mat3 normalMatrix = det != 0.0f && std::isfinite(det) ? glm::inverseTranspose(linear) : glm::mat3(1.0f);
            putMatrix(g.firstMatrix, world);
            putMatrix(g.firstMatrix + 1, glm::mat4(normalMatrix));
        }
        const std::vector<float>& w = pose.weights[size_t(r.node)];
        for (uint32_t t = 0; t < g.morphTargets && t < w.size(); ++t) weights[g.firstWeight + t] = w[t];
    }
    return packed;
}

std::vector<int> vertexRanges(const NodeAnimation& animation, size_t vertexCount) {
    std::vector<int> rangeOf(vertexCount, -1);
    for (size_t ri = 0; ri < animation.ranges.size(); ++ri) {
        const NodeVertexRange& r = animation.ranges[ri];
        for (uint32_t k = r.firstVertex; k < r.firstVertex + r.vertexCount && k < vertexCount; ++k) rangeOf[k] = int(ri);
    }
    return rangeOf;
}

PoseBounds makePoseBounds(const NodeAnimation& animation, const std::vector<Vertex>& vertices, const std::vector<int>& rangeOf,
                          const std::vector<uint32_t>& indices, uint32_t first, uint32_t count) {
    std::map<std::pair<int, int>, size_t> partOf;
    PoseBounds bounds;
    auto add = [&](int range, int joint, const glm::vec3& p, const MorphDelta* deltas, uint32_t targets, uint32_t stride) {
        auto [it, fresh] = partOf.emplace(std::make_pair(range, joint), bounds.parts.size());
        if (fresh) {
            PoseBoundsPart part;
            part.range = range;
            part.joint = joint;
            part.lo = part.hi = p;
            part.deltaLo.assign(targets, glm::vec3(std::numeric_limits<float>::max()));
            part.deltaHi.assign(targets, glm::vec3(-std::numeric_limits<float>::max()));
            bounds.parts.push_back(std::move(part));
        }
        PoseBoundsPart& part = bounds.parts[it->second];
        part.lo = glm::min(part.lo, p);
        part.hi = glm::max(part.hi, p);
        for (uint32_t t = 0; t < targets; ++t) {
            part.deltaLo[t] = glm::min(part.deltaLo[t], deltas[size_t(t) * stride].position);
            part.deltaHi[t] = glm::max(part.deltaHi[t], deltas[size_t(t) * stride].position);
        }
    };
    for (uint32_t k = first; k < first + count && k < indices.size(); ++k) {
        const uint32_t v = indices[k];
        if (v >= vertices.size() || v >= rangeOf.size()) continue;
        const int ri = rangeOf[v];
        if (ri < 0) {
            add(-1, -1, vertices[v].position, nullptr, 0, 0);
            continue;
        }
        const NodeVertexRange& r = animation.ranges[size_t(ri)];
        const uint32_t i = v - r.firstVertex;
        const glm::vec3 rest = animation.restLocal[r.firstLocal + i].position;
        const MorphDelta* deltas = r.morphTargets > 0 ? &animation.morphDeltas[r.firstDelta + i] : nullptr;
        if (r.skin < 0) {
            add(ri, -1, rest, deltas, r.morphTargets, r.vertexCount);
            continue;
        }
        const VertexJoints& vj = animation.vertexJoints[r.firstJoints + i];
        bool any = false;
        for (int j = 0; j < 8; ++j)
            if (vj.weight[j] != 0.0f) {
                add(ri, int(vj.joint[j]), rest, deltas, r.morphTargets, r.vertexCount);
                any = true;
            }
        if (!any) add(ri, -1, rest, deltas, r.morphTargets, r.vertexCount);
    }
    return bounds;
}

void poseBoundsBox(const PoseBounds& bounds, const NodeAnimation& animation, const NodePose& pose,
                   const std::vector<std::vector<glm::mat4>>& jointMatrices, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(-std::numeric_limits<float>::max());
    for (const PoseBoundsPart& part : bounds.parts) {
        glm::vec3 plo = part.lo, phi = part.hi;
        glm::mat4 m(1.0f);
        if (part.range >= 0) {
            const NodeVertexRange& r = animation.ranges[size_t(part.range)];
            // Morphed: the rest box plus each weighted delta box (interval arithmetic; a negative
            // weight swaps the delta box's ends).
            const std::vector<float>& w = pose.weights[size_t(r.node)];
            for (size_t t = 0; t < part.deltaLo.size() && t < w.size(); ++t) {
                const glm::vec3 a = w[t] * part.deltaLo[t], b = w[t] * part.deltaHi[t];
                plo += glm::min(a, b);
                phi += glm::max(a, b);
            }
            if (r.skin < 0) m = pose.worlds[size_t(r.node)];
            else if (part.joint >= 0 && size_t(part.joint) < jointMatrices[size_t(r.skin)].size()) m = jointMatrices[size_t(r.skin)][size_t(part.joint)];
        }
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner((c & 1) ? phi.x : plo.x, (c & 2) ? phi.y : plo.y, (c & 4) ? phi.z : plo.z);
            const glm::vec3 p = glm::vec3(m * glm::vec4(corner, 1.0f));
            if (!std::isfinite(p.x + p.y + p.z)) continue;
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
}

}  // namespace lp
