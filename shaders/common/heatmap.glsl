// Heat-map colours for the lights-per-tile and lights-per-cluster views, drawn over the tone-mapped
// image: they write the HDR value that the lightpass tone map turns into the wanted display colour.
#ifndef LP_HEATMAP_GLSL
#define LP_HEATMAP_GLSL
#include "common/tonemap.glsl"

vec3 heatColour(float t) {  // blue -> cyan -> green -> yellow -> red
    t = clamp(t, 0.0, 1.0);
    return clamp(vec3(1.5 - abs(4.0 * t - 3.0), 1.5 - abs(4.0 * t - 2.0), 1.5 - abs(4.0 * t - 1.0)), 0.0, 1.0);
}

// HDR value that the lightpass tone map (at exposure EV) turns into display-linear y.
vec3 heatUntonemap(vec3 y, float exposure) {
    vec3 x = pow(clamp(y, 0.0, 0.995), vec3(1.0 / 1.2));
    return x / (1.0 - x) * exp2(-exposure);
}

#endif
