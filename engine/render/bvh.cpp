#include "engine/render/bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace lp {

namespace {
struct Box {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    void grow(glm::vec3 p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void grow(const Box& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
    bool empty() const { return !(lo.x <= hi.x); }
    float area() const {
        if (empty()) return 0.0f;
        const glm::vec3 e = hi - lo;
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

struct BuildTask {
    int node;
    int begin, end;  // range of `order`
    int depth;
};
}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& positions, const BvhBuildOptions& options) {
    Bvh bvh;
    const int triangles = int(positions.size() / 3);
    if (triangles == 0) return bvh;
    const int bins = std::max(options.bins, 2);
    const int maxLeaf = std::max(options.maxLeafSize, 1);
    std::vector<Box> boxes(static_cast<size_t>(triangles));
    std::vector<glm::vec3> centroids(static_cast<size_t>(triangles));
    for (int i = 0; i < triangles; ++i) {
        for (int k = 0; k < 3; ++k) boxes[size_t(i)].grow(positions[size_t(3 * i + k)]);
        centroids[size_t(i)] = 0.5f * (boxes[size_t(i)].lo + boxes[size_t(i)].hi);
    }
    bvh.triangleOrder.resize(size_t(triangles));
    for (int i = 0; i < triangles; ++i) bvh.triangleOrder[size_t(i)] = uint32_t(i);
    std::vector<uint32_t>& order = bvh.triangleOrder;
    bvh.nodes.reserve(size_t(2 * triangles));
    bvh.nodes.emplace_back();
    std::vector<BuildTask> stack{{0, 0, triangles, 1}};
    std::vector<Box> binBoxes(static_cast<size_t>(bins)), rightBoxes(static_cast<size_t>(bins));
    std::vector<int> binCounts(static_cast<size_t>(bins));
    while (!stack.empty()) {
        const BuildTask task = stack.back();
        stack.pop_back();
        bvh.depth = std::max(bvh.depth, task.depth);
        Box bounds, centroidBounds;
        for (int i = task.begin; i < task.end; ++i) {
            bounds.grow(boxes[order[size_t(i)]]);
            centroidBounds.grow(centroids[order[size_t(i)]]);
        }
        BvhNode& node = bvh.nodes[size_t(task.node)];
        node.lo = bounds.lo;
        node.hi = bounds.hi;
        const int count = task.end - task.begin;
        auto makeLeaf = [&] {
            bvh.nodes[size_t(task.node)].first = task.begin;
            bvh.nodes[size_t(task.node)].count = count;
        };
        if (count == 1) {
            makeLeaf();
            continue;
        }
        // The cheapest plane over every axis's bins: cost = traversal + (nL aL + nR aR) / a.
        float bestCost = std::numeric_limits<float>::infinity();
        int bestAxis = -1, bestBin = 0;
        const glm::vec3 extent = centroidBounds.hi - centroidBounds.lo;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0f)) continue;
            std::fill(binBoxes.begin(), binBoxes.end(), Box{});
            std::fill(binCounts.begin(), binCounts.end(), 0);
            const float scale = float(bins) / extent[axis];
            for (int i = task.begin; i < task.end; ++i) {
                const uint32_t t = order[size_t(i)];
                const int b = std::min(bins - 1, int((centroids[t][axis] - centroidBounds.lo[axis]) * scale));
                binBoxes[size_t(b)].grow(boxes[t]);
                ++binCounts[size_t(b)];
            }
            Box right;
            for (int b = bins - 1; b > 0; --b) {
                right.grow(binBoxes[size_t(b)]);
                rightBoxes[size_t(b)] = right;
            }
            Box left;
            int leftCount = 0;
            for (int b = 0; b < bins - 1; ++b) {  // plane after bin b
                left.grow(binBoxes[size_t(b)]);
                leftCount += binCounts[size_t(b)];
                const int rightCount = count - leftCount;
                if (leftCount == 0 || rightCount == 0) continue;
                const float cost = float(leftCount) * left.area() + float(rightCount) * rightBoxes[size_t(b + 1)].area();
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = b;
                }
            }
        }
        const float area = bounds.area();
        const float splitCost = area > 0.0f ? options.traversalCost + bestCost / area : float(count);
        int mid;
        if (bestAxis >= 0 && (splitCost < float(count) || count > maxLeaf)) {
            const float scale = float(bins) / extent[bestAxis];
            const float lo = centroidBounds.lo[bestAxis];
            auto inLeft = [&](uint32_t t) {
                return std::min(bins - 1, int((centroids[t][bestAxis] - lo) * scale)) <= bestBin;
            };
            mid = int(std::partition(order.begin() + task.begin, order.begin() + task.end, inLeft) - order.begin());
        } else if (count > maxLeaf) {
            // Every centroid in one point (or no plane found): halves by index keep leaves small.
            mid = task.begin + count / 2;
        } else {
            makeLeaf();
            continue;
        }
        const int left = int(bvh.nodes.size());
        bvh.nodes[size_t(task.node)].first = left;
        bvh.nodes[size_t(task.node)].count = 0;
        bvh.nodes.emplace_back();
        bvh.nodes.emplace_back();
        stack.push_back({left, task.begin, mid, task.depth + 1});
        stack.push_back({left + 1, mid, task.end, task.depth + 1});
    }
    return bvh;
}

bool intersectTriangle(glm::vec3 origin, glm::vec3 dir, glm::vec3 a, glm::vec3 b, glm::vec3 c, float tMin, float tMax,
                       float& t, float& u, float& v) {
    const glm::vec3 e1 = b - a, e2 = c - a;
    const glm::vec3 p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (det == 0.0f || !std::isfinite(det)) return false;
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - a;
    const float uu = glm::dot(s, p) * inv;
    if (uu < 0.0f || uu > 1.0f) return false;
    const glm::vec3 q = glm::cross(s, e1);
    const float vv = glm::dot(dir, q) * inv;
    if (vv < 0.0f || uu + vv > 1.0f) return false;
    const float tt = glm::dot(e2, q) * inv;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    u = uu;
    v = vv;
    return true;
}

namespace {
bool rayHitsBox(glm::vec3 origin, glm::vec3 invDir, const BvhNode& n, float tMin, float tMax) {
    const glm::vec3 t0 = (n.lo - origin) * invDir, t1 = (n.hi - origin) * invDir;
    const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
    const float enter = std::max(std::max(near.x, near.y), std::max(near.z, tMin));
    const float leave = std::min(std::min(far.x, far.y), std::min(far.z, tMax));
    return enter <= leave;
}
}  // namespace

RayHit intersectBvh(const Bvh& bvh, const std::vector<glm::vec3>& positions, glm::vec3 origin, glm::vec3 dir,
                    float tMin, float tMax) {
    RayHit hit;
    if (bvh.nodes.empty()) return hit;
    const glm::vec3 invDir = 1.0f / dir;  // +-inf for a zero component: the slab test still holds
    std::vector<int> stack{0};
    float nearest = tMax;
    while (!stack.empty()) {
        const BvhNode& n = bvh.nodes[size_t(stack.back())];
        stack.pop_back();
        if (!rayHitsBox(origin, invDir, n, tMin, nearest)) continue;
        if (n.count == 0) {
            stack.push_back(n.first);
            stack.push_back(n.first + 1);
            continue;
        }
        for (int i = n.first; i < n.first + n.count; ++i) {
            const uint32_t tri = bvh.triangleOrder[size_t(i)];
            float t, u, v;
            if (intersectTriangle(origin, dir, positions[3 * tri], positions[3 * tri + 1], positions[3 * tri + 2], tMin,
                                  nearest, t, u, v)) {
                nearest = t;
                hit = {t, int(tri), u, v};
            }
        }
    }
    return hit;
}

RayHit intersectBruteForce(const std::vector<glm::vec3>& positions, glm::vec3 origin, glm::vec3 dir, float tMin,
                           float tMax) {
    RayHit hit;
    float nearest = tMax;
    for (size_t tri = 0; tri < positions.size() / 3; ++tri) {
        float t, u, v;
        if (intersectTriangle(origin, dir, positions[3 * tri], positions[3 * tri + 1], positions[3 * tri + 2], tMin, nearest,
                              t, u, v)) {
            nearest = t;
            hit = {t, int(tri), u, v};
        }
    }
    return hit;
}

}  // namespace lp
