// Inspecting the HDR buffer: invalid pixels (Falcor's InvalidPixelDetection) and luminance in EV
// stops as false colour (Filament's DisplayRange). Shared by hdr_view.comp and the shader tests.
#ifndef LP_HDR_INSPECT_GLSL
#define LP_HDR_INSPECT_GLSL

const vec3 LP_NAN_COLOR = vec3(1.0, 0.0, 1.0);  // magenta: a NaN in any channel
const vec3 LP_INF_COLOR = vec3(0.0, 1.0, 1.0);  // cyan: +-Inf in a channel (and no NaN)

// 0 valid, 1 NaN, 2 Inf.
int invalidPixelKind(vec4 c) {
    if (any(isnan(c))) return 1;
    if (any(isinf(c))) return 2;
    return 0;
}

// Rec. 709 luminance.
float hdrLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The stop a luminance falls in, relative to middle grey (0.18) after `exposureEV`: round(log2(L x
// 2^EV / 0.18)), clamped to [-6, 6]; -6 also for L <= 0 (black) and 6 for +Inf.
int evBand(float luminance, float exposureEV) {
    if (!(luminance > 0.0)) return -6;
    float ev = log2(luminance / 0.18) + exposureEV;
    if (isinf(ev)) return ev > 0.0 ? 6 : -6;
    return int(clamp(floor(ev + 0.5), -6.0, 6.0));
}

// One colour per stop, cold to hot: -6 black (and below), -5 .. -1 blues to teal, 0 green (middle
// grey), +1 .. +5 yellow to red and magenta, +6 white (and above). docs/viewer.md ("Debug views") lists them.
vec3 evBandColor(int band) {
    const vec3 colors[13] = vec3[13](
        vec3(0.0, 0.0, 0.0),     // -6
        vec3(0.10, 0.0, 0.35),   // -5
        vec3(0.20, 0.0, 0.70),   // -4
        vec3(0.0, 0.15, 1.0),    // -3
        vec3(0.0, 0.55, 1.0),    // -2
        vec3(0.0, 0.75, 0.55),   // -1
        vec3(0.0, 0.85, 0.0),    //  0 middle grey
        vec3(0.60, 0.90, 0.0),   // +1
        vec3(1.0, 0.90, 0.0),    // +2
        vec3(1.0, 0.55, 0.0),    // +3
        vec3(1.0, 0.10, 0.0),    // +4
        vec3(0.90, 0.0, 0.60),   // +5
        vec3(1.0, 1.0, 1.0));    // +6
    return colors[clamp(band, -6, 6) + 6];
}

#endif
