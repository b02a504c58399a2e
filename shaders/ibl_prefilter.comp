#version 450
// One mip of the prefiltered specular cube: radiance convolved with the GGX lobe for N = V = R,
// by importance sampling with filtered importance sampling (Krivanek & Colbert 2008): each sample
// reads the source at the mip whose texel solid angle matches the sample's, so a tiny bright sun
// is integrated over its footprint instead of being hit by a few samples (no fireflies).
#include "common/ibl.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube uSource;
layout(rgba16f, binding = 0) uniform writeonly imageCube uOut;
uniform int uSize;            // this mip's face size
uniform float uRoughness;     // perceptual
uniform int uSamples;
uniform int uSourceSize;      // face size of the source's mip 0
uniform float uSourceMaxLod;

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= uSize || p.y >= uSize) return;
    vec3 N = cubeTexelDirection(p.z, p.xy, uSize);
    vec3 T, B;
    basisAround(N, T, B);
    float alpha = uRoughness * uRoughness;
    float texelSolidAngle = 4.0 * LP_IBL_PI / (6.0 * float(uSourceSize * uSourceSize));
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    uint n = uint(uSamples);
    for (uint i = 0u; i < n; ++i) {
        vec3 h = importanceSampleGgx(hammersley(i, n), alpha);
        vec3 H = T * h.x + B * h.y + N * h.z;
        float NdotH = h.z;
        vec3 L = 2.0 * NdotH * H - N;
        float NdotL = dot(N, L);
        if (NdotL <= 0.0) continue;
        // pdf(L) = D(h) N.H / (4 V.H) with V = N: D / 4.
        float pdf = ggxD(NdotH, alpha) * 0.25;
        float sampleSolidAngle = 1.0 / (float(n) * pdf + 1e-12);
        float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0, uSourceMaxLod);
        sum += textureLod(uSource, L, lod).rgb * NdotL;
        weight += NdotL;
    }
    imageStore(uOut, p, vec4(sanitizeHdr(weight > 0.0 ? sum / weight : vec3(0.0)), 1.0));
}
