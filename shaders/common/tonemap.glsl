// Tone mapping and output encoding. Shared by the tone-map pass and the shader tests.
#ifndef LP_TONEMAP_GLSL
#define LP_TONEMAP_GLSL

const float LP_HALF_MAX = 65504.0;

// NaN -> 0, negatives -> 0, +Inf and overflow -> the largest half float, so one bad texel can
// neither turn black through fp16 overflow nor spread through later filters.
vec3 sanitizeHdr(vec3 c) {
    c = mix(c, vec3(0.0), isnan(c));
    return clamp(c, vec3(0.0), vec3(LP_HALF_MAX));
}

// The seeds' operator: pow(c / (c + 1), 1.2) per channel. Sanitising first bounds c by 65504, so
// c = 1e38 or +Inf gives 65504/65505 (about 1) instead of Inf/Inf = NaN; c <= 0 and NaN give 0.
vec3 tonemapLightpass(vec3 c) {
    c = sanitizeHdr(c);
    vec3 x = c / (c + vec3(1.0));
    return pow(clamp(x, 0.0, 1.0), vec3(1.2));
}

// ACES filmic fit (Narkowicz 2015), on the sanitised input, clamped to [0, 1].
vec3 tonemapAces(vec3 c) {
    c = sanitizeHdr(c);
    return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
}

// Khronos PBR Neutral (2024 reference implementation): identity for base colours up to 0.76, then
// a highlight compression towards white that keeps hue.
vec3 tonemapPbrNeutral(vec3 c) {
    c = sanitizeHdr(c);
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(c.r, min(c.g, c.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    c -= offset;
    float peak = max(c.r, max(c.g, c.b));
    if (peak < startCompression) return clamp(c, 0.0, 1.0);
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    c *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return clamp(mix(c, vec3(newPeak), g), 0.0, 1.0);
}

// AgX (Sobotka), the minimal polynomial fit of its default look (Wrensch 2023): inset matrix,
// log2 encoding over [-12.47, 4.03] EV, sigmoid, outset matrix, back to linear (gamma 2.2).
vec3 tonemapAgx(vec3 c) {
    c = sanitizeHdr(c);
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                             -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                             -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    const float minEv = -12.47393, maxEv = 4.026069;
    vec3 v = inset * c;
    v = clamp(log2(max(v, vec3(1e-10))), minEv, maxEv);
    v = (v - minEv) / (maxEv - minEv);
    vec3 v2 = v * v, v4 = v2 * v2;
    v = 15.5 * v4 * v2 - 40.14 * v4 * v + 31.96 * v4 - 6.868 * v2 * v + 0.4298 * v2 + 0.1191 * v - 0.00232;
    v = outset * v;
    return pow(clamp(v, 0.0, 1.0), vec3(2.2));
}

// 0 lightpass, 1 ACES, 2 PBR Neutral, 3 AgX (the order of lp::ToneMapOperator).
vec3 applyToneMap(vec3 c, int op) {
    if (op == 1) return tonemapAces(c);
    if (op == 2) return tonemapPbrNeutral(c);
    if (op == 3) return tonemapAgx(c);
    return tonemapLightpass(c);
}

// Exposure in EV stops, applied before the curve.
vec3 applyExposure(vec3 c, float ev) { return c * exp2(ev); }

// IEC 61966-2-1 sRGB encoding of a linear value in [0, 1].
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 lo = c * 12.92;
    vec3 hi = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
    return mix(hi, lo, lessThanEqual(c, vec3(0.0031308)));
}

vec3 srgbToLinear(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 lo = c / 12.92;
    vec3 hi = pow((c + 0.055) / 1.055, vec3(2.4));
    return mix(hi, lo, lessThanEqual(c, vec3(0.04045)));
}

#endif
