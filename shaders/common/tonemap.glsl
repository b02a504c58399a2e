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
