#pragma once
// What `auto` settings measured on a GPU, kept between runs so that the next start does not measure
// again: one JSON file per user, one section per choice (the post backend's times, the shadow
// raster), each section's entries keyed by what the measurement depends on (the GPU, its driver, ...).
//
//   { "version": 1, "sections": { "post_backend": { KEY: {...} }, "shadow_raster": { KEY: "compute" } } }
//
// The owner of a section checks its entries; this file only reads and writes them. No GL here.
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace lp {

// $LIGHTPASS_CACHE_DIR/measured_choices.json when set, else $XDG_CACHE_HOME/lightpass/... (an
// absolute XDG_CACHE_HOME only, as the XDG spec requires), else $HOME/.cache/lightpass/...; empty
// when none is set: nothing is cached then (never the working directory).
std::filesystem::path measuredCachePath(const std::function<const char*(const char*)>& getenv);
std::filesystem::path measuredCachePath();  // of this process's environment

struct MeasuredSection {
    nlohmann::json entries = nlohmann::json::object();  // key -> what the owner stored
    std::string warning;  // set when the file exists but cannot be used: the caller measures again
};
// One section's entries. A missing file or section is empty without a warning; an unreadable,
// malformed or other-version file is empty with a one-line warning naming the file. Never throws.
MeasuredSection readMeasuredSection(const std::filesystem::path& file, const std::string& section);
// Replaces one section and keeps the others (an unusable file is replaced whole). Written to a
// temporary file renamed into place, so a crash never leaves half a file; returns a one-line
// warning instead of throwing when it cannot.
std::string writeMeasuredSection(const std::filesystem::path& file, const std::string& section,
                                 const nlohmann::json& entries);

}  // namespace lp
