#include "engine/post/backend_timings.hpp"

#include <cmath>
#include <sstream>

#include "engine/core/measured_cache.hpp"

namespace lp::post {

namespace {
constexpr const char* kCacheSection = "post_backend";  // in the measurement cache (engine/core/measured_cache.hpp)
}

const char* postEffectName(PostEffect e) {
    switch (e) {
        case PostEffect::Bloom: return "bloom";
        case PostEffect::Composite: return "composite";
        case PostEffect::Toon: return "toon";
    }
    return "bloom";
}

std::string TimingKey::text() const {
    std::ostringstream k;
    k << gpu << '|' << driver << '|' << width << 'x' << height << "|kernel " << kernel << '|' << method << '|'
      << interop << '|' << postEffectName(effect);
    return k.str();
}

bool cudaWins(const BackendTimes& t) { return t.measured() && t.cudaMs < t.glslMs; }

CacheRead readTimingCache(const std::filesystem::path& file) {
    CacheRead out;
    MeasuredSection section = readMeasuredSection(file, kCacheSection);
    if (!section.warning.empty()) {
        out.warning = section.warning;
        return out;
    }
    for (const auto& [key, value] : section.entries.items()) {
        auto bad = [&](const std::string& what) {
            out.entries.clear();
            out.warning = file.string() + ": " + kCacheSection + " entry \"" + key + "\" " + what + "; measuring again";
            return out;
        };
        if (!value.is_object() || !value.contains("cuda_ms") || !value.contains("glsl_ms") ||
            !value["cuda_ms"].is_number() || !value["glsl_ms"].is_number())
            return bad("needs numbers cuda_ms and glsl_ms");
        BackendTimes t{value["cuda_ms"].get<double>(), value["glsl_ms"].get<double>()};
        if (!std::isfinite(t.cudaMs) || !std::isfinite(t.glslMs) || !t.measured()) return bad("has a negative or non-finite time");
        out.entries[key] = t;
    }
    return out;
}

std::string writeTimingCache(const std::filesystem::path& file, const TimingCache& entries) {
    nlohmann::json section = nlohmann::json::object();
    for (const auto& [key, t] : entries) section[key] = {{"cuda_ms", t.cudaMs}, {"glsl_ms", t.glslMs}};
    return writeMeasuredSection(file, kCacheSection, section);
}

}  // namespace lp::post
