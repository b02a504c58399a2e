#include "engine/post/post_reference.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/post/post_math.hpp"

namespace lp::post {

float roundToHalf(float v) {
    if (std::isnan(v)) return v;
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    const uint32_t sign = bits & 0x80000000u;
    float a = std::fabs(v);
    if (a >= 65520.0f) return sign ? -INFINITY : INFINITY;  // rounds past the largest half
    if (a < 6.103515625e-05f) {  // subnormal halves: multiples of 2^-24
        float q = std::nearbyint(a * 16777216.0f) / 16777216.0f;
        return sign ? -q : q;
    }
    uint32_t ab = bits & 0x7fffffffu;
    // Keep 10 mantissa bits, round to nearest even on the 13 dropped bits.
    uint32_t lsb = (ab >> 13) & 1u;
    ab += 0x0fffu + lsb;
    ab &= ~0x1fffu;
    ab |= sign;
    float out;
    std::memcpy(&out, &ab, 4);
    return out;
}

namespace {

float store(float v, Storage s) { return s == Storage::Half ? roundToHalf(v) : v; }

int clampi(int v, int lo, int hi) { return v < lo ? lo : (v > hi ? hi : v); }

Rgb texel(const ImageF& img, int x, int y) {
    x = clampi(x, 0, img.width - 1);
    y = clampi(y, 0, img.height - 1);
    const float* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
    return {p[0], p[1], p[2]};
}

void put(ImageF& img, int x, int y, Rgb c, Storage s) {
    float* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
    p[0] = store(c.r, s);
    p[1] = store(c.g, s);
    p[2] = store(c.b, s);
    p[3] = 1.0f;
}

ImageF blank(int w, int h) {
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(size_t(w) * size_t(h) * 4, 0.0f);
    return img;
}

Rgb add(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
Rgb scale(Rgb a, float k) { return {a.r * k, a.g * k, a.b * k}; }

// The 13-tap downsample of one destination texel (see shaders/bloom_down.comp): `fetch(x, y)`
// returns the source texel (bright-passed on the first level).
template <typename Fetch>
Rgb downsample13(int dx, int dy, bool karis, Fetch fetch) {
    // The 6x6 source texels 2x-2 .. 2x+3 around the destination texel.
    Rgb t[6][6];
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) t[j][i] = fetch(2 * dx - 2 + i, 2 * dy - 2 + j);
    // Corner sample at offset (ox, oy) in {-2..2} from the destination centre = 2x2 box average.
    auto corner = [&](int ox, int oy) {
        int i = ox + 2, j = oy + 2;  // the box spans t[j..j+1][i..i+1]
        return scale(add(add(t[j][i], t[j][i + 1]), add(t[j + 1][i], t[j + 1][i + 1])), 0.25f);
    };
    auto group = [&](Rgb a, Rgb b, Rgb c, Rgb d) { return scale(add(add(a, b), add(c, d)), 0.25f); };
    const Rgb g[5] = {
        group(corner(-1, -1), corner(1, -1), corner(-1, 1), corner(1, 1)),
        group(corner(-2, -2), corner(0, -2), corner(-2, 0), corner(0, 0)),
        group(corner(0, -2), corner(2, -2), corner(0, 0), corner(2, 0)),
        group(corner(-2, 0), corner(0, 0), corner(-2, 2), corner(0, 2)),
        group(corner(0, 0), corner(2, 0), corner(0, 2), corner(2, 2)),
    };
    const float base[5] = {0.5f, 0.125f, 0.125f, 0.125f, 0.125f};
    Rgb sum;
    float wsum = 0.0f;
    for (int k = 0; k < 5; ++k) {
        float w = karis ? base[k] * karisWeight(g[k]) : base[k];
        sum = add(sum, scale(g[k], w));
        wsum += w;
    }
    return scale(sum, 1.0f / wsum);
}

// The (1, 5, 7, 3) / 16 upsample of `coarse` at fine texel (x, y).
Rgb upsample(const ImageF& coarse, int x, int y) {
    const int bx = (x >> 1) - ((x & 1) ? 1 : 2), by = (y >> 1) - ((y & 1) ? 1 : 2);
    Rgb sum;
    for (int j = 0; j < 4; ++j) {
        Rgb row;
        for (int i = 0; i < 4; ++i) row = add(row, scale(texel(coarse, bx + i, by + j), upsampleWeight(i, x & 1)));
        sum = add(sum, scale(row, upsampleWeight(j, y & 1)));
    }
    return sum;
}

}  // namespace

ImageF brightPassImage(const ImageF& hdr, const BloomParams& p, Storage storage) {
    ImageF out = blank(hdr.width, hdr.height);
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x)
            put(out, x, y, brightPass(texel(hdr, x, y), p.threshold, p.knee, p.highlight), storage);
    return out;
}

ImageF blurImage(const ImageF& in, const std::vector<float>& weights, bool horizontal, Storage storage) {
    ImageF out = blank(in.width, in.height);
    const int r = int(weights.size()) - 1;
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            Rgb sum = scale(texel(in, x, y), weights[0]);
            for (int i = 1; i <= r; ++i) {
                Rgb a = horizontal ? texel(in, x - i, y) : texel(in, x, y - i);
                Rgb b = horizontal ? texel(in, x + i, y) : texel(in, x, y + i);
                sum = add(sum, scale(add(a, b), weights[size_t(i)]));
            }
            put(out, x, y, sum, storage);
        }
    return out;
}

std::vector<ImageF> mipChainDown(const ImageF& hdr, const BloomParams& p, Storage storage) {
    const int levels = mipLevelCount(p.kernel, hdr.width, hdr.height);
    std::vector<ImageF> down;
    for (int l = 0; l < levels; ++l) {
        const ImageF& src = l == 0 ? hdr : down.back();
        ImageF dst = blank(mipSize(hdr.width, l), mipSize(hdr.height, l));
        for (int y = 0; y < dst.height; ++y)
            for (int x = 0; x < dst.width; ++x) {
                Rgb c = l == 0 ? downsample13(x, y, p.karis,
                                              [&](int sx, int sy) {
                                                  return brightPass(texel(src, sx, sy), p.threshold, p.knee, p.highlight);
                                              })
                               : downsample13(x, y, false, [&](int sx, int sy) { return texel(src, sx, sy); });
                put(dst, x, y, c, storage);
            }
        down.push_back(std::move(dst));
    }
    return down;
}

ImageF bloomBuffer(const ImageF& hdr, const BloomParams& p, Storage storage) {
    if (p.method == BloomMethod::Separable) {
        const std::vector<float> w = gaussianWeights(p.kernel);
        ImageF bright = brightPassImage(hdr, p, storage);
        return blurImage(blurImage(bright, w, true, storage), w, false, storage);
    }
    std::vector<ImageF> chain = mipChainDown(hdr, p, storage);
    const int levels = int(chain.size());
    // up_i = down_i + U(up_{i+1}), in place from the coarsest level up.
    for (int l = levels - 2; l >= 0; --l) {
        ImageF& fine = chain[size_t(l)];
        const ImageF& coarse = chain[size_t(l) + 1];
        for (int y = 0; y < fine.height; ++y)
            for (int x = 0; x < fine.width; ++x) put(fine, x, y, add(texel(fine, x, y), upsample(coarse, x, y)), storage);
    }
    // Full resolution: U(up_0) / levels, so a constant image keeps its value.
    ImageF out = blank(hdr.width, hdr.height);
    const float norm = 1.0f / float(levels);
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) put(out, x, y, scale(upsample(chain[0], x, y), norm), storage);
    return out;
}

ImageF compositeBloom(const ImageF& hdr, const ImageF& bloom, float strength) {
    ImageF out = blank(hdr.width, hdr.height);
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) {
            Rgb h = texel(hdr, x, y), b = texel(bloom, x, y);
            put(out, x, y, sanitize(add(sanitize(h), scale(b, strength))), Storage::Half);
        }
    return out;
}

std::vector<unsigned char> toonEdges(const ImageF& position, const ImageF& normal, const ToonParams& p) {
    const int w = position.width, h = position.height;
    std::vector<unsigned char> edges(size_t(w) * size_t(h), 0);
    auto depthAt = [&](int x, int y) {
        x = clampi(x, 0, w - 1);
        y = clampi(y, 0, h - 1);
        const float* q = &position.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
        return q[3] > 0.0f ? -q[2] : p.farDepth;
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float z[3][3], n[3][3][3];
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) {
                    z[j][i] = depthAt(x + i - 1, y + j - 1);
                    Rgb nn = texel(normal, x + i - 1, y + j - 1);
                    n[0][j][i] = nn.r;
                    n[1][j][i] = nn.g;
                    n[2][j][i] = nn.b;
                }
            const float normalEdge = sobelSquared(n[0]) + sobelSquared(n[1]) + sobelSquared(n[2]);
            edges[size_t(y) * size_t(w) + size_t(x)] =
                depthEdge(z, x > 0 && x < w - 1, y > 0 && y < h - 1) > p.depthEdge ||
                normalEdge > p.normalEdge * p.normalEdge;
        }
    return edges;
}

ImageF toonImage(const ImageF& hdr, const ImageF& position, const ImageF& normal, const ToonParams& p) {
    std::vector<unsigned char> edges = toonEdges(position, normal, p);
    ImageF out = blank(hdr.width, hdr.height);
    for (int y = 0; y < hdr.height; ++y)
        for (int x = 0; x < hdr.width; ++x) {
            const size_t i = size_t(y) * size_t(hdr.width) + size_t(x);
            Rgb c = sanitize(texel(hdr, x, y));
            if (edges[i]) c = Rgb{};
            else if (position.rgba[i * 4 + 3] > 0.0f) c = scale(c, toonScale(luminance(c), p.levels));
            put(out, x, y, sanitize(c), Storage::Half);
        }
    return out;
}

}  // namespace lp::post
