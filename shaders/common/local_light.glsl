// Shading of one local light (a ranged point light or a spot), shared by every local-light method
// (full screen, scissor, volumes, tiled, clustered) so they produce the same image. Positions are eye
// space.
#ifndef LP_LOCAL_LIGHT_GLSL
#define LP_LOCAL_LIGHT_GLSL
#include "common/attenuation.glsl"
#include "common/brdf.glsl"

// One light as the SSBO holds it (std430; matches GpuLocalLight in engine/render/local_lights.hpp).
struct LpLocalLight {
    vec4 positionRange;  // xyz eye-space position, w range (m)
    vec4 intensity;      // rgb radiant intensity (colour x intensity), w cos(inner angle); a point light -1.5
    vec4 directionCos;   // xyz eye-space spot axis, w cos(outer angle); a point light -2 (no falloff)
    vec4 bound;          // eye-space bounding sphere of all the light reaches: xyz centre, w radius
    vec4 shadow;         // x: layer of the spot shadow map array, < 0 none; y: point shadow cube, < 0 none
};

// Does the sphere (eye-space centre c, radius r) touch the screen tile between NDC x in [lo.x, hi.x],
// y in [lo.y, hi.y] and eye distances [d0, d1] of the perspective `projection`? Its four side planes
// through the eye and the two depths; conservative: a sphere near a frustum corner may pass. The
// tiled method's culling and the clustered grid's first, per-tile, test (lp::lightTouchesTileColumn).
bool sphereTouchesTileFrustum(vec3 c, float r, vec2 lo, vec2 hi, float d0, float d1, mat4 projection) {
    float dist = -c.z;
    if (dist + r < d0 || dist - r > d1) return false;
    float p00 = projection[0][0], p20 = projection[2][0], p11 = projection[1][1], p21 = projection[2][1];
    // x_ndc >= lo.x  <=>  p00 x + (p20 + lo.x) z >= 0 (with z < 0); likewise for the other sides.
    vec3 planes[4] = vec3[4](vec3(p00, 0.0, p20 + lo.x), vec3(-p00, 0.0, -(p20 + hi.x)),
                             vec3(0.0, p11, p21 + lo.y), vec3(0.0, -p11, -(p21 + hi.y)));
    for (int i = 0; i < 4; ++i)
        if (dot(planes[i], c) < -r * length(planes[i])) return false;
    return true;
}

const int LP_LOCAL_SPECULAR_OFF = 0;      // diffuse only
const int LP_LOCAL_SPECULAR_RANGED = 1;   // diffuse and specular both limited by the range window
const int LP_LOCAL_SPECULAR_UNRANGED = 2; // seed 003's extra mode: specular keeps 1/d^2 past the range

// Radiance a surface point P (normal N, view direction V) reflects from the light, with the BRDF of
// uBrdf (common/brdf.glsl): the same as the suns'.
// `coat`: KHR_materials_clearcoat's layer (kd and ks already the base under it), windowed as the specular.
vec3 lpLocalLightRadiance(vec3 lightPos, float range, vec3 intensity, vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks,
                          float shininess, int specularMode, ClearcoatLayer coat) {
    vec3 toLight = lightPos - P;
    float d = length(toLight);
    // A light exactly on the surface: light it from the normal (N.L = 1), the limit of a light
    // approaching along the normal.
    vec3 L = d > 0.0 ? toLight / d : N;
    float nl = dot(N, L);
    float coatNl = coat.weight > 0.0 ? dot(coat.normal, L) : 0.0;
    if (nl <= 0.0 && coatNl <= 0.0) return vec3(0.0);
    float window = lpRangeWindow(d, range);
    float specularWindow = specularMode == LP_LOCAL_SPECULAR_UNRANGED ? 1.0 : window;
    vec3 coatLight = specularMode != LP_LOCAL_SPECULAR_OFF && coatNl > 0.0
                         ? clearcoatRadiance(coat, V, L, intensity * (lpInverseSquare(d, range) * specularWindow))
                         : vec3(0.0);
    if (nl <= 0.0) return coatLight;
    vec3 e = intensity * (lpInverseSquare(d, range) * nl);  // unwindowed irradiance
    vec3 c = window > 0.0 ? brdfDiffuse(uBrdf, N, V, L, kd, ks) * window : vec3(0.0);
    if (specularMode != LP_LOCAL_SPECULAR_OFF)
        c += brdfSpecular(uBrdf, N, V, L, ks, shininess) * specularWindow;
    return c * e + coatLight;
}
vec3 lpLocalLightRadiance(vec3 lightPos, float range, vec3 intensity, vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks,
                          float shininess, int specularMode) {
    return lpLocalLightRadiance(lightPos, range, intensity, P, N, V, kd, ks, shininess, specularMode, noClearcoat());
}
vec3 lpLocalLightRadiance(vec3 lightPos, float range, vec3 intensity, vec3 P, vec3 N, vec3 V, vec3 kd, vec3 ks,
                          float shininess, int specularMode) {
    return lpLocalLightRadiance(lightPos, range, intensity, P, N, V, kd, fresnelEndsOfF0(ks), shininess, specularMode);
}

// Spot cone falloff: smoothstep from cos(outer) (0) to cos(inner) (1) of the cosine of the angle
// between the spot's axis and the direction from the light to the point; a hard edge when inner =
// outer. With the point-light encoding (cosOuter -2, cosInner -1.5) it is exactly 1 for every angle.
float lpSpotFalloff(float cosAngle, float cosOuter, float cosInner) {
    float t = clamp((cosAngle - cosOuter) / max(cosInner - cosOuter, 1e-6), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

#if defined(LP_SPOT_SHADOWS) || defined(LP_POINT_SHADOWS)
#include "common/shadow.glsl"
// Perspective shadow maps of local lights: a spot's (passes/spot_shadow_pass) and each face of a
// point light's cube (passes/point_shadow_pass), square tiles of a D32F atlas. Compared in linear
// depth along the map's axis, with a bias of a few texels' world size (a perspective map's window
// depth is not linear, so the suns' receiver-plane gradient does not carry over), and the suns'
// filters (shadow.glsl's taps; Poisson unrotated).
struct LpPerspectiveShadow {
    mat4 eyeToClip;  // camera eye space -> the map's clip space
    vec4 tile;       // xy first texel of the atlas tile, z tile size (texels), w a texel's world size per metre
    vec4 depth;      // x near, y far (metres along the axis), z filter (LP_SHADOW_FILTER_*), w normal bias (texels)
    vec4 bias;       // x constant depth bias (texels)
};

// Fraction of the light reaching P (0 shadowed .. 1 lit) by map s of `atlas`; L: unit direction to the light.
float lpPerspectiveShadow(LpPerspectiveShadow s, sampler2D atlas, vec3 P, vec3 N, vec3 L) {
    float nl = clamp(dot(N, L), 0.0, 1.0);
    float texel = max((s.eyeToClip * vec4(P, 1.0)).w, 0.0) * s.tile.w;  // world size of a texel at P
    vec4 q = s.eyeToClip * vec4(P + N * (s.depth.w * texel * (1.0 - nl)), 1.0);
    if (q.w <= 0.0) return 1.0;
    vec2 pos = s.tile.xy + (q.xy / q.w * 0.5 + 0.5) * s.tile.z;
    int mode = int(s.depth.z);
    // Taps reach (radius + 1) texels away: the receiver's depth may change by tan(angle) per texel.
    float reach = mode == LP_SHADOW_FILTER_OFF ? 1.0 : (mode == LP_SHADOW_FILTER_PCF3 ? 2.0 : 3.6);
    float tanAngle = min(sqrt(max(1.0 - nl * nl, 0.0)) / max(nl, 1e-3), 10.0);
    float bias = texel * (s.bias.x + reach * tanAngle);
    ivec2 tileMin = ivec2(s.tile.xy), tileMax = tileMin + ivec2(s.tile.z) - 1;
    float n = s.depth.x, f = s.depth.y;
    float sum = 0.0;
    int taps = shadowTapCount(mode);
    for (int k = 0; k < taps; ++k) {
        ivec2 t;
        float weight;
        shadowTap(mode, k, pos, mat2(1.0), t, weight);
        float stored = texelFetch(atlas, clamp(t, tileMin, tileMax), 0).r;
        float occluder = n * f / (f - stored * (f - n));  // window depth -> distance along the axis
        sum += weight * ((stored >= 1.0 || q.w - bias <= occluder) ? 1.0 : 0.0);
    }
    return sum;
}
#endif

#ifdef LP_SPOT_SHADOWS
// One map per shadowed spot (LpLocalLight.shadow.x), SSBO binding 4, atlas on unit 5.
layout(std430, binding = 4) readonly buffer SpotShadows { LpPerspectiveShadow uSpotShadows[]; };
layout(binding = 5) uniform sampler2D uSpotShadowAtlas;

float lpSpotShadow(int layer, vec3 P, vec3 N, vec3 L) {
    return lpPerspectiveShadow(uSpotShadows[layer], uSpotShadowAtlas, P, N, L);
}
#endif

#ifdef LP_POINT_SHADOWS
// Six maps per shadowed point light (cube LpLocalLight.shadow.y: entries 6 cube .. 6 cube + 5, faces
// +X, -X, +Y, -Y, +Z, -Z), SSBO binding LP_POINT_SHADOW_BUFFER, atlas on unit LP_POINT_SHADOW_UNIT
// (passes/local_light_pass.cpp binds both).
#define LP_POINT_SHADOW_BUFFER 5
#define LP_POINT_SHADOW_UNIT 22
layout(std430, binding = LP_POINT_SHADOW_BUFFER) readonly buffer PointShadows { LpPerspectiveShadow uPointShadowFaces[]; };
layout(binding = LP_POINT_SHADOW_UNIT) uniform sampler2D uPointShadowAtlas;

// The face is the one whose clip w (the distance along its axis: the face matrices' last row) is
// largest at P, the major axis of P's direction from the light (lp::pointShadowFace).
float lpPointShadow(int cube, vec3 P, vec3 N, vec3 L) {
    int first = 6 * cube, face = 0;
    float best = -3.4e38;
    for (int f = 0; f < 6; ++f) {
        mat4 m = uPointShadowFaces[first + f].eyeToClip;
        float w = m[0][3] * P.x + m[1][3] * P.y + m[2][3] * P.z + m[3][3];
        if (w > best) {
            best = w;
            face = f;
        }
    }
    return lpPerspectiveShadow(uPointShadowFaces[first + face], uPointShadowAtlas, P, N, L);
}
#endif

// Radiance from light l (a point light or a spot; with LP_SPOT_SHADOWS / LP_POINT_SHADOWS shadowed by its map) at P: lpLocalLightRadiance times the
// cone falloff. Zero exactly outside the cone and past the range, so every method can cut at the bound.
vec3 lpShadeLocalLight(LpLocalLight l, vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks, float shininess, int specularMode,
                       ClearcoatLayer coat) {
    vec3 toLight = l.positionRange.xyz - P;
    // Past the range the window is exactly 0 (the unranged specular mode aside): skip the rest. The
    // tiled and clustered methods' lists hold many lights that reach the tile but not this pixel.
    float d2 = dot(toLight, toLight);
    if (specularMode != LP_LOCAL_SPECULAR_UNRANGED && d2 >= l.positionRange.w * l.positionRange.w) return vec3(0.0);
    float d = sqrt(d2);
    float cosAngle = d > 0.0 ? dot(-toLight / d, l.directionCos.xyz) : 1.0;  // at the apex: on the axis
    float cone = lpSpotFalloff(cosAngle, l.directionCos.w, l.intensity.w);
    if (cone <= 0.0) return vec3(0.0);
    vec3 c = cone * lpLocalLightRadiance(l.positionRange.xyz, l.positionRange.w, l.intensity.rgb, P, N, V, kd, ks,
                                         shininess, specularMode, coat);
#ifdef LP_SPOT_SHADOWS
    if (l.shadow.x >= 0.0 && d > 0.0 && any(greaterThan(c, vec3(0.0))))
        c *= lpSpotShadow(int(l.shadow.x), P, N, toLight / d);
#endif
#ifdef LP_POINT_SHADOWS
    if (l.shadow.y >= 0.0 && d > 0.0 && any(greaterThan(c, vec3(0.0))))
        c *= lpPointShadow(int(l.shadow.y), P, N, toLight / d);
#endif
    return c;
}

vec3 lpShadeLocalLight(LpLocalLight l, vec3 P, vec3 N, vec3 V, vec3 kd, FresnelEnds ks, float shininess, int specularMode) {
    return lpShadeLocalLight(l, P, N, V, kd, ks, shininess, specularMode, noClearcoat());
}

#endif
