#version 450
// HDR -> display: exposure, the chosen tone map (default pow(c / (c + 1), 1.2)), sRGB encoding, into an RGBA8 image.
#include "common/tonemap.glsl"
#include "common/gbuffer_layout.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = LP_BIND_HDR) uniform sampler2D uHdr;
layout(rgba8, binding = 0) uniform writeonly image2D uLdr;
uniform float uExposureEV;      // manual, or the compensation added to auto exposure
uniform bool uAutoExposure;
layout(binding = 7) uniform sampler2D uExposure;  // auto_exposure's 1x1 EV
uniform int uOperator;  // lp::ToneMapOperator: 0 lightpass, 1 aces, 2 pbr-neutral, 3 agx

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(uLdr);
    if (p.x >= size.x || p.y >= size.y) return;
    float ev = uExposureEV + (uAutoExposure ? texelFetch(uExposure, ivec2(0), 0).r : 0.0);
    vec3 c = applyExposure(texelFetch(uHdr, p, 0).rgb, ev);
    imageStore(uLdr, p, vec4(linearToSrgb(applyToneMap(c, uOperator)), 1.0));
}
