// The path tracer's BVH (engine/render/bvh.hpp): every triangle in exactly one leaf, every node's box
// holding its children (and a leaf's box its triangles), and ray queries equal to testing every
// triangle.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "engine/render/bvh.hpp"

namespace lp {
namespace {

// `n` random triangles in a 10 m cube: sizes from millimetres to metres, some slivers, some repeated.
std::vector<glm::vec3> randomTriangles(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-5.0f, 5.0f), unit(-1.0f, 1.0f), logSize(-3.0f, 0.3f);
    std::vector<glm::vec3> p;
    for (int i = 0; i < n; ++i) {
        if (i % 17 == 16) {  // a copy of the previous triangle: identical centroids
            p.insert(p.end(), p.end() - 3, p.end());
            continue;
        }
        const glm::vec3 c(pos(rng), pos(rng), pos(rng));
        const float size = std::pow(10.0f, logSize(rng));
        for (int k = 0; k < 3; ++k) p.push_back(c + size * glm::vec3(unit(rng), unit(rng), unit(rng)));
    }
    return p;
}

bool contains(const BvhNode& outer, glm::vec3 lo, glm::vec3 hi) {
    return glm::all(glm::lessThanEqual(outer.lo, lo)) && glm::all(glm::greaterThanEqual(outer.hi, hi));
}

void checkStructure(const Bvh& bvh, const std::vector<glm::vec3>& p) {
    const size_t triangles = p.size() / 3;
    ASSERT_EQ(bvh.triangleOrder.size(), triangles);
    std::vector<int> seen(triangles, 0);
    int maxDepth = 0;
    std::vector<std::pair<int, int>> stack{{0, 1}};
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        maxDepth = std::max(maxDepth, depth);
        ASSERT_LT(size_t(index), bvh.nodes.size());
        const BvhNode& n = bvh.nodes[size_t(index)];
        if (n.count == 0) {
            ASSERT_LT(size_t(n.first + 1), bvh.nodes.size()) << "node " << index;
            for (int c : {n.first, n.first + 1}) {
                const BvhNode& child = bvh.nodes[size_t(c)];
                EXPECT_TRUE(contains(n, child.lo, child.hi)) << "node " << index << " does not contain child " << c;
                stack.push_back({c, depth + 1});
            }
        } else {
            ASSERT_LE(size_t(n.first + n.count), triangles) << "leaf " << index;
            for (int i = n.first; i < n.first + n.count; ++i) {
                const uint32_t t = bvh.triangleOrder[size_t(i)];
                ++seen[t];
                for (int k = 0; k < 3; ++k)
                    EXPECT_TRUE(contains(n, p[3 * t + k], p[3 * t + k])) << "leaf " << index << " misses triangle " << t;
            }
        }
    }
    for (size_t t = 0; t < triangles; ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t << " is in " << seen[t] << " leaves";
    EXPECT_EQ(maxDepth, bvh.depth);
}

TEST(Bvh, EveryTriangleInOneLeafAndNodesContainTheirChildren) {
    for (int n : {1, 2, 5, 100, 3000}) {
        SCOPED_TRACE(n);
        const std::vector<glm::vec3> p = randomTriangles(n, unsigned(n));
        const Bvh bvh = buildBvh(p);
        checkStructure(bvh, p);
        // Binned SAH keeps leaves small and the tree far from a list.
        for (const BvhNode& node : bvh.nodes) EXPECT_LE(node.count, 4);
        if (n == 3000) EXPECT_LT(bvh.depth, 40);
    }
}

TEST(Bvh, IdenticalTrianglesStillSplitDownToSmallLeaves) {
    std::vector<glm::vec3> p;
    for (int i = 0; i < 50; ++i) p.insert(p.end(), {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)});
    const Bvh bvh = buildBvh(p);
    checkStructure(bvh, p);
    for (const BvhNode& node : bvh.nodes) EXPECT_LE(node.count, 4);
}

TEST(Bvh, EmptyInputGivesNoNodesAndNoHit) {
    const Bvh bvh = buildBvh({});
    EXPECT_TRUE(bvh.nodes.empty());
    EXPECT_FALSE(intersectBvh(bvh, {}, glm::vec3(0), glm::vec3(0, 0, 1), 0.0f, 1e30f).hit());
}

TEST(Bvh, RayQueriesEqualBruteForceOnRandomRays) {
    const std::vector<glm::vec3> p = randomTriangles(2000, 7u);
    const Bvh bvh = buildBvh(p);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-7.0f, 7.0f), unit(-1.0f, 1.0f), tMax(0.5f, 20.0f);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 o(pos(rng), pos(rng), pos(rng));
        glm::vec3 d(unit(rng), unit(rng), unit(rng));
        if (glm::length(d) < 1e-3f) continue;
        d = glm::normalize(d);
        const float limit = i % 4 == 0 ? tMax(rng) : 1e30f;  // shadow-ray style queries too
        const RayHit a = intersectBvh(bvh, p, o, d, 1e-4f, limit);
        const RayHit b = intersectBruteForce(p, o, d, 1e-4f, limit);
        ASSERT_EQ(a.hit(), b.hit()) << "ray " << i;
        if (!a.hit()) continue;
        ++hits;
        EXPECT_EQ(a.t, b.t) << "ray " << i;
        // The same nearest triangle, or one at exactly the same distance (the repeated copies).
        if (a.triangle != b.triangle) {
            float t, u, v;
            const uint32_t tri = uint32_t(a.triangle);
            ASSERT_TRUE(intersectTriangle(o, d, p[3 * tri], p[3 * tri + 1], p[3 * tri + 2], 1e-4f, limit, t, u, v));
            EXPECT_EQ(t, b.t) << "ray " << i;
        }
    }
    EXPECT_GT(hits, 400);  // the query is exercised, not only misses
}

}  // namespace
}  // namespace lp
