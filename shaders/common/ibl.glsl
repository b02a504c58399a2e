// Image-based lighting math shared by the bake kernels, the IBL pass and the shader tests.
// Conventions (world space, +Y up):
//   equirect: u = atan(d.x, -d.z) / (2 pi) + 0.5, v = acos(d.y) / pi (v = 0 is the top row, +Y):
//     the centre column looks down -Z and u grows to the right seen from inside (+X at u = 0.75), so
//     the map reads as the flat image, not mirrored; engine/render/ibl_sh.hpp equirectDirection is
//     the same on the CPU (light extraction, SH)
//   cube faces: the GL layer order +X -X +Y -Y +Z -Z, texel (i, j) of a face as imageStore sees it
//   roughness: perceptual r, GGX alpha = r^2; Blinn-Phong shininess n maps to alpha = sqrt(2 / (n + 2))
#ifndef LP_IBL_GLSL
#define LP_IBL_GLSL
#include "common/brdf.glsl"

const float LP_IBL_PI = 3.14159265358979;

vec2 equirectUv(vec3 d) {
    return vec2(atan(d.x, -d.z) / (2.0 * LP_IBL_PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / LP_IBL_PI);
}

vec3 equirectDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * LP_IBL_PI, theta = uv.y * LP_IBL_PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// Unit direction through point (s, t) in [-1, 1]^2 of cube face `face` (GL convention: t grows
// downwards in the face image).
vec3 cubeDirection(int face, vec2 st) {
    float s = st.x, t = st.y;
    vec3 d;
    if (face == 0) d = vec3(1.0, -t, -s);
    else if (face == 1) d = vec3(-1.0, -t, s);
    else if (face == 2) d = vec3(s, 1.0, t);
    else if (face == 3) d = vec3(s, -1.0, -t);
    else if (face == 4) d = vec3(s, -t, 1.0);
    else d = vec3(-s, -t, -1.0);
    return normalize(d);
}

// Direction through the centre of texel `texel` of a face of `size` x `size`.
vec3 cubeTexelDirection(int face, ivec2 texel, int size) {
    return cubeDirection(face, (vec2(texel) + 0.5) / float(size) * 2.0 - 1.0);
}

// Solid angle of texel `texel` of a cube face of `size` x `size` (every face alike). Exact
// (the area element integrated, atan(xy / sqrt(x^2 + y^2 + 1)) at the corners) on small faces; on
// faces of 64 and more the midpoint rule h^2 / (1 + s^2 + t^2)^1.5 (relative error below 1e-3),
// since the four-corner difference cancels to float noise there.
float cubeTexelSolidAngle(ivec2 texel, int size) {
    float h = 2.0 / float(size);
    vec2 lo = vec2(texel) * h - 1.0, hi = lo + h;
    if (size >= 64) {
        vec2 c = 0.5 * (lo + hi);
        float r2 = 1.0 + dot(c, c);
        return h * h / (r2 * sqrt(r2));
    }
    float a00 = atan(lo.x * lo.y, sqrt(dot(lo, lo) + 1.0));
    float a01 = atan(lo.x * hi.y, sqrt(lo.x * lo.x + hi.y * hi.y + 1.0));
    float a10 = atan(hi.x * lo.y, sqrt(hi.x * hi.x + lo.y * lo.y + 1.0));
    float a11 = atan(hi.x * hi.y, sqrt(dot(hi, hi) + 1.0));
    return a00 - a01 - a10 + a11;
}

// Rotation of the environment about +Y by `radians` (world direction -> map direction uses -angle).
vec3 rotateY(vec3 d, float radians) {
    float c = cos(radians), s = sin(radians);
    return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}

// Van der Corput radical inverse / Hammersley point i of n.
float radicalInverseVdC(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}
vec2 hammersley(uint i, uint n) { return vec2((float(i) + 0.5) / float(n), radicalInverseVdC(i)); }

// Orthonormal basis around n (Duff et al. 2017), for tangent-space samples.
void basisAround(vec3 n, out vec3 t, out vec3 b) {
    float sgn = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + sgn * n.x * n.x * a, sgn * c, -sgn * n.x);
    b = vec3(c, sgn + n.y * n.y * a, -n.y);
}

// GGX normal distribution D(h) for alpha.
float ggxD(float NdotH, float alpha) {
    float a2 = alpha * alpha;
    float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
    return a2 / (LP_IBL_PI * d * d);
}

// Half vector (tangent space, z = normal) distributed by D(h) (N.H): pdf(h) = D(h) N.H.
vec3 importanceSampleGgx(vec2 xi, float alpha) {
    float a2 = alpha * alpha;
    float phi = 2.0 * LP_IBL_PI * xi.x;
    // sin^2 = a2 xi / d directly, not 1 - cos^2: the difference cancels to a few ulps of noise at
    // alpha -> 0 (NVIDIA's fast division), tilting H by ~3e-4 rad where N.V ~ 1e-4 makes the
    // estimator V.H / N.V swing by 4x. This form gives H = N exactly at alpha = 0.
    float d = max(1.0 + (a2 - 1.0) * xi.y, 1e-30);
    float cosTheta = sqrt(clamp((1.0 - xi.y) / d, 0.0, 1.0));
    float sinTheta = sqrt(clamp(a2 * xi.y / d, 0.0, 1.0));
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// The BRDF's Smith visibility (common/brdf.glsl's, model `masking`) without its alpha floor: the LUT's
// row of roughness 0 holds the mirror's exact limit (A + B = 1 at every N.V, also at N.V = 1e-4 where
// alpha 1e-3 would not be a mirror yet).
float dfgVisibility(int masking, float NdotV, float NdotL, float alpha) {
    float a2 = alpha * alpha;
    return smithVisibilityFromLengths(masking, NdotV, NdotL, sqrt(NdotV * NdotV * (1.0 - a2) + a2),
                                      sqrt(NdotL * NdotL * (1.0 - a2) + a2));
}

// The split-sum DFG terms (Karis 2013): specular reflectance of a white environment is
// F0 * A + B with A = integral of (1 - Fc) f cos, B = integral of Fc f cos, Fc = (1 - V.H)^5.
// N.V is clamped to 1e-4 (a view exactly along the surface has a finite limit). `masking`: the Smith
// model of the BRDF (LP_SPECULAR_MASKING_*, common/brdf.glsl).
vec2 dfgIntegrate(float NdotV, float roughness, uint samples, int masking) {
    NdotV = clamp(NdotV, 1e-4, 1.0);
    float alpha = roughness * roughness;
    vec3 V = vec3(sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    vec2 ab = vec2(0.0);
    for (uint i = 0u; i < samples; ++i) {
        vec3 H = importanceSampleGgx(hammersley(i, samples), alpha);
        float VdotH = dot(V, H);
        vec3 L = 2.0 * VdotH * H - V;
        float NdotL = L.z;
        if (NdotL <= 0.0 || VdotH <= 0.0) continue;
        // f cos / pdf(L), pdf(L) = D N.H / (4 V.H): = V_vis * 4 N.L V.H / N.H
        float w = dfgVisibility(masking, NdotV, NdotL, alpha) * 4.0 * NdotL * VdotH / max(H.z, 1e-12);
        float fc = pow(1.0 - VdotH, 5.0);
        ab += vec2((1.0 - fc) * w, fc * w);
    }
    return ab / float(samples);
}

// The DFG LUT's grid includes its ends: texel i of `size` holds the parameter i / (size - 1), and a
// lookup maps [0, 1] onto the texel centres, so N.V and roughness 0 and 1 are stored, not clamped
// half a texel in (at 32^2, roughness 1 used to read the row of 0.984: +3% white-furnace albedo at alpha 1).
vec2 dfgLutTexelParameters(ivec2 texel, int size) {
    return vec2(texel) / float(max(size - 1, 1));
}
vec2 dfgLutCoordinate(float NdotV, float roughness, int size) {
    return (clamp(vec2(NdotV, roughness), 0.0, 1.0) * float(size - 1) + 0.5) / float(size);
}

// Where a GGX lobe of roughness alpha around the mirror direction R gathers most of its energy:
// it leans from R (smooth) towards N (rough). Filament's fit, mix(R, N, alpha^2): Frostbite's
// (Lagarde & de Rousiers 2014) bends near-mirror lobes too far, which moved a sharp sun's reflection
// in the Mitsuba comparison (bench/mitsuba).
vec3 specularDominantDirection(vec3 N, vec3 R, float alpha) {
    vec3 d = mix(R, N, clamp(alpha * alpha, 0.0, 1.0));
    float l = length(d);
    return l > 0.0 ? d / l : N;
}

// Prefiltered chain: which mip holds perceptual roughness r, and back (Filament's perceptual
// mapping, lod = maxLod * r (2 - r)). Levels are dense where the lobe changes fastest (near-mirror):
// with 6 levels they hold r = 0, 0.106, 0.225, 0.368, 0.553, 1 instead of steps of 0.2, whose blend
// of a mirror and an r = 0.2 lobe pulled lamps above the horizon into a smooth plane at grazing angles.
float prefilteredLodFromRoughness(float r, float maxLod) {
    r = clamp(r, 0.0, 1.0);
    return maxLod * r * (2.0 - r);
}
float roughnessOfPrefilteredLod(float lod, float maxLod) {
    return maxLod > 0.0 ? 1.0 - sqrt(max(1.0 - lod / maxLod, 0.0)) : 0.0;
}

// The split sum's specular reflectance F0 A + f90 B, with f90 as the analytic GGX's Schlick term
// (shaders/common/brdf.glsl's FresnelEnds: clamp(50 mean(F0), 0, 1), or KHR_materials_specular's
// weight), so that Ks = 0 or a specular weight 0 reflects nothing and the material is exactly
// Lambertian under IBL as under the suns.
vec3 splitSumReflectance(FresnelEnds e, vec2 ab) { return e.f0 * ab.x + e.f90 * ab.y; }

// Perceptual roughness for an energy-normalised Blinn-Phong exponent (Walter et al. 2007:
// alpha = sqrt(2 / (n + 2))); n = 0 gives the roughest lobe, 1. The floor is roughness 0.02
// (n = 1.25e7, a scene's `roughness: 0.02`); the analytic BRDFs keep n <= 10000 (shaders/common/brdf.glsl).
const float LP_IBL_MAX_SHININESS = 12499998.0;
float roughnessFromShininess(float n) {
    float alpha = sqrt(2.0 / (clamp(n, 0.0, LP_IBL_MAX_SHININESS) + 2.0));
    return sqrt(alpha);
}

// The inverse for a roughness texture (glTF metallic-roughness): n = 2 / r^4 - 2 down to the floor
// r = 0.02, past the analytic BRDFs' 10000 (brdf.glsl's shininessFromRoughness stops at r = 0.119).
float shininessFromRoughnessToFloor(float roughness) {
    float r = clamp(roughness, 0.02, 1.0);
    return min(2.0 / (r * r * r * r) - 2.0, LP_IBL_MAX_SHININESS);
}

// Irradiance from 9 SH coefficients of radiance (Ramamoorthi & Hanrahan 2001): E(n) =
// sum_l A_l sum_m L_lm Y_lm(n), A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4. Clamped at 0: for a
// sun-dominated map the order-2 truncation rings negative on the far side (Filament #744).
vec3 shIrradiance(vec3 sh[9], vec3 n) {
    const float A0 = LP_IBL_PI, A1 = 2.0 * LP_IBL_PI / 3.0, A2 = LP_IBL_PI / 4.0;
    vec3 e = A0 * 0.282095 * sh[0]
           + A1 * 0.488603 * (n.y * sh[1] + n.z * sh[2] + n.x * sh[3])
           + A2 * (1.092548 * (n.x * n.y * sh[4] + n.y * n.z * sh[5] + n.x * n.z * sh[7])
                   + 0.315392 * (3.0 * n.z * n.z - 1.0) * sh[6]
                   + 0.546274 * (n.x * n.x - n.y * n.y) * sh[8]);
    return max(e, vec3(0.0));
}

#endif
