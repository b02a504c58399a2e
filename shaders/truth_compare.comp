#version 450
// The viewer's comparison with the path tracer ('c', app/viewer_compare): one RGBA8 image of 2 x 2
// tiles, each tile the size of the two HDR frames: top left the raster frame, top right the path
// tracer's, both exposed alike (uExposureEv) and tone-mapped by the frame's operator; bottom left the
// signed error of the raster's luminance against the tracer's, relative to the tracer's: red where
// the raster is brighter, blue where it is darker, black where they agree, full at +-uFullScale;
// bottom right black (the panel's numbers and the legend go there).
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uRaster;  // linear HDR
layout(binding = 1) uniform sampler2D uTruth;   // linear HDR, the same size
layout(rgba8, binding = 0) uniform writeonly image2D uOut;
uniform float uExposureEv;
uniform int uOperator;      // the tone map (lp::ToneMapOperator's order, common/tonemap.glsl)
uniform float uFullScale;   // relative error shown at full colour
uniform float uFloor;       // luminance below which the error is taken against this instead

float luminanceOf(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Signed relative error e in [-1, 1] of full scale -> colour: red for e > 0, blue for e < 0.
vec3 errorColour(float e) {
    float a = clamp(abs(e), 0.0, 1.0);
    return e >= 0.0 ? vec3(a, a * a * 0.35, 0.0) : vec3(0.0, a * a * 0.35, a);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 tile = textureSize(uRaster, 0);
    if (p.x >= 2 * tile.x || p.y >= 2 * tile.y) return;
    // GL's window y runs up: the top row of tiles is the upper half of the image.
    bool right = p.x >= tile.x, top = p.y >= tile.y;
    ivec2 q = p - ivec2(right ? tile.x : 0, top ? tile.y : 0);
    vec3 raster = sanitizeHdr(texelFetch(uRaster, q, 0).rgb);
    vec3 truth = sanitizeHdr(texelFetch(uTruth, q, 0).rgb);
    vec3 c;
    if (top) {
        c = linearToSrgb(applyToneMap(applyExposure(right ? truth : raster, uExposureEv), uOperator));
    } else if (!right) {
        float lt = luminanceOf(truth);
        float e = (luminanceOf(raster) - lt) / max(lt, uFloor);
        c = linearToSrgb(errorColour(e / uFullScale));
    } else {
        c = vec3(0.0);
    }
    imageStore(uOut, p, vec4(c, 1.0));
}
