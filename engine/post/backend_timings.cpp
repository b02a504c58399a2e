#include "engine/post/backend_timings.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

namespace lp::post {

namespace {
constexpr int kCacheVersion = 1;
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
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return out;
    auto bad = [&](const std::string& what) {
        out.entries.clear();
        out.warning = file.string() + ": " + what + "; measuring again";
        return out;
    };
    std::ifstream in(file);
    if (!in) return bad("cannot be read");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception&) {
        return bad("not valid JSON");
    }
    if (!j.is_object() || !j.contains("version") || !j["version"].is_number_integer() || j["version"] != kCacheVersion)
        return bad("not a version " + std::to_string(kCacheVersion) + " post-backend timing cache");
    if (!j.contains("entries") || !j["entries"].is_object()) return bad("no \"entries\" object");
    for (const auto& [key, value] : j["entries"].items()) {
        if (!value.is_object() || !value.contains("cuda_ms") || !value.contains("glsl_ms") ||
            !value["cuda_ms"].is_number() || !value["glsl_ms"].is_number())
            return bad("entry \"" + key + "\" needs numbers cuda_ms and glsl_ms");
        BackendTimes t{value["cuda_ms"].get<double>(), value["glsl_ms"].get<double>()};
        if (!std::isfinite(t.cudaMs) || !std::isfinite(t.glslMs) || !t.measured())
            return bad("entry \"" + key + "\" has a negative or non-finite time");
        out.entries[key] = t;
    }
    return out;
}

std::string writeTimingCache(const std::filesystem::path& file, const TimingCache& entries) {
    nlohmann::json j;
    j["version"] = kCacheVersion;
    j["entries"] = nlohmann::json::object();
    for (const auto& [key, t] : entries) j["entries"][key] = {{"cuda_ms", t.cudaMs}, {"glsl_ms", t.glslMs}};
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec) return file.parent_path().string() + ": cannot create the cache folder (" + ec.message() + ")";
    const std::filesystem::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        out << j.dump(2) << "\n";
        if (!out) return tmp.string() + ": cannot write the post-backend timing cache";
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return file.string() + ": cannot replace the post-backend timing cache";
    }
    return {};
}

std::filesystem::path timingCachePath(const std::function<const char*(const char*)>& getenv) {
    const std::string name = "post_backend_timings.json";
    auto set = [&](const char* var) -> std::string {
        const char* v = getenv(var);
        return v ? v : "";
    };
    if (const std::string dir = set("LIGHTPASS_CACHE_DIR"); !dir.empty()) return std::filesystem::path(dir) / name;
    if (const std::string xdg = set("XDG_CACHE_HOME"); !xdg.empty() && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "lightpass" / name;
    if (const std::string home = set("HOME"); !home.empty())
        return std::filesystem::path(home) / ".cache" / "lightpass" / name;
    return {};
}

}  // namespace lp::post
