#pragma once
// Image error against a reference, on linear HDR values: what "accuracy" means in a sweep.
#include "engine/io/image_io.hpp"

namespace lp {

struct ImageError {
    double rmse = 0.0;  // over the RGB channels of every pixel
    double psnr = 0.0;  // 10 log10(peak^2 / MSE), peak = 1 (display white); +inf when identical
    double maxAbs = 0.0;
    size_t nonFinite = 0;  // NaN/Inf texels in the test image (counted, excluded from the sums)
};

// Throws lp::Error when the sizes differ.
ImageError compareHdr(const ImageF& image, const ImageF& reference);

}  // namespace lp
