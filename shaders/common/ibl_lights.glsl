// The small, very bright sources taken out of the environment map at bake time
// (engine/render/ibl_lights.hpp), lit as distant discs with lightpass's GGX (D, height-correlated
// Smith, Schlick towards f90: common/brdf.glsl) and the IBL's diffuse kd (1 - Fss) / pi, so that
// residual map + sources shade a surface as the whole map would. No shadows: IBL is unshadowed.
#ifndef LP_IBL_LIGHTS_GLSL
#define LP_IBL_LIGHTS_GLSL
#include "common/brdf.glsl"

// GGX alpha of a surface of alpha `alpha` lit by a distant disc of angular radius asin(sinRadius): the
// disc, seen through the half vector, is a disc of radius sinRadius / 2 (at normal incidence), whose
// half-energy radius a GGX lobe of alpha sinRadius / (2 sqrt 2) shares; the two widths add in
// quadrature. A source much smaller than the lobe leaves alpha as it is (a point light), and a
// near-mirror surface shows a highlight about the disc's size instead of a pinpoint. Widening D keeps
// it normalised, so the reflected energy is right at every view angle; Karis 2013's representative
// point with its (alpha / alpha')^2 normalisation holds energy only near normal incidence (at grazing
// view it tripled a smooth plane's reflection of a small lamp).
float environmentLightAlpha(float alpha, float sinRadius) {
    return sqrt(alpha * alpha + 0.125 * sinRadius * sinRadius);
}

// GGX specular (D Vis F, no N.L) of a distant disc of angular radius asin(sinRadius) centred on unit D,
// for a surface with normal N and view V (all in one space), alpha widened by the disc.
vec3 environmentLightSpecular(vec3 N, vec3 V, vec3 D, float sinRadius, vec3 f0, float alpha) {
    return ggxSpecular(N, V, D, f0, environmentLightAlpha(alpha, sinRadius));
}

// Radiance one source reflects: diffuse kd (1 - fss) / pi and the specular above, times E N.L at the
// disc's centre; `ao` darkens the diffuse and `specularAo` the specular, as for the IBL terms.
vec3 environmentLightRadiance(vec3 N, vec3 V, vec3 D, float sinRadius, vec3 E, vec3 kd, vec3 f0, float alpha,
                              vec3 fss, float ao, float specularAo) {
    float nl = dot(N, D);
    if (nl <= 0.0) return vec3(0.0);
    vec3 diffuse = kd * (1.0 - fss) / LP_PI;
    vec3 specular = environmentLightSpecular(N, V, D, sinRadius, f0, alpha);
    return (ao * diffuse + specularAo * specular) * E * nl;
}

#endif
