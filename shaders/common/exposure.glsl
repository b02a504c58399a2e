// Auto exposure's centre-weighted histogram of log2 luminance, shared by auto_exposure_histogram.comp,
// auto_exposure_average.comp and the CPU reference (passes/auto_exposure_pass.cpp mirrors it).
// Metering: each pixel counts with a weight that falls off from the image centre (a Gaussian of the
// distance in half-extents, sigma 0.35: 1 at the centre, 0.017 at the middle of an edge), as a
// camera's centre-weighted average metering; of that weighted histogram, the log2 mean of the part
// between 20% and 70% of the weight (past the dark shadows and the background, short of the sky,
// lamps and highlights) is put on middle grey 0.18. Middle grey then displays at 0.105 linear under
// `lightpass` (pow(c/(c+1), 1.2)) and 0.108 under `aces` (Filament's): where Filament puts it.
#ifndef LP_EXPOSURE_GLSL
#define LP_EXPOSURE_GLSL

const int LP_EXPOSURE_BINS = 128;
const float LP_EXPOSURE_MIN_LOG2 = -16.0;  // darker pixels (black, the empty background) are not counted
const float LP_EXPOSURE_MAX_LOG2 = 16.0;
// A pixel adds round(weight x 64) to its bin's count and round(place x that) to the bin's places (its
// position inside the bin): at most 64 each, so 8K (33 M pixels) fits a uint.
const float LP_EXPOSURE_WEIGHT_SCALE = 64.0;
const float LP_EXPOSURE_CENTRE_SIGMA = 0.35;  // the centre weight's width, in half-extents of the image
const float LP_EXPOSURE_LOW = 0.20;   // the darkest 20% of the weight is left out of the average
const float LP_EXPOSURE_HIGH = 0.70;  // and the brightest 30%
const float LP_EXPOSURE_KEY = 0.18;   // the average lands on middle grey

// Bin position of a luminance: [0, BINS) for counted pixels, -1 for dark / NaN ones; +Inf and beyond
// the range go to the last bin.
float exposureBinPosition(float luminance) {
    if (!(luminance >= exp2(LP_EXPOSURE_MIN_LOG2))) return -1.0;
    float t = (min(log2(luminance), LP_EXPOSURE_MAX_LOG2) - LP_EXPOSURE_MIN_LOG2) /
              (LP_EXPOSURE_MAX_LOG2 - LP_EXPOSURE_MIN_LOG2);
    return min(t * float(LP_EXPOSURE_BINS), float(LP_EXPOSURE_BINS) - 1e-3);
}

// The metering weight of pixel p of a size-sized image, in fixed point (0 .. 64).
uint exposureMeteringWeight(ivec2 p, ivec2 size) {
    vec2 d = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;  // -1 .. 1 across each axis
    float w = exp(-dot(d, d) / (2.0 * LP_EXPOSURE_CENTRE_SIGMA * LP_EXPOSURE_CENTRE_SIGMA));
    return uint(w * LP_EXPOSURE_WEIGHT_SCALE + 0.5);
}

float exposureBinLog2(float position) {
    return LP_EXPOSURE_MIN_LOG2 + position / float(LP_EXPOSURE_BINS) * (LP_EXPOSURE_MAX_LOG2 - LP_EXPOSURE_MIN_LOG2);
}

#endif
