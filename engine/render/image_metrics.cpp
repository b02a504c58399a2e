#include "engine/render/image_metrics.hpp"

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"

namespace lp {

namespace {
double luminance(const float* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }
}  // namespace

ImageError compareHdr(const ImageF& image, const ImageF& reference, const std::vector<uint8_t>* mask) {
    if (image.width != reference.width || image.height != reference.height)
        throw Error("image comparison: sizes differ (" + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " vs " + std::to_string(reference.width) + "x" + std::to_string(reference.height) + ")");
    const size_t pixels = size_t(image.width) * size_t(image.height);
    if (mask && mask->size() != pixels)
        throw Error("image comparison: the mask has " + std::to_string(mask->size()) + " pixels, the images " +
                    std::to_string(pixels));
    ImageError e;
    double sum = 0.0, lumDiff = 0.0, lumRef = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < pixels; ++p) {
        if (mask && !(*mask)[p]) continue;
        ++e.pixels;
        const float* a = &image.rgba[4 * p];
        const float* b = &reference.rgba[4 * p];
        bool finite = true;
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(a[c]) || !std::isfinite(b[c])) {
                ++e.nonFinite;
                finite = false;
                continue;
            }
            const double d = double(a[c]) - double(b[c]);
            sum += d * d;
            e.maxAbs = std::max(e.maxAbs, std::abs(d));
            ++n;
        }
        if (!finite) continue;
        const double ya = luminance(a), yb = luminance(b);
        lumDiff += std::abs(ya - yb);
        lumRef += std::abs(yb);
    }
    const double mse = n ? sum / double(n) : 0.0;
    e.rmse = std::sqrt(mse);
    e.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    e.relativeError = lumRef > 0.0 ? lumDiff / lumRef : 0.0;
    return e;
}

}  // namespace lp
