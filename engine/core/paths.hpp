#pragma once
// Where lightpass finds its data (shaders/, scenes/, models/, hdr/), whatever the working directory:
//   1. $LIGHTPASS_DATA_DIR;
//   2. an install next to the executable: <bin>/../share/lightpass (cmake --install);
//   3. the source tree the binary was built from (a build tree);
//   4. the working directory (a copy of the repository).
// The first that holds shaders/common is used.
#include <filesystem>
#include <string>

namespace lp {

std::filesystem::path dataRoot();
// A user's relative path that does not exist from the working directory, looked up in the data root
// ("scenes/cornell.json" from anywhere; a bundled scene by name: "cornell"). Unchanged otherwise.
std::string resolveDataPath(const std::string& path);

}  // namespace lp
