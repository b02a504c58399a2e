#include "engine/gl/shader_reload.hpp"

#include <algorithm>
#include <system_error>

#include "engine/core/error.hpp"

namespace lp::gl {
namespace fs = std::filesystem;

namespace {
decltype(ShaderFileWatcher::stamps) scan(const fs::path& root) {
    decltype(ShaderFileWatcher::stamps) stamps;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code fileEc;
        if (!it->is_regular_file(fileEc)) continue;
        auto time = it->last_write_time(fileEc);
        auto size = it->file_size(fileEc);
        if (fileEc) continue;  // removed between listing and stat: the next poll sees it gone
        stamps[fs::relative(it->path(), root).generic_string()] = {time, size};
    }
    return stamps;
}
}  // namespace

ShaderFileWatcher watchShaderFiles(const fs::path& root) { return {root, scan(root)}; }

std::vector<std::string> pollChangedShaderFiles(ShaderFileWatcher& watcher) {
    auto now = scan(watcher.root);
    std::vector<std::string> changed;
    for (const auto& [file, stamp] : now) {
        auto old = watcher.stamps.find(file);
        if (old == watcher.stamps.end() || old->second != stamp) changed.push_back(file);
    }
    for (const auto& [file, stamp] : watcher.stamps)
        if (!now.count(file)) changed.push_back(file);
    watcher.stamps = std::move(now);
    return changed;
}

ShaderReloadResult rebuildProgramsReading(const ShaderLibrary& shaders, const std::vector<std::string>& changedFiles) {
    ShaderReloadResult result;
    auto reads = [&](const std::string& file) {
        return std::find(changedFiles.begin(), changedFiles.end(), file) != changedFiles.end();
    };
    for (const ProgramRecipe& recipe : shaders.builtPrograms()) {
        bool affected = false;
        try {
            for (const auto& stage : recipe.stages)
                for (const auto& file : shaders.preprocess(stage, recipe.defines).files) affected = affected || reads(file);
        } catch (const Error& e) {  // an #include broke or a file vanished
            affected = true;
            if (result.error.empty()) result.error = e.what();
        }
        if (!affected) continue;
        result.affected.push_back(recipe);
        if (!result.error.empty()) continue;  // one error is enough to keep the old programs
        try {
            shaders.build(recipe);
        } catch (const Error& e) {
            result.error = e.what();
        }
    }
    return result;
}

}  // namespace lp::gl
