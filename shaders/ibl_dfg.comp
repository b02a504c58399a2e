#version 450
// The split-sum DFG LUT: texel (x, y) holds (A, B) at N.V = x / (size - 1) and perceptual
// roughness y / (size - 1) (dfgLutTexelParameters); readers look up with dfgLutCoordinate. The BRDF's
// Smith model is uSpecularMasking's (common/brdf.glsl): the LUT is baked per masking.
#include "common/ibl.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rg16f, binding = 0) uniform writeonly image2D uLut;
uniform int uSize;
uniform int uSamples;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= uSize || p.y >= uSize) return;
    vec2 c = dfgLutTexelParameters(p, uSize);
    imageStore(uLut, p, vec4(dfgIntegrate(c.x, c.y, uint(uSamples), uSpecularMasking), 0.0, 0.0));
}
