#pragma once
// Generated meshes with analytic normals and tangents: counter-clockwise front faces from outside.
#include "engine/scene/mesh.hpp"

namespace lp {

MeshData makePlane(float size, int subdivisions = 1);  // XZ plane at y = 0, normal +Y, UV 0..1
MeshData makeSphere(float radius, int segments, int rings);
MeshData makeCube(float size);

}  // namespace lp
