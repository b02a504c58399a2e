// Shadow-map filtering for directional lights (cascades packed as tiles of one D32F atlas).
// Positions are in atlas texel units (texel t covers [t, t + 1)); depths are window depths 0..1.
//
// Every tap compares against the receiver's depth *at that texel's centre*, extrapolated along the
// receiver's plane (receiver-plane depth bias): a flat receiver then never shadows itself, whatever
// its slope or the kernel's size, and the constant bias can stay small.
#ifndef LP_SHADOW_GLSL
#define LP_SHADOW_GLSL
#include "common/shadow_caster_depth.glsl"

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

// Texel compare results: lit, occluded, or silent: the texel says nothing about the receiver.
const float LP_SHADOW_SILENT = -1.0;

// 1 where a texel tc (inside the tile) holding depth `stored` does not occlude the receiver, 0 where it
// does, LP_SHADOW_SILENT where it says nothing about the receiver:
// - it holds no caster (cleared to 1.0; casters cover every texel they touch: shadow_depth.geom);
// - in a marked atlas (`marked`: shadow_caster_depth.glsl), no face towards the light covers its
//   centre (a face turned away from the light, or a face grown past its edge) and it does not
//   occlude the receiver. A receiver lit there would be such a face at that centre, so the receiver's
//   plane, extrapolated to the texel, runs past the receiver's end. At a closed crease the texels past
//   the crease hold only the grown edges of its two faces, and the receiver's plane continued past
//   the crease lies in front of the face that shadows it: lit, though no receiver is there.
float shadowCompareStored(float stored, ivec2 tc, vec2 pos, float z, vec2 grad, float bias, bool marked) {
    if (stored >= 1.0) return LP_SHADOW_SILENT;
    float expected = z + dot(grad, vec2(tc) + 0.5 - pos) - bias;
    if (expected > stored) return 0.0;
    return marked && !shadowDepthFrontAtCentre(stored) ? LP_SHADOW_SILENT : 1.0;
}

// The same for texel t, clamped into the tile, read from the atlas.
float shadowTexelCompare(sampler2D map, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad, float bias,
                         bool marked) {
    ivec2 tc = clamp(t, tileMin, tileMax);
    return shadowCompareStored(texelFetch(map, tc, 0).r, tc, pos, z, grad, bias, marked);
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

// Over a 2x2 block of texels t .. t + (1, 1) (depths d from shadowDepths2x2, in its order): the sum of
// weight w times the compare, and the sum of the weights, both over the texels that are not silent.
vec2 shadowBlockSum(vec4 d, vec4 w, ivec2 t, ivec2 tileMin, ivec2 tileMax, vec2 pos, float z, vec2 grad, float bias,
                    bool marked) {
    vec4 c = vec4(shadowCompareStored(d.x, clamp(t, tileMin, tileMax), pos, z, grad, bias, marked),
                  shadowCompareStored(d.y, clamp(t + ivec2(1, 0), tileMin, tileMax), pos, z, grad, bias, marked),
                  shadowCompareStored(d.z, clamp(t + ivec2(0, 1), tileMin, tileMax), pos, z, grad, bias, marked),
                  shadowCompareStored(d.w, clamp(t + ivec2(1, 1), tileMin, tileMax), pos, z, grad, bias, marked));
    vec4 says = vec4(notEqual(c, vec4(LP_SHADOW_SILENT)));
    return vec2(dot(w * says, c), dot(w, says));
}

// Weight of texel column (or row) i of a (2r+2)-wide PCF block, -r <= i <= r + 1, at fraction f.
float shadowPcfWeight(int i, int r, float f) {
    return i == -r ? 1.0 - f : (i == r + 1 ? f : 1.0);
}

// The filter off: the receiver's own texel. Where that one is silent, the four texels around the
// lookup (a bilinear compare, silent ones left out, the others' weights renormalised) decide: next to
// a closed crease the own texel's centre may lie past the crease, and the lookup's neighbours on the
// receiver's side of it then say the crease is in shadow. All silent: lit (nothing the light sees
// lies in front of the receiver there).
float shadowSingleLookup(sampler2D map, vec2 atlasSize, vec2 pos, ivec2 tileMin, ivec2 tileMax, float z, vec2 grad,
                         float bias, bool marked) {
    float own = shadowTexelCompare(map, ivec2(floor(pos)), tileMin, tileMax, pos, z, grad, bias, marked);
    if (own != LP_SHADOW_SILENT) return own;
    vec2 p = pos - 0.5;
    ivec2 t = ivec2(floor(p));
    vec2 f = p - floor(p);
    vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    vec2 sum = shadowBlockSum(shadowDepths2x2(map, atlasSize, t, tileMin, tileMax), w, t, tileMin, tileMax, pos, z, grad,
                              bias, marked);
    return sum.y > 0.0 ? sum.x / sum.y : 1.0;
}

// Fraction of light reaching the receiver (0 shadowed .. 1 lit) with the chosen filter: the texel
// compares of shadowTap (the same texels and weights), read four at a time (shadowDepths2x2).
// `marked`: the atlas's depths say whether a face towards the light covers their texel's centre
// (shadow_caster_depth.glsl).
float shadowFilter(sampler2D map, int filterMode, vec2 pos, ivec2 tileMin, ivec2 tileMax, float z, vec2 grad,
                   float bias, bool marked, vec2 pixel) {
    vec2 atlasSize = vec2(textureSize(map, 0));
    if (filterMode == LP_SHADOW_FILTER_OFF)
        return shadowSingleLookup(map, atlasSize, pos, tileMin, tileMax, z, grad, bias, marked);
    // A silent tap lies where the receiver is not: past the silhouette of everything the light sees
    // (no caster), or past the receiver's end (the grown edges at a closed crease). It says nothing
    // about the light on the receiver, so it is left out and the weights of the others are
    // renormalised: a crease in shadow stays in shadow under any kernel, up to the crease itself.
    vec2 sum = vec2(0.0);  // (weighted compares, weights) over the taps that are not silent
    if (filterMode == LP_SHADOW_FILTER_POISSON) {
        float angle = 6.28318531 * interleavedGradientNoise(pixel);
        float c = cos(angle), s = sin(angle);
        mat2 rotation = mat2(c, s, -s, c);
        for (int k = 0; k < 16; ++k) {  // 16 bilinear compares: a 2x2 block each
            vec2 p = pos - 0.5 + rotation * LP_POISSON_DISC16[k] * LP_SHADOW_POISSON_RADIUS;
            ivec2 t = ivec2(floor(p));
            vec2 f = p - floor(p);
            vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
            sum += shadowBlockSum(shadowDepths2x2(map, atlasSize, t, tileMin, tileMax), w, t, tileMin, tileMax, pos, z,
                                  grad, bias, marked);
        }
    } else {
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
                                      tileMin, tileMax, pos, z, grad, bias, marked);
            }
        }
    }
    // Every tap silent (the PCF kernels hold the texels the filter off reads, Poisson's may not):
    // as the filter off.
    if (sum.y > 0.0) return sum.x / sum.y;
    return shadowSingleLookup(map, atlasSize, pos, tileMin, tileMax, z, grad, bias, marked);
}

#endif
