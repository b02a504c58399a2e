// Checks a GLB written by bench/peers/scene_to_glb.py against lightpass's own reading of the scene
// it came from: lightpass's loaders read both, so the GLB is valid to lightpass's glTF loader and
// draws the same triangles (count), in the same world bounds, seen from the same camera. With the
// sidecar (NAME.peer.json) its triangle count and bounds must match too.
//   peer_glb_check SCENE.json NAME.glb [NAME.peer.json]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "engine/core/error.hpp"
#include "engine/io/gltf_loader.hpp"
#include "engine/scene/scene_loader.hpp"

namespace {

struct Bounds {
    glm::dvec3 lo{std::numeric_limits<double>::max()};
    glm::dvec3 hi{std::numeric_limits<double>::lowest()};
    void add(const glm::dvec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
};

// The vertices triangles use, placed by `transform` (tight bounds, not the transformed local box).
void addPlaced(const lp::MeshData& mesh, const glm::dmat4& transform, Bounds& b) {
    for (uint32_t i : mesh.indices) b.add(glm::dvec3(transform * glm::dvec4(glm::dvec3(mesh.vertices[i].position), 1.0)));
}

int failures = 0;
void check(bool ok, const std::string& what) {
    if (!ok) {
        std::fprintf(stderr, "peer_glb_check: %s\n", what.c_str());
        ++failures;
    }
}
std::string str(const glm::dvec3& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.7g, %.7g, %.7g)", v.x, v.y, v.z);
    return buf;
}
bool near3(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
    return glm::length(a - b) <= tolerance;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3 && argc != 4) {
        std::fprintf(stderr, "usage: peer_glb_check SCENE.json NAME.glb [NAME.peer.json]\n");
        return 2;
    }
    try {
        const lp::Scene scene = lp::loadScene(argv[1]);
        const lp::GltfContent glb = lp::loadGltf(argv[2]);

        size_t sceneTriangles = 0;
        Bounds sceneBounds, glbBounds;
        for (const auto& m : scene.models) {
            sceneTriangles += m.mesh.indices.size() / 3;
            addPlaced(m.mesh, glm::dmat4(m.transform), sceneBounds);
        }
        addPlaced(glb.mesh, glm::dmat4(1.0), glbBounds);  // the glTF loader bakes node transforms
        const size_t glbTriangles = glb.mesh.indices.size() / 3;
        check(glbTriangles == sceneTriangles,
              "triangles: GLB " + std::to_string(glbTriangles) + ", scene " + std::to_string(sceneTriangles));
        const double extent = std::max(1.0, glm::length(sceneBounds.hi - sceneBounds.lo));
        const double tolerance = 2e-6 * extent;  // float positions through a float transform
        check(near3(glbBounds.lo, sceneBounds.lo, tolerance) && near3(glbBounds.hi, sceneBounds.hi, tolerance),
              "bounds: GLB " + str(glbBounds.lo) + ".." + str(glbBounds.hi) + ", scene " + str(sceneBounds.lo) + ".." +
                  str(sceneBounds.hi));

        check(glb.cameras.size() == 1, "cameras: GLB has " + std::to_string(glb.cameras.size()) + ", expected 1");
        if (glb.cameras.size() == 1) {
            const lp::Camera &a = glb.cameras[0], &b = scene.camera;
            const glm::dvec3 fa = glm::normalize(glm::dvec3(a.target) - glm::dvec3(a.position));
            const glm::dvec3 fb = glm::normalize(glm::dvec3(b.target) - glm::dvec3(b.position));
            // The scene's up need not be orthogonal to the view: compare its part across the view.
            const glm::dvec3 ub = glm::normalize(glm::dvec3(b.up) - glm::dot(glm::dvec3(b.up), fb) * fb);
            check(near3(glm::dvec3(a.position), glm::dvec3(b.position), 1e-6 * std::max(1.0, glm::length(glm::dvec3(b.position)))),
                  "camera position: GLB " + str(glm::dvec3(a.position)) + ", scene " + str(glm::dvec3(b.position)));
            check(near3(fa, fb, 1e-6), "camera direction: GLB " + str(fa) + ", scene " + str(fb));
            check(near3(glm::normalize(glm::dvec3(a.up)), ub, 1e-6), "camera up: GLB " + str(glm::dvec3(a.up)) + ", scene " + str(ub));
            check(std::abs(a.fovYDegrees - b.fovYDegrees) <= 1e-4f * b.fovYDegrees,
                  "camera fov: GLB " + std::to_string(a.fovYDegrees) + ", scene " + std::to_string(b.fovYDegrees));
            check(std::abs(a.nearPlane - b.nearPlane) <= 1e-6f * b.nearPlane && std::abs(a.farPlane - b.farPlane) <= 1e-6f * b.farPlane,
                  "camera near/far: GLB " + std::to_string(a.nearPlane) + "/" + std::to_string(a.farPlane) + ", scene " +
                      std::to_string(b.nearPlane) + "/" + std::to_string(b.farPlane));
        }

        if (argc == 4) {
            std::ifstream in(argv[3]);
            check(bool(in), std::string(argv[3]) + ": cannot be read");
            if (in) {
                const nlohmann::json side = nlohmann::json::parse(in);
                check(side.at("triangles").get<size_t>() == sceneTriangles,
                      "sidecar triangles " + std::to_string(side.at("triangles").get<size_t>()) + ", scene " + std::to_string(sceneTriangles));
                const auto& bb = side.at("bounds");
                const glm::dvec3 lo(bb[0][0].get<double>(), bb[0][1].get<double>(), bb[0][2].get<double>());
                const glm::dvec3 hi(bb[1][0].get<double>(), bb[1][1].get<double>(), bb[1][2].get<double>());
                check(near3(lo, sceneBounds.lo, tolerance) && near3(hi, sceneBounds.hi, tolerance),
                      "sidecar bounds " + str(lo) + ".." + str(hi) + ", scene " + str(sceneBounds.lo) + ".." + str(sceneBounds.hi));
            }
        }
        if (failures) return 1;
        std::printf("peer glb ok: %zu triangles, bounds %s..%s, camera at %s\n", sceneTriangles, str(sceneBounds.lo).c_str(),
                    str(sceneBounds.hi).c_str(), str(glm::dvec3(scene.camera.position)).c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "peer_glb_check: %s\n", e.what());
        return 1;
    }
}
