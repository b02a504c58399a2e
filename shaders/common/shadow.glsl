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

// 1 where a texel tc (inside the tile) holding depth `stored` does not occlude the receiver, 0
// where it does, LP_SHADOW_NO_CASTER where it holds no caster (casters cover every texel they touch:
// shadow_depth.geom).
float shadowCompareStored(float stored, ivec2 tc, vec2 pos, float z, vec2 grad, float bias) {
    if (stored >= 1.0) return LP_SHADOW_NO_CASTER;
    float expected = z + dot(grad, vec2(tc) + 0.5 - pos) - bias;
    return expected <= stored ? 1.0 : 0.0;
}

// The same for texel t, clamped into the tile, read from the atlas.
float shadowTexelCompare(sampler2D map, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad, float bias) {
    ivec2 tc = clamp(t, tileMin, tileMax);
    return shadowCompareStored(texelFetch(map, tc, 0).r, tc, pos, z, grad, bias);
}

// The depths of texels t, t + (1, 0), t + (0, 1) and t + (1, 1), each clamped into the tile, in that
// order, from one textureGather: a quarter of the fetch instructions of four texelFetch, which matters
// most where texture fetches are scarce (fragment shaders on compute GPUs: bench/forward_terms.sh).
// The gather reads the 2x2 block at b, t clamped so that the block lies in the tile; every clamped
// texel of t's block is one of b's (it is sampled at the block's shared corner, exactly between texel
// centres, so the footprint is b whatever the rounding; gather reads the base level, whatever the
// filter). One path for every texel, the tile's edges included: no branch around the gather.
vec4 shadowDepths2x2(sampler2D map, vec2 atlasSize, ivec2 t, ivec2 tileMin, ivec2 tileMax) {
    ivec2 b = clamp(t, tileMin, max(tileMax - 1, tileMin));
    vec4 g = textureGather(map, vec2(b + 1) / atlasSize, 0);  // (i0 j1, i1 j1, i1 j0, i0 j0)
    vec2 row0 = vec2(g.w, g.z), row1 = vec2(g.x, g.y);       // rows b.y and b.y + 1
    ivec2 o0 = clamp(t, tileMin, tileMax) - b;                // 0 or 1 on each axis
    ivec2 o1 = clamp(t + 1, tileMin, tileMax) - b;
    vec2 lo = o0.y == 0 ? row0 : row1;  // the row of t.y
    vec2 hi = o1.y == 0 ? row0 : row1;  // the row of t.y + 1
    return vec4(o0.x == 0 ? lo.x : lo.y, o1.x == 0 ? lo.x : lo.y, o0.x == 0 ? hi.x : hi.y, o1.x == 0 ? hi.x : hi.y);
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

// Sum over a 2x2 block of texels t .. t + (1, 1) (depths d from shadowDepths2x2, in its order) of
// weight w times the compare, a texel with no caster taking the receiver's own answer.
float shadowBlockSum(vec4 d, vec4 w, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad,
                     float bias, float own) {
    vec4 c = vec4(shadowCompareStored(d.x, clamp(t, tileMin, tileMax), pos, z, grad, bias),
                  shadowCompareStored(d.y, clamp(t + ivec2(1, 0), tileMin, tileMax), pos, z, grad, bias),
                  shadowCompareStored(d.z, clamp(t + ivec2(0, 1), tileMin, tileMax), pos, z, grad, bias),
                  shadowCompareStored(d.w, clamp(t + ivec2(1, 1), tileMin, tileMax), pos, z, grad, bias));
    c = mix(c, vec4(own), equal(c, vec4(LP_SHADOW_NO_CASTER)));
    return dot(w, c);
}

// Weight of texel column (or row) i of a (2r+2)-wide PCF block, -r <= i <= r + 1, at fraction f.
float shadowPcfWeight(int i, int r, float f) {
    return i == -r ? 1.0 - f : (i == r + 1 ? f : 1.0);
}

// Fraction of light reaching the receiver (0 shadowed .. 1 lit) with the chosen filter: the texel
// compares of shadowTap (the same texels and weights), read four at a time (shadowDepths2x2).
float shadowFilter(sampler2D map, int filterMode, vec2 pos, ivec2 tileMin, ivec2 tileMax, float z, vec2 grad,
                   float bias, vec2 pixel) {
    // A tap on a texel with no caster lies past the silhouette of everything the light sees; the
    // receiver is itself a caster, so such a tap only reaches past an edge where the receiver meets
    // another caster (a concave corner) or ends. It says nothing about the light there: it takes the
    // answer of the receiver's own texel, so a crease in shadow stays in shadow under any kernel.
    float own = shadowTexelLit(map, ivec2(floor(pos)), tileMin, tileMax, pos, z, grad, bias);
    if (filterMode == LP_SHADOW_FILTER_OFF) return own;
    vec2 atlasSize = vec2(textureSize(map, 0));
    float sum = 0.0;
    if (filterMode == LP_SHADOW_FILTER_POISSON) {
        float angle = 6.28318531 * interleavedGradientNoise(pixel);
        float c = cos(angle), s = sin(angle);
        mat2 rotation = mat2(c, s, -s, c);
        for (int k = 0; k < 16; ++k) {  // 16 bilinear compares: a 2x2 block each
            vec2 p = pos - 0.5 + rotation * LP_POISSON_DISC16[k] * LP_SHADOW_POISSON_RADIUS;
            ivec2 t = ivec2(floor(p));
            vec2 f = p - floor(p);
            vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
            sum += shadowBlockSum(shadowDepths2x2(map, atlasSize, t, tileMin, tileMax), w, t, tileMin, tileMax, pos,
                                  z, grad, bias, own);
        }
        return sum / 16.0;
    }
    // 3x3 and 5x5: (2r+1)^2 bilinear compares at unit offsets, as (2r+2)^2 texels with separable
    // weights (1 - f, 1, ..., 1, f), read as (r+1)^2 blocks of 2x2.
    int r = filterMode == LP_SHADOW_FILTER_PCF5 ? 2 : 1;
    vec2 p = pos - 0.5;
    ivec2 corner = ivec2(floor(p));
    vec2 f = p - floor(p);
    for (int j = -r; j <= r; j += 2) {
        vec2 wy = vec2(shadowPcfWeight(j, r, f.y), shadowPcfWeight(j + 1, r, f.y));
        for (int i = -r; i <= r; i += 2) {
            vec2 wx = vec2(shadowPcfWeight(i, r, f.x), shadowPcfWeight(i + 1, r, f.x));
            ivec2 t = corner + ivec2(i, j);
            sum += shadowBlockSum(shadowDepths2x2(map, atlasSize, t, tileMin, tileMax), vec4(wx * wy.x, wx * wy.y), t,
                                  tileMin, tileMax, pos, z, grad, bias, own);
        }
    }
    float n = float(2 * r + 1);
    return sum / (n * n);
}

#endif
