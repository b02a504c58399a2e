// Ranged point-light attenuation (UE4 / Karis 2013): irradiance at distance d from a light of radiant
// intensity I and range R is
//   E(d) = I / max(d^2, dMin^2) * window(d / R),  window(x) = clamp(1 - x^4, 0, 1)^2,
//   dMin = min(LP_ATTEN_MIN_DIST * R, LP_ATTEN_MIN_DIST_CAP).
// The window's value and slope are exactly zero at d = R (so light volumes, scissor rectangles and
// tiles can cut at R without a seam); below d = dMin the inverse square is held constant, so a light
// lying on a surface gives a large but finite irradiance (I / dMin^2) instead of Inf/NaN. dMin is
// capped at 1 cm: a clamp growing with the range (1e4 m at R = 1e6, Inf at 1e30) darkened a
// long-range light to nothing everywhere.
#ifndef LP_ATTENUATION_GLSL
#define LP_ATTENUATION_GLSL

const float LP_ATTEN_MIN_DIST = 0.01;      // fraction of the range below which 1/d^2 stops growing
const float LP_ATTEN_MIN_DIST_CAP = 0.01;  // ... but never beyond 1 cm, whatever the range

// Smooth range window in [0, 1]: 1 at d = 0, value and derivative 0 at d >= range.
float lpRangeWindow(float d, float range) {
    float x = d / range;
    float x2 = x * x;
    float w = clamp(1.0 - x2 * x2, 0.0, 1.0);
    return w * w;
}

// 1 / d^2 with d clamped below at dMin (no window).
float lpInverseSquare(float d, float range) {
    float dMin = min(LP_ATTEN_MIN_DIST * range, LP_ATTEN_MIN_DIST_CAP);
    return 1.0 / max(d * d, dMin * dMin);
}

// The irradiance factor E / I of the brief: inverse square times the range window.
float lpPointAttenuation(float d, float range) { return lpInverseSquare(d, range) * lpRangeWindow(d, range); }

#endif
