#version 450
// Auto exposure, step 2: the mean log2 luminance of the pixels between the LOW and HIGH fractions
// of the weighted histogram, and the exposure (EV) that puts it on middle grey, into a 1x1 R32F image.
#include "common/exposure.glsl"

layout(local_size_x = 1) in;
layout(r32ui, binding = 0) uniform readonly uimage2D uHistogram;
layout(r32f, binding = 1) uniform writeonly image2D uExposure;

void main() {
    float total = 0.0;
    for (int b = 0; b < LP_EXPOSURE_BINS; ++b) total += float(imageLoad(uHistogram, ivec2(b, 0)).r);
    float low = LP_EXPOSURE_LOW * total, high = LP_EXPOSURE_HIGH * total;
    float below = 0.0, weight = 0.0, sumLog2 = 0.0;
    for (int b = 0; b < LP_EXPOSURE_BINS; ++b) {
        float count = float(imageLoad(uHistogram, ivec2(b, 0)).r);
        if (count == 0.0) continue;
        // The part of this bin's pixels inside [low, high] of the cumulative count.
        float take = clamp(min(below + count, high) - max(below, low), 0.0, count);
        below += count;
        if (take <= 0.0) continue;
        float meanPlace = float(imageLoad(uHistogram, ivec2(b, 1)).r) / count;
        sumLog2 += take * exposureBinLog2(float(b) + meanPlace);
        weight += take;
    }
    // Nothing counted (a black frame): exposure 0.
    float ev = weight > 0.0 ? clamp(log2(LP_EXPOSURE_KEY) - sumLog2 / weight, -16.0, 16.0) : 0.0;
    imageStore(uExposure, ivec2(0), vec4(ev));
}
