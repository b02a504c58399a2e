// Double-precision references of shaders/common/tonemap.glsl's curves, for the shader tests.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace lp::test {

// NaN -> 0, negatives -> 0, above the half-float maximum -> 65504 (sanitizeHdr).
inline glm::dvec3 sanitizeHdrRef(glm::dvec3 c) {
    for (int i = 0; i < 3; ++i) c[i] = std::isnan(c[i]) ? 0.0 : std::clamp(c[i], 0.0, 65504.0);
    return c;
}

// Narkowicz 2015 without the 0.6 input scale (--tonemap aces-legacy), clamped to [0, 1].
inline glm::dvec3 acesLegacyRef(glm::dvec3 c) {
    c = sanitizeHdrRef(c);
    glm::dvec3 r;
    for (int i = 0; i < 3; ++i)
        r[i] = std::clamp((c[i] * (2.51 * c[i] + 0.03)) / (c[i] * (2.43 * c[i] + 0.59) + 0.14), 0.0, 1.0);
    return r;
}

// Filament's ACES tone mapper as its colour grading applies it to linear Rec.709 (ToneMapper.cpp
// ACESToneMapper = aces::ACES(c, 1) between ColorGrading's sRGB_to_Rec2020 and Rec2020_to_sRGB, then
// saturated), step by step in double with the matrices of Filament's ColorSpaceUtils.h (column-major,
// as glm's constructors take them).
inline glm::dvec3 filamentAcesRef(glm::dvec3 c) {
    const glm::dmat3 sRGB_to_XYZ(0.4124560, 0.2126730, 0.0193339, 0.3575760, 0.7151520, 0.1191920, 0.1804380,
                                 0.0721750, 0.9503040);
    const glm::dmat3 XYZ_to_sRGB(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314,
                                 0.0415560, 1.0572252);
    const glm::dmat3 Rec2020_to_XYZ(0.6369530, 0.2626983, 0.0000000, 0.1446169, 0.6780088, 0.0280731, 0.1688558,
                                    0.0592929, 1.0608272);
    const glm::dmat3 XYZ_to_Rec2020(1.7166634, -0.6666738, 0.0176425, -0.3556733, 1.6164557, -0.0427770, -0.2533681,
                                    0.0157683, 0.9422433);
    const glm::dmat3 AP1_to_XYZ(0.6624541811, 0.2722287168, -0.0055746495, 0.1340042065, 0.6740817658, 0.0040607335,
                                0.1561876870, 0.0536895174, 1.0103391003);
    const glm::dmat3 XYZ_to_AP1(1.6410233797, -0.6636628587, 0.0117218943, -0.3248032942, 1.6153315917,
                                -0.0082844420, -0.2364246952, 0.0167563477, 0.9883948585);
    const glm::dmat3 AP1_to_AP0(0.6954522414, 0.0447945634, -0.0055258826, 0.1406786965, 0.8596711185, 0.0040252103,
                                0.1638690622, 0.0955343182, 1.0015006723);
    const glm::dmat3 AP0_to_AP1(1.4514393161, -0.0765537734, 0.0083161484, -0.2365107469, 1.1762296998,
                                -0.0060324498, -0.2149285693, -0.0996759264, 0.9977163014);
    const glm::dvec3 lumAP1(0.272229, 0.674082, 0.0536895);
    const glm::dmat3 sRGB_to_Rec2020 = XYZ_to_Rec2020 * sRGB_to_XYZ;
    const glm::dmat3 Rec2020_to_sRGB = XYZ_to_sRGB * Rec2020_to_XYZ;
    const glm::dmat3 Rec2020_to_AP0 = AP1_to_AP0 * XYZ_to_AP1 * Rec2020_to_XYZ;
    const glm::dmat3 AP1_to_Rec2020 = XYZ_to_Rec2020 * AP1_to_XYZ;
    const double halfMax = 65504.0;

    c = sanitizeHdrRef(c);
    glm::dvec3 ap0 = Rec2020_to_AP0 * (sRGB_to_Rec2020 * c);

    // rgb_2_saturation, rgb_2_yc, sigmoid_shaper, glow_fwd
    const double mi = std::min(ap0.x, std::min(ap0.y, ap0.z)), ma = std::max(ap0.x, std::max(ap0.y, ap0.z));
    const double saturation = (std::max(ma, 1e-5) - std::max(mi, 1e-5)) / std::max(ma, 1e-2);
    const double chroma = std::sqrt(std::max(
        ap0.z * (ap0.z - ap0.y) + ap0.y * (ap0.y - ap0.x) + ap0.x * (ap0.x - ap0.z), 0.0));
    const double yc = (ap0.z + ap0.y + ap0.x + 1.75 * chroma) / 3.0;
    const double x = (saturation - 0.4) / 0.2;
    const double t = std::max(1.0 - std::abs(x / 2.0), 0.0);
    const double s = (1.0 + (x > 0 ? 1.0 : x < 0 ? -1.0 : 0.0) * (1.0 - t * t)) / 2.0;
    const double glowGain = 0.05 * s, glowMid = 0.08;
    const double glow = yc <= 2.0 / 3.0 * glowMid ? glowGain
                        : yc >= 2.0 * glowMid     ? 0.0
                                                  : glowGain * (glowMid / yc - 0.5);
    ap0 *= 1.0 + glow;

    // rgb_2_hue, center_hue, the red modifier
    double hue = 0.0;
    if (!(ap0.x == ap0.y && ap0.y == ap0.z))
        hue = 180.0 / 3.14159265358979323846 *
              std::atan2(std::sqrt(3.0) * (ap0.y - ap0.z), 2.0 * ap0.x - ap0.y - ap0.z);
    if (hue < 0.0) hue += 360.0;
    double centred = hue;
    if (centred < -180.0) centred += 360.0;
    if (centred > 180.0) centred -= 360.0;
    const double e = std::clamp(1.0 - std::abs(2.0 * centred / 135.0), 0.0, 1.0);
    double hueWeight = e * e * (3.0 - 2.0 * e);  // smoothstep(0, 1, .)
    hueWeight *= hueWeight;
    ap0.x += hueWeight * saturation * (0.03 - ap0.x) * (1.0 - 0.82);

    glm::dvec3 ap1 = glm::clamp(AP0_to_AP1 * ap0, 0.0, halfMax);
    ap1 = glm::mix(glm::dvec3(glm::dot(ap1, lumAP1)), ap1, 0.96);
    const glm::dvec3 post = (ap1 * (2.785085 * ap1 + 0.107772)) / (ap1 * (2.936045 * ap1 + 0.887122) + 0.806889);

    // darkSurround_to_dimSurround: XYZ -> xyY, Y^0.9811, back
    glm::dvec3 xyz = AP1_to_XYZ * post;
    const double sum = std::max(xyz.x + xyz.y + xyz.z, 1e-5);
    const double cx = xyz.x / sum, cy = xyz.y / sum;
    const double Y = std::pow(std::clamp(xyz.y, 0.0, halfMax), 0.9811);
    const double a = Y / std::max(cy, 1e-5);
    glm::dvec3 linearCv = XYZ_to_AP1 * glm::dvec3(cx * a, Y, (1.0 - cx - cy) * a);
    linearCv = glm::mix(glm::dvec3(glm::dot(linearCv, lumAP1)), linearCv, 0.93);

    return glm::clamp(Rec2020_to_sRGB * (AP1_to_Rec2020 * linearCv), 0.0, 1.0);
}

}  // namespace lp::test
