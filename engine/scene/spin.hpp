#pragma once
// A scene file's "spin" as an animation: one node at the mesh's origin whose rotation turns about an
// axis at a constant speed, so that a spinning OBJ, primitive or static glTF moves through the same
// path as glTF animation (posing, motion vectors, shadow-cache invalidation, the path tracer).
#include <glm/glm.hpp>

#include "engine/scene/animation.hpp"
#include "engine/scene/mesh.hpp"

namespace lp {

// A clip "spin" of period 2 pi / |speed| seconds that turns every vertex of `mesh` about `axis` (unit)
// by speed x t radians at time t (keys every quarter turn, slerped; the clip loops). speed != 0.
NodeAnimation spinAnimation(const MeshData& mesh, glm::vec3 axis, float speed);

}  // namespace lp
