// Sampled specular IBL (--ibl-specular sampled): the GGX lobe's shape at run time instead of the
// split sum's round lobe. The split sum reads the prefiltered chain once, along one direction, with a
// lobe prefiltered for N = V = R; at grazing view the true lobe is narrower across the plane of
// incidence and cut by the horizon, and a small bright lamp loses 8-9% of its reflection on rough
// spheres (bench/results/mitsuba/2026-11-24_ibl-against-mitsuba). Here each pixel draws `samples` directions L from the GGX
// distribution of visible normals (Heitz 2018) for its own V, one fixed Hammersley set for every pixel
// (no noise), and reads each from the prefiltered chain at the roughness whose lobe spans
// LP_SAMPLED_SUBLOBE_SPAN times the sample's solid angle 1 / (samples pdf(L)) (filtered importance
// sampling, Krivanek & Colbert 2008, with GGX sub-lobes instead of box-filtered texels: their sum is
// smooth where a tent of texels would show the sample pattern). The samples come from a lobe
// alpha' = sqrt(alpha^2 - alpha_s^2) narrower by the sub-lobe at its peak, so the sum of sub-lobes is
// about as wide as alpha's lobe. They give the lobe-weighted mean radiance only, split by Schlick's
// Fc into the DFG LUT's two terms; the magnitude stays the LUT's A and B, so a uniform environment
// returns F0 A + f90 B exactly at any sample count (white furnace) and Ks = 0 reflects nothing.
// bench/mitsuba/sampled_specular.py evaluates the same estimator on the CPU.
#ifndef LP_IBL_SAMPLED_GLSL
#define LP_IBL_SAMPLED_GLSL
#include "common/ibl.glsl"

// Each sample's sub-lobe spans this many times its solid angle (overlap of neighbouring samples).
const float LP_SAMPLED_SUBLOBE_SPAN = 2.0;

// Smith's Lambda for GGX at a direction of cosine c to the normal: G1 = 1 / (1 + Lambda).
float smithGgxLambda(float c, float alpha) {
    float c2 = max(c * c, 1e-12);
    return 0.5 * (sqrt(1.0 + alpha * alpha * (1.0 - c2) / c2) - 1.0);
}

// A microfacet normal from the GGX distribution of normals visible from Ve (tangent space, z = the
// normal, Ve.z > 0), for the point u in [0, 1)^2 (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals"). pdf(H) = G1(V) max(V.H, 0) D(H) / V.z.
vec3 sampleGgxVndf(vec3 Ve, float alpha, vec2 u) {
    vec3 Vh = normalize(vec3(alpha * Ve.x, alpha * Ve.y, Ve.z));
    float lensq = Vh.x * Vh.x + Vh.y * Vh.y;
    vec3 T1 = lensq > 0.0 ? vec3(-Vh.y, Vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
    vec3 T2 = cross(Vh, T1);
    float r = sqrt(u.x);
    float phi = 2.0 * LP_IBL_PI * u.y;
    float t1 = r * cos(phi), t2 = r * sin(phi);
    float s = 0.5 * (1.0 + Vh.z);
    t2 = (1.0 - s) * sqrt(max(1.0 - t1 * t1, 0.0)) + s * t2;
    vec3 Nh = t1 * T1 + t2 * T2 + sqrt(max(1.0 - t1 * t1 - t2 * t2, 0.0)) * Vh;
    return normalize(vec3(alpha * Nh.x, alpha * Nh.y, max(Nh.z, 0.0)));
}

// Schlick's Fc = (1 - V.H)^5. V.H can round above 1 where H is V: pow of a negative base is
// undefined (NaN on llvmpipe, which blacked out a pixel of a Lambertian furnace sphere).
float schlickFresnelWeight(float VdotH) { return pow(max(1.0 - VdotH, 0.0), 5.0); }

// The GGX alpha the samples are drawn from: alpha narrowed by the sub-lobe at the lobe's peak (whose
// pdf is 1 / (4 pi alpha^2)), so that samples widened by their sub-lobes span about alpha's lobe; at
// least alpha / 10 (1 or 2 samples: a near-delta lobe would only cost float precision).
float sampledSpecularAlpha(float alpha, int samples) {
    float peak = alpha * sqrt(min(LP_SAMPLED_SUBLOBE_SPAN / float(max(samples, 1)), 1.0));
    return sqrt(max(alpha * alpha - peak * peak, 0.01 * alpha * alpha));
}

// Sample i of `samples` for the view Ve (tangent space, z = the normal) and GGX alpha: the direction L
// (tangent space), the prefiltered chain's lod to read it at (of maxLod) and its weights towards the
// DFG LUT's A and B terms, (1 - Fc) f cos / pdf and Fc f cos / pdf, for the BRDF's Smith model
// `masking` (LP_SPECULAR_MASKING_*, common/brdf.glsl). Weights 0: below the surface.
void sampledSpecularSample(int i, int samples, vec3 Ve, float alpha, float maxLod, int masking, out vec3 L,
                           out float lod, out vec2 weights) {
    float n = float(max(samples, 1));
    float sampledAlpha = sampledSpecularAlpha(alpha, samples);
    float NdotV = max(Ve.z, 1e-4);
    float lambdaV = smithGgxLambda(NdotV, sampledAlpha);
    vec3 H = sampleGgxVndf(Ve, sampledAlpha, hammersley(uint(i), uint(samples)));
    float VdotH = dot(Ve, H);
    L = 2.0 * VdotH * H - Ve;
    lod = 0.0;
    weights = vec2(0.0);
    if (L.z <= 0.0 || VdotH <= 0.0) return;
    // f cos / pdf(L) = G2(V, L) / G1(V); pdf(L) = G1(V) D(H) / (4 N.V).
    float w = smithShadowingGivenMasking(masking, lambdaV, smithGgxLambda(L.z, sampledAlpha));
    float pdf = ggxD(H.z, sampledAlpha) / ((1.0 + lambdaV) * 4.0 * NdotV);
    float solidAngle = 1.0 / (n * max(pdf, 1e-20));
    float subAlpha = min(sqrt(LP_SAMPLED_SUBLOBE_SPAN * solidAngle / (4.0 * LP_IBL_PI)), alpha);
    lod = prefilteredLodFromRoughness(sqrt(subAlpha), maxLod);
    float fc = schlickFresnelWeight(VdotH);
    weights = w * vec2(1.0 - fc, fc);
}

// The lobe-weighted mean radiance of the prefiltered chain around a surface of shading normal N (the
// normal map's), geometric normal Ng (the triangle's, on the viewer's side), view V (world space, unit)
// and GGX alpha: `la` weighted by (1 - Fc) f cos, `lb` by Fc f cos (the DFG LUT's A and B terms), for
// the Smith model `masking`. A sample below the geometric surface (Ng.L <= 0) is light that cannot
// reach it: its weight stays in the totals and it brings no radiance, so a lobe that a normal map tilts
// through the surface loses what it loses in the path tracer (which ends such paths). Without the cut,
// those samples read the map below the plane as if it lit the surface: a normal-mapped gold quad came
// out +42% against the tracer under a window map, +80% under a smooth sky
// (bench/results/ibl/2026-12-08_against-the-path-tracer).
// Ng = N: no cut. False when no sample lies above the shading surface (then use the split sum).
bool sampledSpecularRadiance(samplerCube prefilteredMap, float maxLod, vec3 N, vec3 Ng, vec3 V, float alpha, int samples,
                             int masking, out vec3 la, out vec3 lb) {
    la = vec3(0.0);
    lb = vec3(0.0);
    vec3 T, B;
    basisAround(N, T, B);
    vec3 Ve = normalize(vec3(dot(V, T), dot(V, B), clamp(dot(N, V), 1e-4, 1.0)));
    vec2 total = vec2(0.0);
    for (int i = 0; i < samples; ++i) {
        vec3 L;
        float lod;
        vec2 w;
        sampledSpecularSample(i, samples, Ve, alpha, maxLod, masking, L, lod, w);
        if (w.x + w.y <= 0.0) continue;
        total += w;
        vec3 Lw = T * L.x + B * L.y + N * L.z;
        if (dot(Ng, Lw) <= 0.0) continue;  // below the geometric surface: occluded by it
        vec3 radiance = textureLod(prefilteredMap, Lw, lod).rgb;
        la += radiance * w.x;
        lb += radiance * w.y;
    }
    if (total.x <= 0.0) return false;
    la /= total.x;
    lb = total.y > 0.0 ? lb / total.y : la;
    return true;
}

#endif
