#pragma once
// CPU side of the environment math, in double precision and without GL: the equirectangular
// mapping (the same convention as shaders/common/ibl.glsl), the order-2 spherical-harmonic
// projection of an environment map and its irradiance, and a brute-force irradiance integral the
// tests hold the SH against. Diffuse SH is computed here, on the CPU, from the equirectangular map.
#include <array>

#include <glm/glm.hpp>

#include "engine/io/image_io.hpp"

namespace lp {

using ShCoefficients = std::array<glm::dvec3, 9>;  // radiance, bands 0..2, order as in ibl.glsl

// Map direction for equirect coordinates (u, v) in [0, 1]^2: lightpass's one convention, the CPU's
// (light extraction, SH) and the shaders' (common/ibl.glsl: sky, cube, prefilter). v = 0 is the top
// row (+Y), v = 1 the bottom (-Y); u = 0.5 (the centre column) looks down -Z, where the default
// camera looks, and u grows to the right seen from inside: u = 0.75 is +X, 0.25 is -X, 0 and 1 +Z.
// So a map seen from inside reads as the flat image does, not mirrored (as in Blender and Poly
// Haven's previews; Blender and three.js put the centre at +X, Filament and Mitsuba at +Z).
glm::dvec3 equirectDirection(double u, double v);
// Rotation about +Y by `radians` (world = rotateY(map, rotation)).
glm::dvec3 rotateY(glm::dvec3 d, double radians);
// The 9 real SH basis functions at unit direction d.
std::array<double, 9> shBasis(glm::dvec3 d);

// Projects the map's radiance (rotated by `rotationDegrees` about +Y into world space) onto SH:
// L_lm = sum over texels of L Y_lm(d) dOmega, dOmega = (2 pi / W)(pi / H) sin(theta).
ShCoefficients projectEquirectSh(const ImageF& map, double rotationDegrees);
// Irradiance E(n) from radiance SH (Ramamoorthi & Hanrahan), clamped at 0 like the shader.
glm::dvec3 shIrradiance(const ShCoefficients& sh, glm::dvec3 n);
// E(n) = sum over texels with d.n > 0 of L (d.n) dOmega: the reference the SH is tested against.
glm::dvec3 bruteForceIrradiance(const ImageF& map, double rotationDegrees, glm::dvec3 n);

}  // namespace lp
