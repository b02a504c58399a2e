// Unit-normal encodings for the G-buffer, from the seeds' layouts to octahedral. Each encode maps a
// unit vector to the values a target would store (already quantized where the format is integer),
// each decode returns a unit vector. tests/gl/test_normal_encoding.cpp states and proves each
// format's worst angular error over the whole sphere (poles, the z = 0 seam, ±0, denormals).
#ifndef LP_NORMAL_ENCODING_GLSL
#define LP_NORMAL_ENCODING_GLSL

// ---- seed 001's packed layout: (x, y) stored, z = sqrt(1 - x² - y²) rebuilt -------------------
// It cannot store z < 0: every normal facing away from the camera comes back mirrored to z >= 0.
vec2 seedPackedEncode(vec3 n) { return n.xy; }
vec3 seedPackedDecode(vec2 e) { return vec3(e, sqrt(max(0.0, 1.0 - dot(e, e)))); }

// The fix: the sign of z rides in the sign bit of the channel stored beside it (seed 001 keeps
// shininess there, which is never negative). `carrier` is that channel's non-negative value.
float seedPackedSignedCarrier(vec3 n, float carrier) { return n.z < 0.0 ? -max(carrier, 1e-30) : max(carrier, 0.0); }
vec3 seedPackedSignedDecode(vec2 e, float signedCarrier) {
    vec3 n = seedPackedDecode(e);
    return signedCarrier < 0.0 ? vec3(n.xy, -n.z) : n;
}

// ---- seed 004's two-angle layout: (phi, cos theta) -------------------------------------------
vec2 twoAngleEncode(vec3 n) { return vec2(atan(n.y, n.x), clamp(n.z, -1.0, 1.0)); }
vec3 twoAngleDecode(vec2 e) {
    float s = sqrt(max(0.0, 1.0 - e.y * e.y));
    return vec3(cos(e.x) * s, sin(e.x) * s, e.y);
}

// ---- octahedral (Cigolle et al. 2014, "A Survey of Efficient Representations for Independent
// Unit Vectors") --------------------------------------------------------------------------------
// sign() returns 0 for 0; the fold needs +1 there, or normals on the seam collapse to the origin.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octahedralEncode(vec3 n) {
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    vec2 p = (l1 > 0.0 ? n.xy / l1 : vec2(0.0));
    return n.z < 0.0 ? (1.0 - abs(p.yx)) * signNotZero(p) : p;
}

vec3 octahedralDecode(vec2 e) {
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) v.xy = (1.0 - abs(v.yx)) * signNotZero(v.xy);
    float len = length(v);
    return len > 0.0 ? v / len : vec3(0.0, 0.0, 1.0);
}

// Snorm quantization of [-1, 1] to `bits` per component (what an RG8/RG16 snorm target or a
// packed 12+12-bit integer stores), and back.
vec2 quantizeSnorm(vec2 v, float bits) {
    float m = exp2(bits - 1.0) - 1.0;
    return round(clamp(v, -1.0, 1.0) * m) / m;
}

// Octahedral at 2 x bits/2 (16, 24 or 32 bits in all). Rounds to the nearest grid point, then
// tries the 4 neighbouring grid points and keeps the one whose decoded normal is closest
// ("precise" encoding, Cigolle et al. section 3.2).
vec2 octahedralEncodeQuantized(vec3 n, float totalBits) {
    float bits = totalBits * 0.5;
    float m = exp2(bits - 1.0) - 1.0;
    vec2 e = octahedralEncode(n);
    vec2 base = floor(clamp(e, -1.0, 1.0) * m);
    vec2 best = round(clamp(e, -1.0, 1.0) * m) / m;
    float bestDot = dot(octahedralDecode(best), n);
    for (int i = 0; i < 4; ++i) {
        vec2 c = clamp((base + vec2(i & 1, i >> 1)) / m, -1.0, 1.0);
        float d = dot(octahedralDecode(c), n);
        if (d > bestDot) {
            bestDot = d;
            best = c;
        }
    }
    return best;
}

#endif
