// Shading of one ranged point light, shared by the four local-light methods (full screen, scissor,
// volumes, tiled) so they produce the same image. Positions are eye space.
#ifndef LP_LOCAL_LIGHT_GLSL
#define LP_LOCAL_LIGHT_GLSL
#include "common/attenuation.glsl"
#include "common/brdf.glsl"

// One light as the SSBO holds it (std430; matches GpuLocalLight in engine/render/local_lights.hpp).
struct LpLocalLight {
    vec4 positionRange;  // xyz eye-space position, w range (m)
    vec4 intensity;      // rgb radiant intensity (colour x intensity), w unused
};

const int LP_LOCAL_SPECULAR_OFF = 0;      // diffuse only
const int LP_LOCAL_SPECULAR_RANGED = 1;   // diffuse and specular both limited by the range window
const int LP_LOCAL_SPECULAR_UNRANGED = 2; // seed 003's extra mode: specular keeps 1/d^2 past the range

// Radiance a surface point P (normal N, view direction V) reflects from the light.
vec3 lpLocalLightRadiance(vec3 lightPos, float range, vec3 intensity, vec3 P, vec3 N, vec3 V, vec3 kd, vec3 ks,
                          float shininess, int specularMode) {
    vec3 toLight = lightPos - P;
    float d = length(toLight);
    // A light exactly on the surface: light it from the normal (N.L = 1), the limit of a light
    // approaching along the normal.
    vec3 L = d > 0.0 ? toLight / d : N;
    float window = lpRangeWindow(d, range);
    vec3 e = intensity * lpInverseSquare(d, range);  // unwindowed irradiance
    if (specularMode == LP_LOCAL_SPECULAR_RANGED) return blinnPhongRadiance(N, V, L, kd, ks, shininess, e * window);
    vec3 c = window > 0.0 ? blinnPhongRadiance(N, V, L, kd, vec3(0.0), shininess, e * window) : vec3(0.0);
    if (specularMode == LP_LOCAL_SPECULAR_UNRANGED) c += blinnPhongRadiance(N, V, L, vec3(0.0), ks, shininess, e);
    return c;
}

#endif
