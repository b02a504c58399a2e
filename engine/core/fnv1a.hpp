#pragma once
// FNV-1a over raw bytes: a cheap fingerprint of what a cached result was made from (a value's bytes,
// bit for bit), for caches that compare signatures instead of keeping the inputs.
#include <cstddef>
#include <cstdint>

namespace lp {

struct Fnv1a {
    uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    template <typename T>
    void add(const T& v) {
        add(&v, sizeof v);
    }
};

}  // namespace lp
