#version 450
// Environment debug views, exposed and tone-mapped like the final image (except the LUT):
//   1 environment: cube radiance in the view direction (background) or the mirror direction
//   2 irradiance:  E / pi (a white Lambertian surface's radiance) at the normal / view direction
//   3 prefiltered: prefiltered mip uMip in the mirror / view direction
//   4 dfg:         (A, B) of the split-sum LUT at each pixel's N.V and roughness; the background
//                  shows the whole LUT (x = N.V, y = roughness), raw
#include "common/ibl.glsl"
#include "common/tonemap.glsl"
#define LP_GBUFFER_READ
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 7) uniform samplerCube uEnvironment;
layout(binding = 8) uniform samplerCube uIrradiance;
layout(binding = 9) uniform samplerCube uPrefiltered;
layout(binding = 10) uniform sampler2D uDfg;
layout(rgba8, binding = 0) uniform writeonly image2D uLdr;

uniform int uMode;
uniform vec3 uSh[9];
uniform bool uDiffuseFromCube;
uniform mat3 uEyeToWorld;
uniform mat4 uInvProjection;
uniform float uIntensity;
uniform float uMip;
uniform float uExposureEV;
uniform int uOperator;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uLdr);
    if (p.x >= size.x || p.y >= size.y) return;
    bool background = gbufferIsBackground(p);
    vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 e = uInvProjection * vec4(ndc, 1.0, 1.0);
    vec3 viewEye = normalize(e.xyz / e.w);
    vec3 N = gbufferNormal(p);
    vec3 P = gbufferPosition(p);
    vec3 V = length(P) > 0.0 ? -normalize(P) : vec3(0.0, 0.0, 1.0);
    vec3 R = 2.0 * dot(N, V) * N - V;
    vec3 lookup = normalize(uEyeToWorld * (background ? viewEye : R));
    vec3 c;
    if (uMode == 4) {
        vec2 uv = background ? (vec2(p) + 0.5) / vec2(size)
                             : dfgLutCoordinate(clamp(dot(N, V), 0.0, 1.0), roughnessFromShininess(gbufferShininess(p)),
                                                textureSize(uDfg, 0).x);
        imageStore(uLdr, p, vec4(textureLod(uDfg, uv, 0.0).rg, 0.0, 1.0));
        return;
    }
    if (uMode == 1) c = textureLod(uEnvironment, lookup, 0.0).rgb;
    else if (uMode == 3) c = textureLod(uPrefiltered, lookup, uMip).rgb;
    else {
        vec3 n = normalize(uEyeToWorld * (background ? viewEye : N));
        c = (uDiffuseFromCube ? textureLod(uIrradiance, n, 0.0).rgb : shIrradiance(uSh, n)) / LP_IBL_PI;
    }
    c = applyExposure(c * uIntensity, uExposureEV);
    imageStore(uLdr, p, vec4(linearToSrgb(applyToneMap(c, uOperator)), 1.0));
}
