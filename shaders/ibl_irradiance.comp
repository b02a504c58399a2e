#version 450
// Irradiance cubemap E(n) = integral of L cos over the hemisphere around n, by cosine-weighted
// sampling (E = pi * mean L) with filtered importance sampling against the source's mips.
#include "common/ibl.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube uSource;
layout(rgba16f, binding = 0) uniform writeonly imageCube uOut;
uniform int uSize;
uniform int uSamples;
uniform int uSourceSize;
uniform float uSourceMaxLod;

void main() {
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (p.x >= uSize || p.y >= uSize) return;
    vec3 N = cubeTexelDirection(p.z, p.xy, uSize);
    vec3 T, B;
    basisAround(N, T, B);
    float texelSolidAngle = 4.0 * LP_IBL_PI / (6.0 * float(uSourceSize * uSourceSize));
    uint n = uint(uSamples);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) {
        vec2 xi = hammersley(i, n);
        float phi = 2.0 * LP_IBL_PI * xi.x;
        float cosTheta = sqrt(1.0 - xi.y), sinTheta = sqrt(xi.y);
        vec3 L = T * (sinTheta * cos(phi)) + B * (sinTheta * sin(phi)) + N * cosTheta;
        float pdf = cosTheta / LP_IBL_PI;
        float sampleSolidAngle = 1.0 / (float(n) * pdf + 1e-12);
        float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 1.0, 0.0, uSourceMaxLod);
        sum += textureLod(uSource, L, lod).rgb;
    }
    imageStore(uOut, p, vec4(sanitizeHdr(LP_IBL_PI * sum / float(n)), 1.0));
}
