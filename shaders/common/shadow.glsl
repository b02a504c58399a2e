// Shadow-map filtering for directional lights (cascades packed as tiles of one D32F atlas).
// Positions are in atlas texel units (texel t covers [t, t + 1)); depths are window depths 0..1.
//
// Every tap compares against the receiver's depth *at that texel's centre*, extrapolated along the
// receiver's plane (receiver-plane depth bias): a flat receiver then never shadows itself, whatever
// its slope or the kernel's size, and the constant bias can stay small.
#ifndef LP_SHADOW_GLSL
#define LP_SHADOW_GLSL

// ShadowSettings::Filter
#define LP_SHADOW_FILTER_OFF 0
#define LP_SHADOW_FILTER_PCF3 1
#define LP_SHADOW_FILTER_PCF5 2
#define LP_SHADOW_FILTER_POISSON 3

// Window depth change of a planar receiver per texel step, from its light-space unit normal
// (z towards the light) and texelOverRange = texel size / depth range (both world units).
// n.z is clamped at 0.01 (89.4 degrees): beyond that the light's N.L is negligible anyway.
vec2 shadowReceiverGradient(vec3 nLight, float texelOverRange) {
    return nLight.xy / max(nLight.z, 0.01) * texelOverRange;
}

// Texel compare results: lit, occluded, or no caster at all in that texel (cleared to 1.0).
const float LP_SHADOW_NO_CASTER = -1.0;

// 1 where texel t (clamped into the tile) does not occlude the receiver, 0 where it does,
// LP_SHADOW_NO_CASTER where it holds no caster (casters cover every texel they touch:
// shadow_depth.geom).
float shadowTexelCompare(sampler2D map, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad, float bias) {
    ivec2 tc = clamp(t, tileMin, tileMax);
    float stored = texelFetch(map, tc, 0).r;
    if (stored >= 1.0) return LP_SHADOW_NO_CASTER;
    float expected = z + dot(grad, vec2(tc) + 0.5 - pos) - bias;
    return expected <= stored ? 1.0 : 0.0;
}

// 1 where texel t does not occlude the receiver, else 0. Cleared texels (no caster) never occlude,
// even where the receiver's plane, extrapolated to the texel, lies past the far end of the range.
float shadowTexelLit(sampler2D map, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad, float bias) {
    float r = shadowTexelCompare(map, t, tileMin, tileMax, pos, z, grad, bias);
    return r == LP_SHADOW_NO_CASTER ? 1.0 : r;
}

// 16-tap Poisson disc (max radius 1.29), scaled to LP_SHADOW_POISSON_RADIUS texels and rotated per
// pixel by interleaved gradient noise (Jimenez 2014), so banding becomes fine noise.
const float LP_SHADOW_POISSON_RADIUS = 2.0;
const vec2 LP_POISSON_DISC16[16] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725), vec2(-0.094184101, -0.92938870),
    vec2(0.34495938, 0.29387760), vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379), vec2(0.44323325, -0.97511554),
    vec2(0.53742981, -0.47373420), vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590), vec2(0.19984126, 0.78641367),
    vec2(0.14383161, -0.14100790));

float interleavedGradientNoise(vec2 pixel) {
    return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
}

// Texel compares a filter makes: off 1; 3x3 and 5x5 are (2r+1)^2 bilinear compares at unit offsets,
// done as (2r+2)^2 texel compares with separable weights (1 - f, 1, ..., 1, f); Poisson is 16
// bilinear compares of 4 texels each.
int shadowTapCount(int filterMode) {
    if (filterMode == LP_SHADOW_FILTER_PCF3) return 16;
    if (filterMode == LP_SHADOW_FILTER_PCF5) return 36;
    if (filterMode == LP_SHADOW_FILTER_POISSON) return 64;
    return 1;
}

// The k-th texel compare of a filter at `pos`: which texel, with what weight (weights sum to 1).
void shadowTap(int filterMode, int k, vec2 pos, mat2 rotation, out ivec2 texel, out float weight) {
    if (filterMode == LP_SHADOW_FILTER_OFF) {
        texel = ivec2(floor(pos));
        weight = 1.0;
        return;
    }
    vec2 p = pos - 0.5;
    ivec2 corner;
    if (filterMode == LP_SHADOW_FILTER_POISSON) {
        p += rotation * LP_POISSON_DISC16[k / 4] * LP_SHADOW_POISSON_RADIUS;
        corner = ivec2(k % 2, (k / 2) % 2);
        vec2 f = p - floor(p);
        texel = ivec2(floor(p)) + corner;
        weight = (corner.x == 1 ? f.x : 1.0 - f.x) * (corner.y == 1 ? f.y : 1.0 - f.y) / 16.0;
        return;
    }
    int r = filterMode == LP_SHADOW_FILTER_PCF5 ? 2 : 1;
    int side = 2 * r + 2;
    ivec2 ij = ivec2(k % side, k / side) - ivec2(r);
    vec2 f = p - floor(p);
    float wx = ij.x == -r ? 1.0 - f.x : (ij.x == r + 1 ? f.x : 1.0);
    float wy = ij.y == -r ? 1.0 - f.y : (ij.y == r + 1 ? f.y : 1.0);
    texel = ivec2(floor(p)) + ij;
    float n = float(2 * r + 1);
    weight = wx * wy / (n * n);
}

// Fraction of light reaching the receiver (0 shadowed .. 1 lit) with the chosen filter. One loop
// with one texel fetch for every filter: small code (llvmpipe compiles it quickly) and no unrolling.
float shadowFilter(sampler2D map, int filterMode, vec2 pos, ivec2 tileMin, ivec2 tileMax, float z, vec2 grad,
                   float bias, vec2 pixel) {
    float angle = 6.28318531 * interleavedGradientNoise(pixel);
    float c = cos(angle), s = sin(angle);
    mat2 rotation = mat2(c, s, -s, c);
    // A tap on a texel with no caster lies past the silhouette of everything the light sees; the
    // receiver is itself a caster, so such a tap only reaches past an edge where the receiver meets
    // another caster (a concave corner) or ends. It says nothing about the light there: it takes the
    // answer of the receiver's own texel, so a crease in shadow stays in shadow under any kernel.
    float own = shadowTexelLit(map, ivec2(floor(pos)), tileMin, tileMax, pos, z, grad, bias);
    if (filterMode == LP_SHADOW_FILTER_OFF) return own;
    float sum = 0.0;
    int n = shadowTapCount(filterMode);
    for (int k = 0; k < n; ++k) {
        ivec2 texel;
        float weight;
        shadowTap(filterMode, k, pos, rotation, texel, weight);
        float r = shadowTexelCompare(map, texel, tileMin, tileMax, pos, z, grad, bias);
        sum += weight * (r == LP_SHADOW_NO_CASTER ? own : r);
    }
    return sum;
}

#endif
