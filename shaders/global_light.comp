#version 450
// Directional lights with the chosen analytic BRDF (normalised Blinn-Phong or GGX), cascaded shadow
// maps, plus a constant ambient (times the ambient occlusion, when on), into the HDR buffer.
#include "common/sun_light.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba16f, binding = 0) uniform writeonly image2D uHdr;

uniform bool uLightingOnly;  // debug: white albedo, so the image shows light alone
// Ambient occlusion (passes/ambient_occlusion_pass): indirect light only, so the ambient term alone.
layout(binding = 14) uniform sampler2D uAo;
uniform bool uAmbientOcclusion;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uHdr);
    if (p.x >= size.x || p.y >= size.y) return;
    if (gbufferIsBackground(p)) {
        imageStore(uHdr, p, vec4(0.0));  // background: the sky pass fills it
        return;
    }
    if (!uLightingOnly && gbufferIsFlat(p)) {  // flat-lit: its colour, no light
        imageStore(uHdr, p, vec4(gbufferDiffuse(p), 1.0));
        return;
    }
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    float ao = uAmbientOcclusion ? texelFetch(uAo, p, 0).r : 1.0;
    vec3 c = uAmbient * kd * ao * (uLightingOnly ? 1.0 : gbufferOcclusion(p));  // occlusion darkens ambient light only
#if defined(LP_GBUFFER_FRESNEL) || defined(LP_GBUFFER_CLEARCOAT)
    c += lpSunRadiance(P, N, V, kd, gbufferFresnel(p), spec.a, vec2(p), gbufferClearcoat(p));
#else
    c += lpSunRadiance(P, N, V, kd, spec.rgb, spec.a, vec2(p), noClearcoat());  // the ends per sun, from F0
#endif
    imageStore(uHdr, p, vec4(sanitizeHdr(c), 1.0));
}
