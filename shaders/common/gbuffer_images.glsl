// The G-buffer's colour targets as write-only images, for the compute passes that write them (the
// visibility resolve, and the classic pass's background: gbuffer_background.comp), and what a pixel
// where nothing is drawn holds. Defines: gbufferImageDefines (passes/gbuffer_pass.hpp), which sets
// the normal and specular targets' image formats; binding i = target i of bindGBufferImages.
// The sRGB targets (diffuse; the seed formats' specular) are bound as RGBA8 views of their storage
// (image units take no sRGB format): storeDiffuse and storeSpecular write the sRGB encoding, the
// bytes the raster's hardware encode writes there.
#ifndef LP_GBUFFER_IMAGES_GLSL
#define LP_GBUFFER_IMAGES_GLSL
#include "common/gbuffer_layout.glsl"
#include "common/tonemap.glsl"
#include "common/velocity.glsl"

layout(binding = 0, LP_NORMAL_IMAGE_FORMAT) uniform writeonly LP_NORMAL_IMAGE uNormalOut;
layout(binding = 1, rgba8) uniform writeonly image2D uDiffuseOut;  // SRGB8_ALPHA8 target
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
layout(binding = 2, rgba32f) uniform writeonly image2D uPositionOut;
#endif
layout(binding = 3, LP_SPECULAR_IMAGE_FORMAT) uniform writeonly image2D uSpecularOut;
#ifdef LP_GBUFFER_CLEARCOAT
layout(binding = 4, rgba16) uniform writeonly image2D uClearcoatOut;  // gbuffer.clearcoat: unit 4 outside the texcoords view
#else
layout(binding = 4, rg32f) uniform writeonly image2D uTexcoordOut;
#endif
layout(binding = 5, rgba16f) uniform writeonly image2D uTangentOut;
layout(binding = 6, rg16f) uniform writeonly image2D uVelocityOut;
#ifdef LP_GBUFFER_FRESNEL
layout(binding = 7, rg16f) uniform writeonly image2D uFresnelOut;  // gbuffer.fresnel: unit 7 outside the material-input views
#else
layout(binding = 7, rgba16f) uniform writeonly image2D uMaterialInputOut;
#endif
// Bit i set: target i (normal, diffuse, position, specular, texcoord or, with LP_GBUFFER_CLEARCOAT,
// clearcoat, tangent, velocity, material input or, with LP_GBUFFER_FRESNEL, fresnel) is bound.
uniform uint uTargets;
// Background velocity (common/velocity.glsl's backgroundVelocity).
uniform vec2 uJitterNdc;
uniform mat4 uInverseRotationProjection;
uniform mat4 uViewProjection;
uniform mat4 uPreviousViewProjection;

const uint LP_TARGET_NORMAL = 1u, LP_TARGET_DIFFUSE = 2u, LP_TARGET_POSITION = 4u, LP_TARGET_SPECULAR = 8u;
const uint LP_TARGET_TEXCOORD = 16u, LP_TARGET_TANGENT = 32u, LP_TARGET_VELOCITY = 64u, LP_TARGET_MATERIAL_INPUT = 128u;
const uint LP_TARGET_FRESNEL = 128u;  // the same unit: a program compiled with LP_GBUFFER_FRESNEL has no material input
const uint LP_TARGET_CLEARCOAT = 16u;  // the same unit: a program compiled with LP_GBUFFER_CLEARCOAT has no texcoord

void storeNormal(ivec2 p, vec3 n, float shininess) {
#ifdef LP_GBUFFER_NORMAL_OCT
    imageStore(uNormalOut, p, uvec4(gbufferEncodeNormalOct(n), 0u, 0u, 0u));
#else
    imageStore(uNormalOut, p, gbufferEncodeNormal(n, shininess));
#endif
}

// kd (linear) and the diffuse alpha (occlusion, 0 for flat-lit; alpha is not sRGB-encoded).
void storeDiffuse(ivec2 p, vec3 kd, float alpha) { imageStore(uDiffuseOut, p, vec4(linearToSrgb(kd), alpha)); }

// F0 (linear) and the encoded shininess; the seed formats' sRGB target keeps the colour alone.
void storeSpecular(ivec2 p, vec3 f0, float encodedShininess) {
#ifdef LP_GBUFFER_SHININESS_IN_NORMAL
    imageStore(uSpecularOut, p, vec4(linearToSrgb(f0), 0.0));
#else
    imageStore(uSpecularOut, p, vec4(f0, encodedShininess));
#endif
}

// What the classic pass leaves where no mesh is drawn: its clear values, and the background's motion.
void storeBackground(ivec2 p, vec2 size) {
#ifdef LP_GBUFFER_NORMAL_OCT
    if ((uTargets & LP_TARGET_NORMAL) != 0u) imageStore(uNormalOut, p, uvec4(0u));
#else
    if ((uTargets & LP_TARGET_NORMAL) != 0u) imageStore(uNormalOut, p, vec4(0.0));
#endif
    if ((uTargets & LP_TARGET_DIFFUSE) != 0u) imageStore(uDiffuseOut, p, vec4(0.0));
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    if ((uTargets & LP_TARGET_POSITION) != 0u) imageStore(uPositionOut, p, vec4(0.0));
#endif
    if ((uTargets & LP_TARGET_SPECULAR) != 0u) imageStore(uSpecularOut, p, vec4(0.0));
#ifdef LP_GBUFFER_CLEARCOAT
    if ((uTargets & LP_TARGET_CLEARCOAT) != 0u) imageStore(uClearcoatOut, p, vec4(0.0));
#else
    if ((uTargets & LP_TARGET_TEXCOORD) != 0u) imageStore(uTexcoordOut, p, vec4(0.0));
#endif
    if ((uTargets & LP_TARGET_TANGENT) != 0u) imageStore(uTangentOut, p, vec4(0.0));
#ifdef LP_GBUFFER_FRESNEL
    if ((uTargets & LP_TARGET_FRESNEL) != 0u) imageStore(uFresnelOut, p, vec4(0.0));
#else
    if ((uTargets & LP_TARGET_MATERIAL_INPUT) != 0u) imageStore(uMaterialInputOut, p, vec4(0.0));
#endif
    if ((uTargets & LP_TARGET_VELOCITY) != 0u) {
        vec2 ndc = (vec2(p) + 0.5) / size * 2.0 - 1.0;
        vec2 v = backgroundVelocity(ndc, uJitterNdc, uInverseRotationProjection, uViewProjection, uPreviousViewProjection);
        imageStore(uVelocityOut, p, vec4(v, 0.0, 0.0));
    }
}

#endif
