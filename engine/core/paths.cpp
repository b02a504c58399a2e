#include "engine/core/paths.hpp"

#include <cstdlib>
#include <system_error>

namespace lp {
namespace fs = std::filesystem;

namespace {
bool holdsShaders(const fs::path& root) {
    std::error_code ec;
    return fs::is_directory(root / "shaders" / "common", ec);
}

fs::path executableDir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
}
}  // namespace

fs::path dataRoot() {
    if (const char* env = std::getenv("LIGHTPASS_DATA_DIR"); env && *env) return fs::path(env);
    const fs::path bin = executableDir();
    if (!bin.empty() && holdsShaders(bin.parent_path() / "share" / "lightpass"))
        return bin.parent_path() / "share" / "lightpass";
#ifdef LIGHTPASS_SOURCE_DIR
    if (holdsShaders(LIGHTPASS_SOURCE_DIR)) return fs::path(LIGHTPASS_SOURCE_DIR);
#endif
    return fs::current_path();
}

std::string resolveDataPath(const std::string& path) {
    std::error_code ec;
    const fs::path p(path);
    if (path.empty() || p.is_absolute() || fs::exists(p, ec)) return path;
    const fs::path root = dataRoot();
    for (const fs::path& candidate : {root / p, root / "scenes" / p, root / "scenes" / (path + ".json")})
        if (fs::exists(candidate, ec)) return candidate.string();
    return path;
}

}  // namespace lp
