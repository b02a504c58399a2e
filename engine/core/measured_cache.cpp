#include "engine/core/measured_cache.hpp"

#include <cstdlib>
#include <fstream>
#include <system_error>

namespace lp {

namespace {

constexpr int kVersion = 1;
constexpr const char* kFileName = "measured_choices.json";

// The whole file, or an empty object with `warning` set when it exists but cannot be used.
nlohmann::json readFile(const std::filesystem::path& file, std::string& warning) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return nlohmann::json::object();
    auto bad = [&](const std::string& what) {
        warning = file.string() + ": " + what + "; measuring again";
        return nlohmann::json::object();
    };
    std::ifstream in(file);
    if (!in) return bad("cannot be read");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const std::exception&) {
        return bad("not valid JSON");
    }
    if (!j.is_object() || !j.contains("version") || !j["version"].is_number_integer() || j["version"] != kVersion)
        return bad("not a version " + std::to_string(kVersion) + " lightpass measurement cache");
    if (!j.contains("sections") || !j["sections"].is_object()) return bad("no \"sections\" object");
    return j;
}

}  // namespace

std::filesystem::path measuredCachePath(const std::function<const char*(const char*)>& getenv) {
    auto value = [&](const char* var) -> std::string {
        const char* v = getenv(var);
        return v ? v : "";
    };
    if (const std::string dir = value("LIGHTPASS_CACHE_DIR"); !dir.empty()) return std::filesystem::path(dir) / kFileName;
    if (const std::string xdg = value("XDG_CACHE_HOME"); !xdg.empty() && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "lightpass" / kFileName;
    if (const std::string home = value("HOME"); !home.empty())
        return std::filesystem::path(home) / ".cache" / "lightpass" / kFileName;
    return {};
}

std::filesystem::path measuredCachePath() {
    return measuredCachePath([](const char* var) { return std::getenv(var); });
}

MeasuredSection readMeasuredSection(const std::filesystem::path& file, const std::string& section) {
    MeasuredSection out;
    const nlohmann::json j = readFile(file, out.warning);
    if (!out.warning.empty() || !j.contains("sections")) return out;
    const nlohmann::json& sections = j["sections"];
    if (!sections.contains(section)) return out;
    if (!sections[section].is_object()) {
        out.warning = file.string() + ": section \"" + section + "\" is not an object; measuring again";
        return out;
    }
    out.entries = sections[section];
    return out;
}

std::string writeMeasuredSection(const std::filesystem::path& file, const std::string& section,
                                 const nlohmann::json& entries) {
    std::string unusable;  // an unusable file is replaced whole
    nlohmann::json j = readFile(file, unusable);
    j["version"] = kVersion;
    if (!j.contains("sections")) j["sections"] = nlohmann::json::object();
    j["sections"][section] = entries;
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
    if (ec) return file.parent_path().string() + ": cannot create the cache folder (" + ec.message() + ")";
    const std::filesystem::path tmp = file.string() + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        out << j.dump(2) << "\n";
        if (!out) {
            out.close();
            std::filesystem::remove(tmp, ec);
            return tmp.string() + ": cannot write the measurement cache";
        }
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return file.string() + ": cannot replace the measurement cache";
    }
    return {};
}

}  // namespace lp
