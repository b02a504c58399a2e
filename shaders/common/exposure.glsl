// Auto exposure's histogram of log2 luminance, shared by auto_exposure_histogram.comp,
// auto_exposure_average.comp and the CPU reference (passes/auto_exposure_pass.cpp mirrors it).
#ifndef LP_EXPOSURE_GLSL
#define LP_EXPOSURE_GLSL

const int LP_EXPOSURE_BINS = 128;
const float LP_EXPOSURE_MIN_LOG2 = -16.0;  // darker pixels (black, the empty background) are not counted
const float LP_EXPOSURE_MAX_LOG2 = 16.0;
const float LP_EXPOSURE_FRACTION_SCALE = 256.0;  // a pixel's place in its bin, fixed point (4K fits a uint)
const float LP_EXPOSURE_LOW = 0.40;   // the darkest 40% of counted pixels are left out of the average
const float LP_EXPOSURE_HIGH = 0.95;  // and the brightest 5%
const float LP_EXPOSURE_KEY = 0.18;   // the average lands on middle grey

// Bin position of a luminance: [0, BINS) for counted pixels, -1 for dark / NaN ones; +Inf and beyond
// the range go to the last bin.
float exposureBinPosition(float luminance) {
    if (!(luminance >= exp2(LP_EXPOSURE_MIN_LOG2))) return -1.0;
    float t = (min(log2(luminance), LP_EXPOSURE_MAX_LOG2) - LP_EXPOSURE_MIN_LOG2) /
              (LP_EXPOSURE_MAX_LOG2 - LP_EXPOSURE_MIN_LOG2);
    return min(t * float(LP_EXPOSURE_BINS), float(LP_EXPOSURE_BINS) - 1e-3);
}

float exposureBinLog2(float position) {
    return LP_EXPOSURE_MIN_LOG2 + position / float(LP_EXPOSURE_BINS) * (LP_EXPOSURE_MAX_LOG2 - LP_EXPOSURE_MIN_LOG2);
}

#endif
