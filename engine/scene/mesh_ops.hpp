#pragma once
// Derived mesh data: area-weighted normals, tangents, bounds.
#include "engine/scene/mesh.hpp"

namespace lp {

// Area-weighted vertex normals: the sum of unnormalised face cross products over the faces that
// share each vertex. A vertex with no area around it gets +Y. Never NaN.
void computeNormals(MeshData& mesh);
// Per-vertex tangents from UVs (Lengyel), Gram-Schmidt against the normal, w = handedness. Where
// UVs are absent or degenerate, any unit tangent perpendicular to the normal (Duff et al. 2017).
void computeTangents(MeshData& mesh);
void computeBounds(MeshData& mesh);  // of the finite positions (none: zero)
// A unit vector perpendicular to unit n, continuous except on a measure-zero set, never 0/0
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
glm::vec3 anyPerpendicular(glm::vec3 n);
// Judged by the triangle's own size, never the model's: its area over its longest edge squared (in
// double, so edges of 1e20 do not overflow) is about the sine of its smallest angle. Below 1e-10 it
// is a sliver no rasteriser can shade; a 5 mm face beside a 20 km one keeps its angles and survives.
bool degenerateTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

}  // namespace lp
