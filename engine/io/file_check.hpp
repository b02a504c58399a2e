#pragma once
// The one place where every input file the program reads (scene, OBJ, MTL, textures, environment
// maps) is checked before it is opened: it must exist, be a regular file (a FIFO would block the
// read forever, /dev/zero never ends, a folder is not data) and be no larger than a sane limit.
// Every failure is an lp::Error "<path>: <what is wrong>".
#include <cstdint>
#include <filesystem>
#include <string>

namespace lp {

// Sane upper bounds, per kind of file: far above any real asset, far below "out of memory".
constexpr uintmax_t kMaxTextFileBytes = uintmax_t(1) << 30;   // scene, OBJ, MTL: 1 GiB
constexpr uintmax_t kMaxImageFileBytes = uintmax_t(1) << 31;  // textures, environment maps: 2 GiB

// Throws unless `path` names an existing regular file (after symlinks) of at most maxBytes.
// `kind`, with its article, words the folder case ("is a folder, not an OBJ file"). Returns the file's size.
uintmax_t requireRegularFile(const std::filesystem::path& path, uintmax_t maxBytes, const std::string& kind = "a file");

// The whole file, checked as above and read without blocking on special files; a read error or a
// short read is an error naming the file. A leading UTF-8 byte order mark is removed when stripBom.
// With stripBom the file is text: requireUtf8Text applies.
std::string readFileChecked(const std::filesystem::path& path, uintmax_t maxBytes, const std::string& kind = "a file",
                            bool stripBom = false);
// Throws "<path>: ..." for text that is not UTF-8: a UTF-16 byte order mark, or any NUL byte.
void requireUtf8Text(const std::filesystem::path& path, const std::string& text);

}  // namespace lp
