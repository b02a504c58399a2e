// Motion blur after McGuire, Hennessy, Bukowski and Osman, "A Reconstruction Filter for Plausible
// Motion Blur" (I3D 2012): per pixel a half blur vector V (pixels), its maximum over K x K tiles and
// over each tile's 3 x 3 neighbours, and a gather along that neighbour maximum whose samples are
// weighted by depth order and by whether their own blur reaches the pixel.
#ifndef LP_MOTION_BLUR_GLSL
#define LP_MOTION_BLUR_GLSL

// Half the blur vector in pixels: the shutter's fraction of a frame's motion (velocity in uv units
// x image size), halved because the blur is centred on the pixel; its length clamped to maxRadius
// (the tile size K: the gather never looks further than one tile). 0 for NaN or no motion.
vec2 motionBlurHalfVector(vec2 velocityUv, vec2 sizePixels, float shutter, float maxRadius) {
    vec2 v = 0.5 * shutter * velocityUv * sizePixels;
    float len = length(v);
    if (!(len > 0.0) || isinf(len)) return vec2(0.0);
    return v * (min(len, maxRadius) / len);
}

// The paper's weights. Distances and lengths in pixels; a blur shorter than half a pixel counts as
// half a pixel (the pixel itself).
float motionBlurCone(float distance, float halfLength) {
    return clamp(1.0 - distance / max(halfLength, 0.5), 0.0, 1.0);
}
float motionBlurCylinder(float distance, float halfLength) {
    float l = max(halfLength, 0.5);
    return 1.0 - smoothstep(0.95 * l, 1.05 * l, distance);
}
// 1 where the surface at distance za (metres, positive) is not behind the one at zb, falling to 0
// once it is `extent` x zb behind (a soft test: 2% of the depth in the pass).
float motionBlurInFront(float za, float zb, float extent) {
    return clamp(1.0 - (za - zb) / max(extent * zb, 1e-6), 0.0, 1.0);
}

// Tap i of n along the neighbour maximum: t in (-1, 1), offset by the pixel's jitter j in [-0.5, 0.5].
float motionBlurTap(int i, int n, float j) { return mix(-1.0, 1.0, (float(i) + j + 1.0) / float(n + 1)); }

#endif
