#version 450
// Auto exposure, step 1: each pixel's log2 luminance into a 128-bin histogram (row 0: counts, row 1:
// the pixels' places inside their bins in fixed point, so the average is exact within a bin).
// Per work group in shared memory first, then one atomic per bin into the image.
#include "common/exposure.glsl"
#include "common/hdr_inspect.glsl"

layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D uHdr;
layout(r32ui, binding = 0) uniform coherent uimage2D uHistogram;

shared uint sCount[LP_EXPOSURE_BINS];
shared uint sFraction[LP_EXPOSURE_BINS];

void main() {
    uint i = gl_LocalInvocationIndex;
    if (i < uint(LP_EXPOSURE_BINS)) {
        sCount[i] = 0u;
        sFraction[i] = 0u;
    }
    barrier();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uHdr, 0);
    if (p.x < size.x && p.y < size.y) {
        vec3 c = texelFetch(uHdr, p, 0).rgb;
        float position = exposureBinPosition(hdrLuminance(c));
        if (position >= 0.0) {
            int bin = int(position);
            atomicAdd(sCount[bin], 1u);
            atomicAdd(sFraction[bin], uint((position - float(bin)) * LP_EXPOSURE_FRACTION_SCALE));
        }
    }
    barrier();
    if (i < uint(LP_EXPOSURE_BINS) && sCount[i] > 0u) {
        imageAtomicAdd(uHistogram, ivec2(int(i), 0), sCount[i]);
        imageAtomicAdd(uHistogram, ivec2(int(i), 1), sFraction[i]);
    }
}
