#version 450
// HDR -> display: exposure, the chosen tone map (default pow(c / (c + 1), 1.2)), sRGB encoding, into
// an RGBA8 image, quantised with dither (common/dither.glsl) unless uDither is off. With
// LP_TONEMAP_FLOAT_TARGET (FXAA follows) the sRGB-encoded values go unquantised into RGBA16F and the
// FXAA pass does the one 8-bit quantisation.
#include "common/tonemap.glsl"
#include "common/gbuffer_layout.glsl"
#include "common/dither.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = LP_BIND_HDR) uniform sampler2D uHdr;
#ifdef LP_TONEMAP_FLOAT_TARGET
layout(rgba16f, binding = 0) uniform writeonly image2D uLdr;
#else
layout(rgba8, binding = 0) uniform writeonly image2D uLdr;
#endif
uniform float uExposureEV;      // exposureEvBase(): --exposure, plus a scene's fixed exposure when not metered
uniform bool uAutoExposure;
layout(binding = 7) uniform sampler2D uExposure;  // auto_exposure's 1x1 EV
uniform int uOperator;  // lp::ToneMapOperator: 0 lightpass, 1 aces, 2 pbr-neutral, 3 agx, 4 aces-legacy
uniform bool uDither;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uLdr);
    if (p.x >= size.x || p.y >= size.y) return;
    float ev = uExposureEV + (uAutoExposure ? texelFetch(uExposure, ivec2(0), 0).r : 0.0);
    vec3 c = applyExposure(texelFetch(uHdr, p, 0).rgb, ev);
    vec3 encoded = linearToSrgb(applyToneMap(c, uOperator));
#ifndef LP_TONEMAP_FLOAT_TARGET
    encoded = quantize8(encoded, p, uDither);
#endif
    imageStore(uLdr, p, vec4(encoded, 1.0));
}
