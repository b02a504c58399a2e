#version 450
// One light at one pixel, added (blend ONE, ONE) into the HDR buffer. The same code
// serves the fullscreen, scissor and volumes methods; the tiled method runs the same function.
#include "common/local_light.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(std430, binding = 0) readonly buffer LocalLights { LpLocalLight uLights[]; };
uniform bool uLightingOnly;  // the lighting view: white albedo
uniform int uSpecularMode;   // LP_LOCAL_SPECULAR_*
flat in int vLight;
layout(location = 0) out vec4 oColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (gbufferIsBackground(p)) discard;  // background: no surface to light
    if (!uLightingOnly && gbufferIsFlat(p)) discard;  // flat-lit: no light adds to it
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec4 spec = vec4(gbufferSpecular(p), gbufferShininess(p));
    vec3 kd = uLightingOnly ? vec3(1.0) : gbufferDiffuse(p);
    float pl = length(P);
    vec3 V = pl > 0.0 ? -P / pl : vec3(0.0, 0.0, 1.0);
    LpLocalLight l = uLights[vLight];
    vec3 c = lpShadeLocalLight(l, P, N, V, kd, gbufferFresnel(p), spec.a, uSpecularMode, gbufferClearcoat(p));
    oColor = vec4(sanitizeHdr(c), 0.0);
}
