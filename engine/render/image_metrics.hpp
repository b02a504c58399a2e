#pragma once
// Image error against a reference, on linear HDR values: what "accuracy" means in a sweep.
#include <cstdint>
#include <vector>

#include "engine/io/image_io.hpp"

namespace lp {

struct ImageError {
    double rmse = 0.0;  // over the RGB channels of every pixel
    double psnr = 0.0;  // 10 log10(peak^2 / MSE), peak = 1 (display white); +inf when identical
    double maxAbs = 0.0;
    size_t nonFinite = 0;  // NaN/Inf texels in the test image (counted, excluded from the sums)
    // Sum of |luminance - the reference's luminance| over the sum of the reference's luminance (0 where
    // the reference is black): the error as a fraction of the light, whatever the scene's brightness.
    double relativeError = 0.0;
    size_t pixels = 0;  // pixels compared (every pixel, or those of the mask)
};

// Throws lp::Error when the sizes differ. `mask` (width x height, rows top first, non-zero: compared),
// when given, limits every figure to its pixels (e.g. those that see a surface: surfaceMask).
ImageError compareHdr(const ImageF& image, const ImageF& reference, const std::vector<uint8_t>* mask = nullptr);

}  // namespace lp
