// Ranged point-light attenuation (UE4 / Karis 2013): irradiance at distance d from a light of radiant
// intensity I and range R is
//   E(d) = I / max(d^2, (LP_ATTEN_MIN_DIST * R)^2) * window(d / R),  window(x) = clamp(1 - x^4, 0, 1)^2.
// The window's value and slope are exactly zero at d = R (so light volumes, scissor rectangles and
// tiles can cut at R without a seam); below d = 0.01 R the inverse square is held constant, so a
// light lying on a surface gives a large but finite irradiance (I / (0.01 R)^2) instead of Inf/NaN.
#ifndef LP_ATTENUATION_GLSL
#define LP_ATTENUATION_GLSL

const float LP_ATTEN_MIN_DIST = 0.01;  // fraction of the range below which 1/d^2 stops growing

// Smooth range window in [0, 1]: 1 at d = 0, value and derivative 0 at d >= range.
float lpRangeWindow(float d, float range) {
    float x = d / range;
    float x2 = x * x;
    float w = clamp(1.0 - x2 * x2, 0.0, 1.0);
    return w * w;
}

// 1 / d^2 with d clamped below at LP_ATTEN_MIN_DIST * range (no window).
float lpInverseSquare(float d, float range) {
    float dMin = LP_ATTEN_MIN_DIST * range;
    return 1.0 / max(d * d, dMin * dMin);
}

// The irradiance factor E / I of the brief: inverse square times the range window.
float lpPointAttenuation(float d, float range) { return lpInverseSquare(d, range) * lpRangeWindow(d, range); }

#endif
