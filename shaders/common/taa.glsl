// Temporal anti-aliasing's resolve: the current jittered HDR frame blended with the history
// reprojected through the motion vectors, the history clipped to the current neighbourhood's colour
// distribution and dropped where the depth says the surface was not there. Shared by the TAA pass
// and the shader tests.
#ifndef LP_TAA_GLSL
#define LP_TAA_GLSL

#include "common/tonemap.glsl"

// YCoCg (Malvar): luma and two chroma differences, where a box around the neighbourhood's colours
// is tighter than in RGB (Karis 2014).
vec3 rgbToYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b, -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 yCoCgToRgb(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// Variance clipping (Salvi 2016): the box mean +- gamma sigma of the neighbourhood in YCoCg; the
// history is moved along the line towards the mean until it is inside the box (clipping, Karis
// 2014, keeps its hue better than clamping each axis).
vec3 taaClipToBox(vec3 history, vec3 mean, vec3 extent) {
    vec3 d = history - mean;
    vec3 unit = abs(d) / max(extent, vec3(1e-6));
    float m = max(unit.x, max(unit.y, unit.z));
    return m > 1.0 ? mean + d / m : history;
}

// Bilinear by hand at pixel position pos (centres at i + 0.5), clamp to edge, taps sanitised.
vec4 taaBilinear(sampler2D src, vec2 pos) {
    ivec2 size = textureSize(src, 0);
    vec2 c = pos - 0.5;
    vec2 f0 = floor(c);
    vec2 f = c - f0;
    ivec2 i = ivec2(f0);
    vec4 sum = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 t = texelFetch(src, clamp(i + o, ivec2(0), size - 1), 0);
        sum += w * vec4(sanitizeHdr(t.rgb), t.a);
    }
    return sum;
}

// The current frame's 3x3 neighbourhood in YCoCg: mean, standard deviation, minimum and maximum.
struct TaaNeighbourhood {
    vec3 mean, sigma, lo, hi;
};

TaaNeighbourhood taaNeighbourhood(sampler2D current, ivec2 p) {
    ivec2 size = textureSize(current, 0);
    vec3 m1 = vec3(0.0), m2 = vec3(0.0), lo = vec3(1e30), hi = vec3(-1e30);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            vec3 c = rgbToYCoCg(sanitizeHdr(texelFetch(current, clamp(p + ivec2(dx, dy), ivec2(0), size - 1), 0).rgb));
            m1 += c;
            m2 += c * c;
            lo = min(lo, c);
            hi = max(hi, c);
        }
    TaaNeighbourhood n;
    n.mean = m1 / 9.0;
    n.sigma = sqrt(max(m2 / 9.0 - n.mean * n.mean, vec3(0.0)));
    n.lo = lo;
    n.hi = hi;
    return n;
}

// The history colour clipped to the neighbourhood's variance box (gamma 1) intersected with its
// min/max box, in YCoCg, towards the box's centre.
vec3 taaClipHistory(vec3 history, TaaNeighbourhood n) {
    vec3 lo = max(n.mean - n.sigma, n.lo), hi = min(n.mean + n.sigma, n.hi);
    vec3 centre = 0.5 * (lo + hi);
    return yCoCgToRgb(taaClipToBox(rgbToYCoCg(history), centre, 0.5 * (hi - lo)));
}

// Whether the history at the reprojected position shows the same surface: its motion (the velocity
// stored with it) agrees with this pixel's within max(0.5 px, 20% of the motion), in output pixels.
// Where the history held another surface (the background revealed behind a moving object, a
// disocclusion under parallax) the two motions differ.
bool taaMotionAgrees(vec2 velocityPixels, vec2 historyVelocityPixels) {
    float tolerance = max(0.5, 0.2 * length(velocityPixels));
    return length(velocityPixels - historyVelocityPixels) <= tolerance;
}

// The blend of the current sample and the (clipped) history, each weighted by 1 / (1 + luma)
// (Karis 2014): a single very bright sample cannot dominate the average and flicker.
// currentWeight: the current frame's share before that weighting (--taa-history-weight).
vec3 taaBlend(vec3 current, vec3 history, float currentWeight) {
    float wc = currentWeight / (1.0 + rgbToYCoCg(current).x);
    float wh = (1.0 - currentWeight) / (1.0 + rgbToYCoCg(history).x);
    return (wc * current + wh * history) / max(wc + wh, 1e-8);
}

#endif
