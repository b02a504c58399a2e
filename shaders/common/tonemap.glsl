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

// --tonemap aces-legacy: Narkowicz's 2015 ACES fit without its 0.6 input scale (Filament's FILMIC
// operator), on the sanitised input, clamped to [0, 1]: +0.74 EV against `aces` at middle grey.
vec3 tonemapAcesLegacy(vec3 c) {
    c = sanitizeHdr(c);
    return clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
}

// --tonemap aces: the ACES 1.0 reference rendering transform and a 100-nit sRGB output transform as
// Filament (ToneMapper.cpp, ACESToneMapper) and its colour grading apply them: linear Rec.709 in,
// through Rec.2020 to ACES2065-1 (AP0); the RRT's glow and red modifier; AP1 and its global
// desaturation; the RRT+ODT tone curve fit (colour-science's CIECAM02 notebook); the dim-surround
// gamma on luminance; the ODT desaturation; back through Rec.2020 to Rec.709, clamped to [0, 1].
// Matrices are column-major, as GLSL's constructors take them; the constants are ACES's.
const mat3 LP_SRGB_TO_XYZ = mat3(0.4124560, 0.2126730, 0.0193339, 0.3575760, 0.7151520, 0.1191920,
                                 0.1804380, 0.0721750, 0.9503040);
const mat3 LP_XYZ_TO_SRGB = mat3(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259,
                                 -0.4985314, 0.0415560, 1.0572252);
const mat3 LP_REC2020_TO_XYZ = mat3(0.6369530, 0.2626983, 0.0000000, 0.1446169, 0.6780088, 0.0280731,
                                    0.1688558, 0.0592929, 1.0608272);
const mat3 LP_XYZ_TO_REC2020 = mat3(1.7166634, -0.6666738, 0.0176425, -0.3556733, 1.6164557, -0.0427770,
                                    -0.2533681, 0.0157683, 0.9422433);
const mat3 LP_AP1_TO_XYZ = mat3(0.6624541811, 0.2722287168, -0.0055746495, 0.1340042065, 0.6740817658,
                                0.0040607335, 0.1561876870, 0.0536895174, 1.0103391003);
const mat3 LP_XYZ_TO_AP1 = mat3(1.6410233797, -0.6636628587, 0.0117218943, -0.3248032942, 1.6153315917,
                                -0.0082844420, -0.2364246952, 0.0167563477, 0.9883948585);
const mat3 LP_AP1_TO_AP0 = mat3(0.6954522414, 0.0447945634, -0.0055258826, 0.1406786965, 0.8596711185,
                                0.0040252103, 0.1638690622, 0.0955343182, 1.0015006723);
const mat3 LP_AP0_TO_AP1 = mat3(1.4514393161, -0.0765537734, 0.0083161484, -0.2365107469, 1.1762296998,
                                -0.0060324498, -0.2149285693, -0.0996759264, 0.9977163014);
const vec3 LP_LUMINANCE_AP1 = vec3(0.272229, 0.674082, 0.0536895);

// The RRT's "yc": luminance plus 1.75 x chroma over 3 (RGB 1 1 1 gives 1).
float acesYc(vec3 c) {
    float chroma = sqrt(max(c.b * (c.b - c.g) + c.g * (c.g - c.r) + c.r * (c.r - c.b), 0.0));
    return (c.r + c.g + c.b + 1.75 * chroma) / 3.0;
}

vec3 tonemapAces(vec3 c) {
    c = sanitizeHdr(c);
    vec3 ap0 = LP_AP1_TO_AP0 * (LP_XYZ_TO_AP1 * (LP_REC2020_TO_XYZ * (LP_XYZ_TO_REC2020 * (LP_SRGB_TO_XYZ * c))));

    // Glow: lifts dark saturated colours by up to 5%.
    float lo = min(ap0.r, min(ap0.g, ap0.b)), hi = max(ap0.r, max(ap0.g, ap0.b));
    float saturation = (max(hi, 1e-5) - max(lo, 1e-5)) / max(hi, 1e-2);
    float yc = acesYc(ap0);
    float x = (saturation - 0.4) / 0.2;  // sigmoid shaper over -2..2
    float t = max(1.0 - abs(x / 2.0), 0.0);
    float shaped = (1.0 + sign(x) * (1.0 - t * t)) / 2.0;
    const float glowMid = 0.08;
    float glowGain = 0.05 * shaped;
    float glow = yc <= 2.0 / 3.0 * glowMid ? glowGain : (yc >= 2.0 * glowMid ? 0.0 : glowGain * (glowMid / yc - 0.5));
    ap0 *= 1.0 + glow;

    // Red modifier: pulls saturated reds' red channel towards 0.03 (their hue sits at 0 degrees).
    float hue = 0.0;
    if (!(ap0.r == ap0.g && ap0.g == ap0.b)) {
        hue = degrees(atan(sqrt(3.0) * (ap0.g - ap0.b), 2.0 * ap0.r - ap0.g - ap0.b));
        if (hue < 0.0) hue += 360.0;
    }
    float centred = hue > 180.0 ? hue - 360.0 : hue;
    float hueWeight = smoothstep(0.0, 1.0, 1.0 - abs(2.0 * centred / 135.0));
    hueWeight *= hueWeight;
    ap0.r += hueWeight * saturation * (0.03 - ap0.r) * (1.0 - 0.82);

    vec3 ap1 = clamp(LP_AP0_TO_AP1 * ap0, 0.0, LP_HALF_MAX);
    ap1 = mix(vec3(dot(ap1, LP_LUMINANCE_AP1)), ap1, 0.96);
    vec3 post = (ap1 * (2.785085 * ap1 + 0.107772)) / (ap1 * (2.936045 * ap1 + 0.887122) + 0.806889);

    // Dark to dim surround: luminance to the power 0.9811, chromaticity kept.
    vec3 xyz = LP_AP1_TO_XYZ * post;
    float sum = max(xyz.x + xyz.y + xyz.z, 1e-5);
    vec2 xy = xyz.xy / sum;
    float luminance = pow(clamp(xyz.y, 0.0, LP_HALF_MAX), 0.9811);
    float scale = luminance / max(xy.y, 1e-5);
    vec3 linearCv = LP_XYZ_TO_AP1 * vec3(xy.x * scale, luminance, (1.0 - xy.x - xy.y) * scale);
    linearCv = mix(vec3(dot(linearCv, LP_LUMINANCE_AP1)), linearCv, 0.93);

    vec3 rec2020 = LP_XYZ_TO_REC2020 * (LP_AP1_TO_XYZ * linearCv);
    return clamp(LP_XYZ_TO_SRGB * (LP_REC2020_TO_XYZ * rec2020), 0.0, 1.0);
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

// 0 lightpass, 1 ACES, 2 PBR Neutral, 3 AgX, 4 ACES legacy (the order of lp::ToneMapOperator).
vec3 applyToneMap(vec3 c, int op) {
    if (op == 1) return tonemapAces(c);
    if (op == 4) return tonemapAcesLegacy(c);
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
