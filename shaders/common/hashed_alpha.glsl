// Hashed alpha testing (Wyman and McGuire, "Hashed Alpha Testing", I3D 2017): a threshold uniform in
// (0, 1] that depends only on an object-space position and the size of the texel it is drawn in, so
// alpha >= threshold keeps a fraction alpha of a surface, the same wherever the camera is. No
// derivatives here (common/shadow_alpha.glsl takes them), so compute shaders and tests can call it.
#ifndef LP_HASHED_ALPHA_GLSL
#define LP_HASHED_ALPHA_GLSL

// PCG3D (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020): integer arithmetic,
// the same on every driver.
uvec3 hashPcg3d(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

// Uniform in [0, 1) per cell of the grid of spacing 1 / scale around object-space point p (the
// cell's index by the bits of floor(): defined for any float, no integer overflow).
float hashedAlphaCell(vec3 p, float scale) {
    return float(hashPcg3d(floatBitsToUint(floor(p * scale))).x >> 8u) * (1.0 / 16777216.0);
}

// The hashed alpha threshold at object-space point p whose texel spans `texel` object-space units
// (Wyman and McGuire's isotropic version, hash scale 1): the grids of the powers of two around one
// cell per texel, the two hashes blended by where the texel lies between them, and the blend's
// distribution made uniform again. In (0, 1]: alpha 1 never drops a fragment, alpha 0 always does.
float hashedAlphaThreshold(vec3 p, float texel) {
    // log2 of cells per object-space unit, clamped so a degenerate footprint stays finite.
    float level = clamp(-log2(max(texel, 1e-30)), -60.0, 60.0);
    float lower = floor(level);
    float x = mix(hashedAlphaCell(p, exp2(lower)), hashedAlphaCell(p, exp2(lower + 1.0)), level - lower);
    float a = min(level - lower, 1.0 - (level - lower));
    float t;
    if (a < 1e-6) t = x;  // on a level: one hash, already uniform
    else if (x < a) t = x * x / (2.0 * a * (1.0 - a));
    else if (x < 1.0 - a) t = (x - 0.5 * a) / (1.0 - a);
    else t = 1.0 - (1.0 - x) * (1.0 - x) / (2.0 * a * (1.0 - a));
    return clamp(t, 1e-6, 1.0);
}

#endif
