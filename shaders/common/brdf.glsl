// BRDFs. Radiance leaving a surface lit by a light of irradiance E (at normal incidence) from L:
//   Lo = f(N, V, L) * E * max(N.L, 0)
#ifndef LP_BRDF_GLSL
#define LP_BRDF_GLSL

const float LP_PI = 3.14159265358979;

// Energy-normalised Blinn-Phong: f = kd/pi + ks * (n + 8) / (8 pi) * (N.H)^n.
// The (n+8)/(8 pi) factor keeps the lobe's reflected energy roughly constant as n changes.
// Safe for n = 0 and n = 10000, for N.L or N.V at or below 0, and for V = -L (H undefined).
vec3 blinnPhongBrdf(vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess) {
    vec3 h = V + L;
    float hl = dot(h, h);
    vec3 H = hl > 1e-12 ? h * inversesqrt(hl) : N;
    float nh = clamp(dot(N, H), 0.0, 1.0);
    float n = clamp(shininess, 0.0, 10000.0);
    // pow(0, 0) is undefined in GLSL: exp2(n * log2(nh)) with nh = 0 and n = 0 must be 1.
    float lobe = (n == 0.0) ? 1.0 : (nh > 0.0 ? exp2(n * log2(nh)) : 0.0);
    return kd / LP_PI + ks * ((n + 8.0) / (8.0 * LP_PI)) * lobe;
}

vec3 blinnPhongRadiance(vec3 N, vec3 V, vec3 L, vec3 kd, vec3 ks, float shininess, vec3 irradiance) {
    float nl = dot(N, L);
    if (nl <= 0.0) return vec3(0.0);
    return blinnPhongBrdf(N, V, L, kd, ks, shininess) * irradiance * nl;
}

#endif
