#include "engine/render/image_metrics.hpp"

#include <cmath>
#include <limits>

#include "engine/core/error.hpp"

namespace lp {

ImageError compareHdr(const ImageF& image, const ImageF& reference) {
    if (image.width != reference.width || image.height != reference.height)
        throw Error("image comparison: sizes differ (" + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " vs " + std::to_string(reference.width) + "x" + std::to_string(reference.height) + ")");
    ImageError e;
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < image.rgba.size(); ++i) {
        if (i % 4 == 3) continue;  // alpha
        const double a = image.rgba[i], b = reference.rgba[i];
        if (!std::isfinite(a) || !std::isfinite(b)) {
            ++e.nonFinite;
            continue;
        }
        const double d = a - b;
        sum += d * d;
        e.maxAbs = std::max(e.maxAbs, std::abs(d));
        ++n;
    }
    const double mse = n ? sum / double(n) : 0.0;
    e.rmse = std::sqrt(mse);
    e.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    return e;
}

}  // namespace lp
