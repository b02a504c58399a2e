// The G-buffer's texture bindings, its layouts, and the one API every pass reads it through.
//   depth     D32F      window depth: standard (near 0, far 1) or reversed-Z (near 1, far 0)
//   normal    depends on the normal format (below)
//   diffuse   SRGB8_A8  diffuse albedo kd, sRGB-encoded as the base colour's texture is: base (1 - metallic)
//                       (1 - dielectric F0) under GGX, base (1 - metallic) under Blinn-Phong
//                       (common/brdf.glsl materialDiffuseAlbedo) and for flat-lit materials. An 8-bit sRGB
//                       base colour comes back as it was (linear 8 bits lost 39 of the 256 codes: 1 to 6
//                       became black); writers encode and readers decode in GLSL through an RGBA8 view
//                       (bindGBuffer, gbufferDiffuse). Alpha (linear) 0 marks a flat-lit
//                       material, else holds the material's ambient occlusion (>= 1/255)
//   position  RGBA32F   eye-space position in xyz; absent when positions are rebuilt from depth
//   specular  RGBA16F   F0 = mix(dielectric F0, base, metallic) in rgb, Blinn-Phong shininess in a
//                       (gbufferEncodeShininess; the roughness's exponent: GGX alpha = sqrt(2 / (n + 2)))
//             (SRGB8_A8, colour only, for the seed-packed formats, which keep shininess with the normal)
//   texcoord  RG32F     texture coordinates (only when a debug view asks for them)
//   velocity  RG16F     uv_current - uv_previous, unjittered (only when a pass reads motion;
//                       common/velocity.glsl); read as a plain sampler by the passes that use it
//   fresnel   RG16F     Schlick's f90 and the diffuse layer's Fresnel shape (common/brdf.glsl's
//                       FresnelEnds), only when a material of the scene gives them
//                       (KHR_materials_specular) and the program is compiled with LP_GBUFFER_FRESNEL;
//                       it takes the material-input views' colour location and image unit (7), which
//                       those views, lighting nothing, never share with it. Without it f90 and the
//                       shape come from F0 (fresnelEndsOfF0)
//   clearcoat RGBA16    KHR_materials_clearcoat's layer (common/brdf.glsl's ClearcoatLayer), unorm: its
//                       weight w = clearcoat x Fresnel(V.Nc), sqrt of its GGX alpha, its normal Nc (eye
//                       space, octahedral x 0.5 + 0.5 in ba: 16 bits, 3e-5 rad, where half floats'
//                       1e-3 rad moved a smooth coat's highlight by 2%); only when an opaque material of the scene has a coat and the
//                       program is compiled with LP_GBUFFER_CLEARCOAT. It takes the texcoord view's
//                       colour location and image unit (4), which that view, lighting nothing, never
//                       shares with it; read on unit LP_BIND_CLEARCOAT. kd (diffuse) already holds the
//                       base's 1 - w; gbufferFresnel applies it to F0 and f90. Without it: no coat
// The layout is chosen by the #defines a program is compiled with (lp::gbufferDefines):
//   LP_GBUFFER_NORMAL_UNPACKED (default)  RGBA32F  xyz
//   LP_GBUFFER_NORMAL_SEED_PACKED         RGBA16F  (x, y, shininess); z = sqrt(1 - x² - y²) >= 0
//   LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED  RGBA16F  (x, y, ±shininess); the sign is z's
//   LP_GBUFFER_NORMAL_TWO_ANGLE           RG32F    (phi, cos theta)
//   LP_GBUFFER_NORMAL_OCT <16|24|32>      R16UI / R32UI: octahedral, two bits/2-bit snorm integers
//   LP_GBUFFER_POSITION_STORED (default), LP_GBUFFER_POSITION_DEPTH, LP_GBUFFER_POSITION_REVERSED_Z
// A shader that reads the G-buffer defines LP_GBUFFER_READ before including this file; it then gets
// the samplers (units LP_BIND_*) and gbufferIsBackground / gbufferNormal / gbufferPosition /
// gbufferEyeZ / gbufferDiffuse / gbufferSpecular / gbufferShininess. The pass sets uGbufferCamera.
#ifndef LP_GBUFFER_LAYOUT_GLSL
#define LP_GBUFFER_LAYOUT_GLSL
#define LP_BIND_DEPTH 0
#define LP_BIND_NORMAL 1
#define LP_BIND_DIFFUSE 2
#define LP_BIND_POSITION 3
#define LP_BIND_SPECULAR 4
#define LP_BIND_TEXCOORD 5
#define LP_BIND_HDR 6
#define LP_BIND_FRESNEL 15
#define LP_BIND_CLEARCOAT 21

#include "common/depth_reconstruct.glsl"
#include "common/tonemap.glsl"
#include "common/normal_encoding.glsl"

#if !defined(LP_GBUFFER_NORMAL_SEED_PACKED) && !defined(LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED) && \
    !defined(LP_GBUFFER_NORMAL_TWO_ANGLE) && !defined(LP_GBUFFER_NORMAL_OCT) && !defined(LP_GBUFFER_NORMAL_UNPACKED)
#define LP_GBUFFER_NORMAL_UNPACKED
#endif
#if defined(LP_GBUFFER_NORMAL_SEED_PACKED) || defined(LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED)
#define LP_GBUFFER_SHININESS_IN_NORMAL
#endif
#if defined(LP_GBUFFER_POSITION_DEPTH) || defined(LP_GBUFFER_POSITION_REVERSED_Z)
#define LP_GBUFFER_POSITION_FROM_DEPTH
#endif

// ---- encoding (gbuffer.frag writes these) ------------------------------------------------------
// The shininess channel is half float: exponents up to 2048 are stored as they are (integers
// exactly), above that logarithmically, 2048 + 1024 log2(n / 2048), so the roughness floor's
// n = 1.25e7 (roughness 0.02) fits with a relative error of n below 0.6% (alpha 0.3%).
float gbufferEncodeShininess(float n) {
    return n <= 2048.0 ? n : 2048.0 + 1024.0 * log2(n / 2048.0);
}
float gbufferDecodeShininess(float stored) {
    return stored <= 2048.0 ? stored : 2048.0 * exp2((stored - 2048.0) / 1024.0);
}
#ifdef LP_GBUFFER_NORMAL_OCT
const uint LP_OCT_BITS = uint(LP_GBUFFER_NORMAL_OCT) / 2u;
const float LP_OCT_MAX = float((1u << (LP_OCT_BITS - 1u)) - 1u);  // snorm scale: 127, 2047, 32767
// Two snorm integers k in [-m, m], stored as k + m in LP_OCT_BITS bits each.
uint gbufferEncodeNormalOct(vec3 n) {
    vec2 q = octahedralEncodeQuantized(n, float(LP_GBUFFER_NORMAL_OCT));
    uvec2 k = uvec2(round(q * LP_OCT_MAX) + LP_OCT_MAX);
    return k.x | (k.y << LP_OCT_BITS);
}
vec3 gbufferDecodeNormalOct(uint u) {
    uint mask = (1u << LP_OCT_BITS) - 1u;
    vec2 k = vec2(float(u & mask), float((u >> LP_OCT_BITS) & mask));
    return octahedralDecode((k - LP_OCT_MAX) / LP_OCT_MAX);
}
#else
// What the float normal target stores for unit normal n and Blinn-Phong exponent `shininess`.
vec4 gbufferEncodeNormal(vec3 n, float shininess) {
#if defined(LP_GBUFFER_NORMAL_SEED_PACKED)
    return vec4(seedPackedEncode(n), shininess, 0.0);
#elif defined(LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED)
    // A carrier of at least fp16's smallest normal number, so shininess 0 keeps a negative sign
    // (-1e-30 would round to -0 in the RGBA16F target and read back as not negative).
    return vec4(n.xy, n.z < 0.0 ? -max(shininess, 1.0 / 16384.0) : shininess, 0.0);
#elif defined(LP_GBUFFER_NORMAL_TWO_ANGLE)
    return vec4(twoAngleEncode(n), 0.0, 0.0);
#else
    return vec4(n, 0.0);
#endif
}
vec3 gbufferDecodeNormal(vec4 t) {
#if defined(LP_GBUFFER_NORMAL_SEED_PACKED)
    return seedPackedDecode(t.xy);
#elif defined(LP_GBUFFER_NORMAL_SEED_PACKED_SIGNED)
    return seedPackedSignedDecode(t.xy, t.z);
#elif defined(LP_GBUFFER_NORMAL_TWO_ANGLE)
    return twoAngleDecode(t.xy);
#else
    return t.xyz;
#endif
}
#endif

// Ambient occlusion in the diffuse target's alpha, kept above 0 (0 marks flat-lit materials).
float gbufferEncodeOcclusion(float occlusion) { return max(clamp(occlusion, 0.0, 1.0), 1.0 / 255.0); }

// ---- decoding (every pass that reads the G-buffer) ---------------------------------------------
#ifdef LP_GBUFFER_READ
layout(binding = LP_BIND_DEPTH) uniform sampler2D uGbufferDepth;
#ifdef LP_GBUFFER_NORMAL_OCT
layout(binding = LP_BIND_NORMAL) uniform usampler2D uGbufferNormal;
#else
layout(binding = LP_BIND_NORMAL) uniform sampler2D uGbufferNormal;
#endif
layout(binding = LP_BIND_DIFFUSE) uniform sampler2D uGbufferDiffuse;
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
layout(binding = LP_BIND_POSITION) uniform sampler2D uGbufferPosition;
#endif
layout(binding = LP_BIND_SPECULAR) uniform sampler2D uGbufferSpecular;
#ifdef LP_GBUFFER_FRESNEL
layout(binding = LP_BIND_FRESNEL) uniform sampler2D uGbufferFresnel;
#endif
#ifdef LP_GBUFFER_CLEARCOAT
layout(binding = LP_BIND_CLEARCOAT) uniform sampler2D uGbufferClearcoat;
#endif
uniform vec4 uGbufferCamera;  // near, far, tan(vertical fov / 2), width / height

float gbufferRawDepth(ivec2 p) { return texelFetch(uGbufferDepth, p, 0).r; }

// No geometry at p (the depth clear value: far plane).
bool gbufferIsBackground(ivec2 p) {
#ifdef LP_GBUFFER_POSITION_REVERSED_Z
    return gbufferRawDepth(p) <= 0.0;
#else
    return gbufferRawDepth(p) >= 1.0;
#endif
}

vec3 gbufferNormal(ivec2 p) {
#ifdef LP_GBUFFER_NORMAL_OCT
    return gbufferDecodeNormalOct(texelFetch(uGbufferNormal, p, 0).r);
#else
    return gbufferDecodeNormal(texelFetch(uGbufferNormal, p, 0));
#endif
}

// Eye-space z (negative in front of the camera) of the surface at p.
float gbufferEyeZ(ivec2 p) {
#if defined(LP_GBUFFER_POSITION_REVERSED_Z)
    return eyeZFromReversedDepth(gbufferRawDepth(p), uGbufferCamera.x, uGbufferCamera.y);
#elif defined(LP_GBUFFER_POSITION_DEPTH)
    return eyeZFromStandardDepth(gbufferRawDepth(p), uGbufferCamera.x, uGbufferCamera.y);
#else
    return texelFetch(uGbufferPosition, p, 0).z;
#endif
}

vec3 gbufferPosition(ivec2 p) {
#ifdef LP_GBUFFER_POSITION_FROM_DEPTH
    vec2 uv = (vec2(p) + 0.5) / vec2(textureSize(uGbufferDepth, 0));
    return eyePositionFromZ(uv, gbufferEyeZ(p), uGbufferCamera.z, uGbufferCamera.w);
#else
    return texelFetch(uGbufferPosition, p, 0).xyz;
#endif
}

// The sRGB targets are bound as RGBA8 views (bindGBuffer) and decoded here, exactly: a software
// rasteriser's sampler decodes sRGB by an approximation up to 0.4% off.
vec3 gbufferDiffuse(ivec2 p) { return srgbToLinear(texelFetch(uGbufferDiffuse, p, 0).rgb); }
// A flat-lit material (Material::flat): its radiance is its diffuse colour and no light adds to it.
// Needs the diffuse target bound (the lighting view does not read it: there every surface is lit).
bool gbufferIsFlat(ivec2 p) { return texelFetch(uGbufferDiffuse, p, 0).a < 0.5 / 255.0; }
// The material's ambient occlusion (1 without an occlusion map): scales ambient and IBL light only.
float gbufferOcclusion(ivec2 p) { return texelFetch(uGbufferDiffuse, p, 0).a; }
vec3 gbufferSpecular(ivec2 p) {
#ifdef LP_GBUFFER_SHININESS_IN_NORMAL
    return srgbToLinear(texelFetch(uGbufferSpecular, p, 0).rgb);  // the seed formats' sRGB F0
#else
    return texelFetch(uGbufferSpecular, p, 0).rgb;
#endif
}
float gbufferShininess(ivec2 p) {
#ifdef LP_GBUFFER_SHININESS_IN_NORMAL
    return gbufferDecodeShininess(abs(texelFetch(uGbufferNormal, p, 0).z));
#else
    return gbufferDecodeShininess(texelFetch(uGbufferSpecular, p, 0).a);
#endif
}
#ifdef LP_BRDF_GLSL
// The Fresnel ends at p (common/brdf.glsl, included before this file): the stored f90 and shape where
// the G-buffer carries them, else derived from F0 as every material without KHR_materials_specular has.
#ifdef LP_GBUFFER_FRESNEL
// The stored (f90, shape) and the ends they make with F0.
vec2 gbufferFresnelStored(ivec2 p) { return texelFetch(uGbufferFresnel, p, 0).rg; }
FresnelEnds gbufferFresnelEnds(vec3 f0, vec2 stored) { return FresnelEnds(f0, stored.x, vec3(stored.y)); }
#endif
// KHR_materials_clearcoat's layer at p (gbuffer.clearcoat), none without the target.
ClearcoatLayer gbufferClearcoat(ivec2 p) {
#ifdef LP_GBUFFER_CLEARCOAT
    vec4 c = texelFetch(uGbufferClearcoat, p, 0);
    return ClearcoatLayer(c.x, c.y * c.y, octahedralDecode(c.zw * 2.0 - 1.0));
#else
    return noClearcoat();
#endif
}
// The material's ends as stored (the base's, before the coat).
FresnelEnds gbufferMaterialFresnel(ivec2 p) {
#ifdef LP_GBUFFER_FRESNEL
    return gbufferFresnelEnds(gbufferSpecular(p), gbufferFresnelStored(p));
#else
    return fresnelEndsOfF0(gbufferSpecular(p));
#endif
}
// The ends the lights see: the base's under the coat (exactly the stored ones without a coat).
FresnelEnds gbufferFresnel(ivec2 p) {
#ifdef LP_GBUFFER_CLEARCOAT
    return clearcoatBaseEnds(gbufferMaterialFresnel(p), gbufferClearcoat(p));
#else
    return gbufferMaterialFresnel(p);
#endif
}
#endif
#endif  // LP_GBUFFER_READ

#endif
