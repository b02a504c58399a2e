#version 450
// The HDR buffer inspected, into an RGBA8 image: 1 invalid pixels (NaN magenta, Inf cyan, the rest
// the tone-mapped image at 40% grey), 2 luminance in EV stops as false colour (common/hdr_inspect.glsl).
#include "common/hdr_inspect.glsl"
#include "common/tonemap.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D uHdr;
layout(rgba8, binding = 0) uniform writeonly image2D uLdr;
uniform int uMode;
uniform float uExposureEV;  // exposureEvBase()
uniform bool uAutoExposure;
layout(binding = 7) uniform sampler2D uExposure;  // auto_exposure's 1x1 EV, as the tone map adds it
uniform int uOperator;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uLdr);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 hdr = texelFetch(uHdr, p, 0);
    float ev = uExposureEV + (uAutoExposure ? texelFetch(uExposure, ivec2(0), 0).r : 0.0);
    vec3 c;
    if (uMode == 1) {
        int kind = invalidPixelKind(hdr);
        vec3 shown = linearToSrgb(applyToneMap(applyExposure(hdr.rgb, ev), uOperator));
        c = kind == 1 ? LP_NAN_COLOR : kind == 2 ? LP_INF_COLOR : vec3(0.4 * hdrLuminance(shown));
    } else {
        c = evBandColor(evBand(hdrLuminance(hdr.rgb), ev));
    }
    imageStore(uLdr, p, vec4(c, 1.0));
}
