#pragma once
// CPU reference of bloom and toon: plain C++, compiled everywhere, the ground truth the GLSL
// and CUDA implementations are tested against. Images are RGBA float, row-major, row 0 first.
// Borders are clamp-to-edge everywhere (a tap outside the image reads the nearest edge texel).
#include "engine/io/image_io.hpp"
#include "engine/post/post_params.hpp"

namespace lp::post {

// Where intermediates are stored: Half rounds every stored value to fp16 (the GLSL path's RGBA16F
// textures); Float keeps fp32 (the CUDA path's device buffers).
enum class Storage { Half, Float };

float roundToHalf(float v);  // round-to-nearest-even to fp16 and back (overflow -> +-Inf)

ImageF brightPassImage(const ImageF& hdr, const BloomParams& p, Storage storage);
// One direction of the separable Gaussian (horizontal when `horizontal`).
ImageF blurImage(const ImageF& in, const std::vector<float>& weights, bool horizontal, Storage storage);
// The bloom buffer alone (before `strength`), by p.method.
ImageF bloomBuffer(const ImageF& hdr, const BloomParams& p, Storage storage);
// sanitize(sanitize(hdr) + strength * bloom) (a NaN texel still gets its neighbours' glow), stored in the HDR buffer (always RGBA16F: rounded to half).
ImageF compositeBloom(const ImageF& hdr, const ImageF& bloom, float strength);
// Mip chain pieces (Jimenez 2014), exposed for tests: level 0 is half resolution.
std::vector<ImageF> mipChainDown(const ImageF& hdr, const BloomParams& p, Storage storage);

// Toon outline mask: 1 where depth or normal edges exceed the thresholds. `position` holds the
// eye-space position in xyz and coverage in w (0: no geometry), `normal` the eye-space normal.
std::vector<unsigned char> toonEdges(const ImageF& position, const ImageF& normal, const ToonParams& p);
// The ramp on every covered texel, outlines black; uncovered texels keep their colour unless an
// outline reaches them. Result stored in the HDR buffer (rounded to half).
ImageF toonImage(const ImageF& hdr, const ImageF& position, const ImageF& normal, const ToonParams& p);

}  // namespace lp::post
