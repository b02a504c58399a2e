#pragma once
// Perceptual GGX roughness for scene-file materials (`material.roughness`), stored as the
// Blinn-Phong exponent of the same lobe width, which is what the G-buffer carries.

namespace lp {

// Smallest perceptual roughness a material can have (GGX alpha = r^2 = 4e-4). The G-buffer's
// shininess channel holds it (shaders/common/gbuffer_layout.glsl gbufferEncodeShininess).
constexpr float kMinRoughness = 0.02f;

// The Blinn-Phong exponent of the same GGX width as perceptual roughness r: alpha = r^2 =
// sqrt(2 / (n + 2)) (shaders/common/ibl.glsl roughnessFromShininess); r = 1 gives 0, r = 0.02 1.25e7.
inline float shininessFromRoughness(float r) { return 2.0f / (r * r * r * r) - 2.0f; }

}  // namespace lp
