// The small, very bright sources taken out of the environment map at bake time
// (engine/render/ibl_lights.hpp), lit as distant discs with lightpass's GGX (D, Smith of the chosen
// masking, Schlick towards f90: common/brdf.glsl) and its diffuse layer (ggxDiffuse; under --brdf
// blinn-phong the IBL's kd (1 - Fss) / pi), so that residual map + sources shade a surface as the whole
// map would. No shadows: IBL is unshadowed.
#ifndef LP_IBL_LIGHTS_GLSL
#define LP_IBL_LIGHTS_GLSL
#include "common/brdf.glsl"

// GGX specular (D Vis F, no N.L) of a distant disc of angular radius asin(s) centred on unit D, for a
// surface with normal N and view V (all in one space). Seen through the half vector the disc is an
// ellipse of radius s / 2 in the plane of incidence and s / (2 N.V) across it (there the half vector
// turns 1 / (2 N.V) times as fast as L); a GGX lobe of alpha r / sqrt 2 shares a disc of radius r's
// half-energy radius. So D becomes an anisotropic GGX whose widths are alpha and those, added in
// quadrature (N.V floored at 0.05), with the anisotropic Smith visibility (uSpecularMasking's model). A source much
// smaller than the lobe leaves it as it is (a point light); a near-mirror reflects a highlight the size
// and shape of the disc's reflection instead of a pinpoint. D stays normalised, so the energy stays near
// the point light's at every view angle. (Karis 2013's representative point with its (alpha / alpha')^2 normalisation
// tripled a smooth plane's reflection of small lamps at grazing view against the exact split sum in
// test_ibl's grazing-plane scene; a round widening of s / (2 sqrt 2) left a roughness-0.05 plane's lamp
// reflections 23% dark against Mitsuba, a sliver narrower than a pixel; a round widening wide enough
// across spilled 16% of the lobe below the horizon: bench/results/mitsuba/2026-11-24_ibl-against-mitsuba/README.md.)
// Energy (test_ibl's ExtractedLightKeepsTheLobesEnergyAtEveryAngle): within 1% of the point light's at
// normal incidence; at grazing view (N.L 0.1) +7% for a 2.9-degree source on alpha 0.05, +2% on alpha 0.2.
// The lobe D Vis alone (no Fresnel, nothing hidden), and V.H for the caller's Fresnel: the base's
// specular below and KHR_materials_clearcoat's layer (lpIblRadiance) share it.
float environmentLightLobe(vec3 N, vec3 V, vec3 D, float sinRadius, float alpha, out float vh) {
    float nl = dot(N, D);
    vh = 0.0;
    if (nl <= 0.0) return 0.0;
    if (sinRadius <= 0.0) {
        vec3 Hp = brdfHalfVector(N, V, D);
        vh = clamp(dot(V, Hp), 0.0, 1.0);
        return ggxDistribution(N, Hp, alpha) * ggxVisibility(dot(N, V), nl, alpha);
    }
    float nv = max(dot(N, V), LP_GGX_MIN_NV);
    float a = max(alpha, LP_GGX_MIN_ALPHA);
    float s2 = 0.125 * sinRadius * sinRadius;
    float along = sqrt(a * a + s2);
    float across = sqrt(a * a + s2 / max(nv * nv, 0.0025));
    vec3 h = V + D;
    float hl = dot(h, h);
    vec3 H = hl > 1e-12 ? h * inversesqrt(hl) : N;
    float nh = dot(N, H);
    if (nh <= 0.0) return 0.0;
    // The plane of incidence: the tangential part of V - D (V's and D's are opposite near the mirror).
    vec3 t = (V - D) - dot(V - D, N) * N;
    float tl = dot(t, t);
    vec3 T = tl > 1e-12 ? t * inversesqrt(tl) : normalize(cross(N, abs(N.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
    if (tl <= 1e-12) across = along;  // V and D along N: nothing to tell the axes apart
    vec3 B = cross(N, T);
    float x = dot(H, T) / along, y = dot(H, B) / across;
    float d = x * x + y * y + nh * nh;
    float distribution = 1.0 / (LP_PI * along * across * max(d * d, 1e-30));
    // Smith with each direction's own projected alpha (Heitz 2014, anisotropic).
    float lv = length(vec3(along * dot(V, T), across * dot(V, B), nv));
    float ll = length(vec3(along * dot(D, T), across * dot(D, B), nl));
    float visibility = smithVisibilityFromLengths(uSpecularMasking, nv, nl, lv, ll);
    vh = clamp(dot(V, H), 0.0, 1.0);
    return distribution * visibility;
}
vec3 environmentLightSpecular(vec3 N, vec3 V, vec3 D, float sinRadius, FresnelEnds f0, float alpha) {
    float vh;
    float lobe = environmentLightLobe(N, V, D, sinRadius, alpha, vh);
    return lobe * fresnelSchlick(f0, vh) * lpSpecularShown();
}
vec3 environmentLightSpecular(vec3 N, vec3 V, vec3 D, float sinRadius, vec3 f0, float alpha) {
    return environmentLightSpecular(N, V, D, sinRadius, fresnelEndsOfF0(f0), alpha);
}

// Radiance one source reflects: the diffuse layer as a sun's (ggxDiffuse at the disc's centre; kd
// (1 - fss) / pi under --brdf blinn-phong) and the specular above, times E N.L at the disc's centre;
// `ao` darkens the diffuse and `specularAo` the specular, as for the IBL terms.
vec3 environmentLightRadiance(vec3 N, vec3 V, vec3 D, float sinRadius, vec3 E, vec3 kd, FresnelEnds f0, float alpha,
                              vec3 fss, float ao, float specularAo) {
    float nl = dot(N, D);
    if (nl <= 0.0) return vec3(0.0);
    vec3 diffuse = uBrdf == LP_BRDF_BLINN_PHONG ? kd * (1.0 - fss) / LP_PI
                                                : ggxDiffuse(kd, f0, clamp(dot(V, brdfHalfVector(N, V, D)), 0.0, 1.0));
    vec3 specular = environmentLightSpecular(N, V, D, sinRadius, f0, alpha);
    return (ao * diffuse + specularAo * specular) * E * nl;
}

#endif
