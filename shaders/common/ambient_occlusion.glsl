// Ground-truth ambient occlusion (GTAO, Jimenez, Wu, Pesce & Jarabo 2016, "Practical Real-Time
// Strategies for Accurate Indirect Occlusion") and the specular occlusion derived from it.
// A slice is the plane through the eye, the shaded point P and one screen direction. Angles in it
// are measured from the view vector V (P towards the eye), positive towards the slice's screen
// direction; n is the angle of the normal projected into the slice, h0 <= n <= h1 the horizons.
// The cosine-weighted visible part of the hemisphere is (1/pi) * integral over slices phi in [0, pi)
// of |Np| (a(h0) + a(h1)), so the mean of gtaoSliceVisibility over uniformly spread slices is the
// AO; an unoccluded point gives exactly 1 in the limit of many slices.
#ifndef LP_AMBIENT_OCCLUSION_GLSL
#define LP_AMBIENT_OCCLUSION_GLSL

#include "common/depth_reconstruct.glsl"

const float LP_AO_PI = 3.14159265358979;
const float LP_AO_HALF_PI = 1.57079632679490;

// integral from 0 to h of cos(t - n) |sin t| dt, for h on either side of 0 (closed form).
float gtaoArc(float h, float n) {
    return 0.25 * (cos(n) + 2.0 * h * sin(n) - cos(2.0 * h - n));
}

// One slice's cosine-weighted visibility: |Np| (a(h0) + a(h1)); h0 <= 0 side, h1 >= 0 side. The
// horizons are first clamped into the normal's hemisphere, [n - pi/2, n + pi/2].
float gtaoSliceVisibility(float h0, float h1, float n, float projectedNormalLength) {
    h0 = n + max(h0 - n, -LP_AO_HALF_PI);
    h1 = n + min(h1 - n, LP_AO_HALF_PI);
    return projectedNormalLength * (gtaoArc(h0, n) + gtaoArc(h1, n));
}

// The slices are spread uniformly in azimuth about V (not in screen angle: off the view axis equal
// screen angles are unequal azimuths, which biases the mean), so slice psi contains V and the unit
// direction w(psi) perpendicular to V returned here.
vec3 gtaoSliceDirection(vec3 V, float psi) {
    vec3 t1 = normalize(abs(V.z) > 1e-4 ? vec3(V.z, 0.0, -V.x) : vec3(1.0, 0.0, 0.0));
    vec3 t2 = cross(V, t1);
    return cos(psi) * t1 + sin(psi) * t2;
}

// The screen direction (pixels, y up) in which the slice through eye-space point P along w runs:
// the derivative of the projection of P + t w at t = 0. Unit length.
vec2 gtaoScreenDirection(vec3 P, vec3 w) {
    vec2 d = w.xy * (-P.z) + P.xy * w.z;
    float len = length(d);
    return len > 1e-12 ? d / len : vec2(1.0, 0.0);
}

// The normal N projected into the slice spanned by V and w (w perpendicular to V): its length and
// its signed angle n from V, positive towards w.
void gtaoProjectNormal(vec3 N, vec3 V, vec3 w, out float n, out float projectedLength) {
    vec3 axis = cross(w, V);
    vec3 Np = N - axis * dot(N, axis);
    projectedLength = length(Np);
    float cosN = projectedLength > 1e-6 ? clamp(dot(Np, V) / projectedLength, 0.0, 1.0) : 1.0;
    n = (dot(Np, w) < 0.0 ? -1.0 : 1.0) * acos(cosN);
}

// Specular occlusion from the AO and the view angle (Lagarde & de Rousiers 2014, "Moving Frostbite
// to PBR", eq. of their listing 25): a mirror-like lobe is occluded only where the AO cone cuts it,
// a rough lobe almost as much as the diffuse. alpha: GGX roughness (perceptual squared). 1 at ao 1,
// 0 at ao 0.
float specularOcclusion(float NdotV, float ao, float alpha) {
    return clamp(pow(max(NdotV + ao, 0.0), exp2(-16.0 * alpha - 1.0)) - 1.0 + ao, 0.0, 1.0);
}

// Eye-space point of an AO texel from its eye depth z > 0: the centre of the G-buffer pixel it stands
// for (texel t * scale at fullSize) on the camera's ray, as gbufferPosition rebuilds it from depth.
// camera: uGbufferCamera (near, far, tan(vertical fov / 2), width / height).
vec3 aoTexelPosition(ivec2 t, float z, int scale, vec2 fullSize, vec4 camera) {
    vec2 uv = (min(vec2(t * scale), fullSize - 1.0) + 0.5) / fullSize;
    return eyePositionFromZ(uv, -z, camera.z, camera.w);
}

// The period, in texels, of the pattern that spreads the slices and steps over neighbouring texels:
// the blur and denoise average exactly one period on each axis.
const int LP_AO_PATTERN_PERIOD = 8;

// Texel p's place in the pattern: an 8x8 Bayer matrix, so each 8x8 block holds 0..63 once and any
// 2x2, 4x4 block spreads its values evenly.
int aoPatternIndex(ivec2 p) {
    int x = p.x & 7, y = p.y & 7, k = 0;
    for (int bit = 0; bit < 3; ++bit) k = (k << 2) | ((((x ^ y) >> bit) & 1) << 1) | ((y >> bit) & 1);
    return k;
}

// The slices' rotation (fraction of the angle between slices) and the steps' offset (fraction of a
// step) at pattern index k: the 64 indices give the 2D Hammersley set (k / 64, k bit-reversed / 64),
// so every rotation pairs with a different offset and any rotation x offset stratum of 1/8 x 1/8 holds
// one pair (rotation and offset both from the Bayer value would pair small with small).
float aoSliceRotation(int k) { return (float(k) + 0.5) / 64.0; }
float aoStepOffset(int k) { return (float(bitfieldReverse(uint(k)) >> 26u) + 0.5) / 64.0; }

// The blur's and the denoise's weight of the tap k texels from the centre along their axis: 1 for
// |k| < 4 and 1/2 at |k| = 4, whose two taps share a phase of the pattern. So each of the 8 phases
// weighs 1: one period averaged exactly, and the filter centred.
float aoPeriodWeight(int k) {
    int a = abs(k);
    return a < LP_AO_PATTERN_PERIOD / 2 ? 1.0 : (a == LP_AO_PATTERN_PERIOD / 2 ? 0.5 : 0.0);
}

// A tap's weight from how far its surface point Q lies from the centre's tangent plane (P, N),
// relative to the centre's eye depth: exp(-1) at 2%. Occlusion does not bleed across depth edges,
// while on a slanted plane every tap keeps its full weight (a plain depth difference would drop the
// far taps there and leave the pattern unevenly averaged).
float aoPlaneWeight(vec3 Q, vec3 P, vec3 N, float depth) {
    float rel = dot(Q - P, N) / (0.02 * depth);
    return exp(-rel * rel);
}

#endif
