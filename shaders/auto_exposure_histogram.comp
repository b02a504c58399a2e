#version 450
// Auto exposure, step 1: each pixel's log2 luminance into a 128-bin histogram, weighted by its
// distance from the centre (row 0: weights, row 1: the weighted places of the pixels inside their bins,
// so the average is exact within a bin), in fixed point (common/exposure.glsl).
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
        uint weight = exposureMeteringWeight(p, size);
        if (position >= 0.0 && weight > 0u) {
            int bin = int(position);
            atomicAdd(sCount[bin], weight);
            atomicAdd(sFraction[bin], uint((position - float(bin)) * float(weight) + 0.5));
        }
    }
    barrier();
    if (i < uint(LP_EXPOSURE_BINS) && sCount[i] > 0u) {
        imageAtomicAdd(uHistogram, ivec2(int(i), 0), sCount[i]);
        imageAtomicAdd(uHistogram, ivec2(int(i), 1), sFraction[i]);
    }
}
