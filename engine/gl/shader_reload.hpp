#pragma once
// Shader hot reload: a watcher that polls the shader tree's modification times, and a check that
// rebuilds every program whose source or any #include changed, so a caller can drop its programs
// only when all of them still compile (a broken edit keeps the last good programs running).
#include <filesystem>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/gl/shader.hpp"

namespace lp::gl {

struct ShaderFileWatcher {
    std::filesystem::path root;
    // relative path -> (modification time, size) at the last poll
    std::map<std::string, std::pair<std::filesystem::file_time_type, std::uintmax_t>> stamps;
};

// Records the current state of every file under `root` (nothing counts as changed yet).
ShaderFileWatcher watchShaderFiles(const std::filesystem::path& root);
// Files (relative to the root, '/'-separated) added, removed or modified since the last poll.
std::vector<std::string> pollChangedShaderFiles(ShaderFileWatcher& watcher);

struct ShaderReloadResult {
    std::vector<ProgramRecipe> affected;  // programs that read one of the changed files
    std::string error;                    // first failure ("shader compile failed: shaders/x:12: ..."), or empty
    bool ok() const { return error.empty(); }
};

// Rebuilds (and discards) every program `shaders` has built that reads one of `changedFiles`.
// Needs a current GL context; a file that no longer preprocesses counts as affected and failing.
ShaderReloadResult rebuildProgramsReading(const ShaderLibrary& shaders, const std::vector<std::string>& changedFiles);

}  // namespace lp::gl
