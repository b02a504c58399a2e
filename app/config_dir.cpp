#include "app/config_dir.hpp"

#include <string>

namespace lp::app {

std::filesystem::path userConfigDir(const std::function<const char*(const char*)>& getenv) {
    auto value = [&](const char* name) {
        const char* v = getenv(name);
        return std::string(v ? v : "");
    };
    if (const std::string dir = value("LIGHTPASS_CONFIG_DIR"); !dir.empty()) return dir;
    if (const std::string xdg = value("XDG_CONFIG_HOME"); !xdg.empty() && std::filesystem::path(xdg).is_absolute())
        return std::filesystem::path(xdg) / "lightpass";
    if (const std::string home = value("HOME"); !home.empty()) return std::filesystem::path(home) / ".config" / "lightpass";
    return {};
}

}  // namespace lp::app
