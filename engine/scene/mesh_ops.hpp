#pragma once
// Derived mesh data: area-weighted normals, tangents, bounds.
#include "engine/scene/mesh.hpp"

namespace lp {

// Area-weighted vertex normals: the sum of unnormalised face cross products over the faces that
// share each vertex. A vertex with no area around it gets +Y. Never NaN.
void computeNormals(MeshData& mesh);
// MikkTSpace-compatible tangents (Mikkelsen 2008; the rules of the reference mikktspace.c at its
// default 180-degree threshold), so that a normal map baked for glTF shades without seams:
// vertices are identified by position, normal and uv (bit for bit); each triangle's tangent is the
// unit direction of increasing u; at each vertex, the triangles of one UV orientation connected
// through edges at the vertex form a group whose tangent is the sum of their tangents projected into
// the vertex's tangent plane, weighted by the corner angles there, normalised; w = +1 where the UV
// mapping keeps the winding, -1 where it mirrors it (the bitangent cross(N, T) w points along +v).
// A vertex whose corners fall into different groups is split (mesh.vertices grows, indices are
// rewritten). Triangles with no UV area join their neighbours' group; a vertex with no usable UV
// mapping gets any unit tangent perpendicular to its normal (Duff et al. 2017).
// `copiedFrom`, when given, gets one entry a vertex the call appended (a vertex split by a break in its
// tangent frame): the vertex it copies (the glTF loader follows each vertex back to its accessor element).
void computeTangents(MeshData& mesh, std::vector<uint32_t>* copiedFrom = nullptr);
void computeBounds(MeshData& mesh);  // of the finite positions (none: zero)
// A unit vector perpendicular to unit n, continuous except on a measure-zero set, never 0/0
// (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
glm::vec3 anyPerpendicular(glm::vec3 n);
// Judged by the triangle's own size, never the model's: its area over its longest edge squared (in
// double, so edges of 1e20 do not overflow) is about the sine of its smallest angle. Below 1e-10 it
// is a sliver no rasteriser can shade; a 5 mm face beside a 20 km one keeps its angles and survives.
bool degenerateTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
// KHR_materials_variants: every sub-mesh draws its material for `variant` (one of
// mesh.materialVariants; "" the file's own materials). False, and nothing changed, when the mesh has
// no variant of that name.
bool selectMaterialVariant(MeshData& mesh, const std::string& variant);
// The variants' names quoted and joined ("'red', 'blue'"), for messages; "" when it has none.
std::string materialVariantList(const MeshData& mesh);

}  // namespace lp
