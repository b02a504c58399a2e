#version 450
#include "common/tonemap.glsl"
// The normal format and position mode come from gbuffer_layout.glsl's #defines.
#include "common/gbuffer_layout.glsl"
#include "common/velocity.glsl"

in vec3 vPosition;
in vec3 vNormal;
in vec2 vUv;
in vec4 vTangent;

uniform vec3 uDiffuse;
uniform vec3 uSpecular;
uniform float uShininess;
uniform bool uHasDiffuseMap;
uniform bool uFlat;  // flat-lit material: diffuse alpha 0 tells the light passes to leave it alone
uniform bool uHasBumpMap;
uniform float uBumpScale;
layout(binding = 0) uniform sampler2D uDiffuseMap;  // sRGB texture: sampled as linear
layout(binding = 1) uniform sampler2D uBumpMap;     // height map in r

#ifdef LP_GBUFFER_NORMAL_OCT
layout(location = 0) out uint outNormal;
#else
layout(location = 0) out vec4 outNormal;
#endif
layout(location = 1) out vec4 outDiffuse;
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
layout(location = 2) out vec4 outPosition;
#endif
layout(location = 3) out vec4 outSpecular;
layout(location = 4) out vec4 outTexcoord;
layout(location = 5) out vec4 outTangent;  // the tangent view: eye-space tangent x 0.5 + 0.5, handedness
#ifdef LP_GBUFFER_VELOCITY
in vec4 vCurrentClip;
in vec4 vPreviousClip;
layout(location = 6) out vec2 outVelocity;  // uv_current - uv_previous, unjittered (common/velocity.glsl)
#endif

void main() {
    vec3 N = vNormal;
    float len = length(N);
    N = len > 1e-20 ? N / len : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) N = -N;  // two-sided: thin walls are lit from either side
    if (uHasBumpMap) {
        // Height map -> normal: central differences in texture space, bent along the tangent frame.
        vec2 texel = 1.0 / vec2(textureSize(uBumpMap, 0));
        float hl = texture(uBumpMap, vUv - vec2(texel.x, 0)).r, hr = texture(uBumpMap, vUv + vec2(texel.x, 0)).r;
        float hd = texture(uBumpMap, vUv - vec2(0, texel.y)).r, hu = texture(uBumpMap, vUv + vec2(0, texel.y)).r;
        vec3 T = vTangent.xyz - N * dot(N, vTangent.xyz);
        float tl = length(T);
        if (tl > 1e-20) {
            T /= tl;
            vec3 B = cross(N, T) * (vTangent.w < 0.0 ? -1.0 : 1.0);
            vec3 bent = N - uBumpScale * 4.0 * ((hr - hl) * T + (hu - hd) * B);
            float bl = length(bent);
            if (bl > 1e-20) N = bent / bl;
        }
    }
    vec3 albedo = uDiffuse;
    if (uHasDiffuseMap) albedo *= texture(uDiffuseMap, vUv).rgb;
    float shininess = clamp(uShininess, 0.0, 10000.0);
#ifdef LP_GBUFFER_NORMAL_OCT
    outNormal = gbufferEncodeNormalOct(N);
#else
    outNormal = gbufferEncodeNormal(N, shininess);
#endif
    outDiffuse = vec4(clamp(albedo, 0.0, 1.0), uFlat ? 0.0 : 1.0);
#ifndef LP_GBUFFER_POSITION_FROM_DEPTH
    outPosition = vec4(vPosition, 1.0);
#endif
    outSpecular = vec4(clamp(uSpecular, 0.0, 1.0), shininess);
    outTexcoord = vec4(vUv, 0.0, 0.0);
    // The interpolated tangent made orthogonal to the shading normal (the frame bump mapping uses).
    vec3 T = vTangent.xyz - N * dot(N, vTangent.xyz);
    float tl = length(T);
    outTangent = vec4(tl > 1e-20 ? T / tl * 0.5 + 0.5 : vec3(0.5), vTangent.w < 0.0 ? 0.0 : 1.0);
#ifdef LP_GBUFFER_VELOCITY
    outVelocity = velocityFromClip(vCurrentClip, vPreviousClip);
#endif
}
