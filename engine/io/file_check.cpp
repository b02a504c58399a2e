#include "engine/io/file_check.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.hpp"

namespace lp {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& path, const std::string& what) { throw Error(shownPath(path) + ": " + what); }

std::string typeName(mode_t mode) {
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

// One check for stat results, whether they came from a path or an open descriptor.
uintmax_t checkStat(const fs::path& path, const struct stat& st, uintmax_t maxBytes, const std::string& kind) {
    if (S_ISDIR(st.st_mode)) fail(path, "is a folder, not " + kind);
    if (!S_ISREG(st.st_mode)) {
        const std::string type = typeName(st.st_mode);
        fail(path, type == "not a regular file" ? type : "is " + type + ", not a regular file");
    }
    const uintmax_t size = uintmax_t(st.st_size);
    if (size > maxBytes)
        fail(path, "file is " + std::to_string(size) + " bytes, over the " + std::to_string(maxBytes) + "-byte limit");
    return size;
}

// Closes on every path out of readFileChecked.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

uintmax_t requireRegularFile(const fs::path& path, uintmax_t maxBytes, const std::string& kind) {
    if (path.empty()) throw Error("(empty path): file not found");
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
        const int err = errno;
        fail(path, err == ENOENT || err == ENOTDIR ? "file not found" : std::string("cannot be read: ") + std::strerror(err));
    }
    return checkStat(path, st, maxBytes, kind);
}

std::string readFileChecked(const fs::path& path, uintmax_t maxBytes, const std::string& kind, bool stripBom) {
    requireRegularFile(path, maxBytes, kind);
    // O_NONBLOCK: if the path was swapped for a FIFO after the check, open() must not wait for a writer;
    // the descriptor is checked again, so what is read is what was checked.
    Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) fail(path, std::string("cannot be read: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) fail(path, std::string("cannot be read: ") + std::strerror(errno));
    const uintmax_t size = checkStat(path, st, maxBytes, kind);
    std::string text(size_t(size), '\0');
    size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::read(file.fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(path, std::string("read failed: ") + std::strerror(errno));
        if (n == 0) fail(path, "file shrank while being read (" + std::to_string(done) + " of " + std::to_string(size) + " bytes)");
        done += size_t(n);
    }
    if (stripBom) {
        requireUtf8Text(path, text);
        if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
    }
    return text;
}

void requireUtf8Text(const fs::path& path, const std::string& text) {
    // UTF-16 read as bytes fails far from its cause ("no triangles", "invalid literal"), and JSON and
    // OBJ parsers stop at a NUL as if the file ended there, silently dropping the rest.
    if (text.compare(0, 2, "\xFF\xFE") == 0 || text.compare(0, 2, "\xFE\xFF") == 0)
        fail(path, "is UTF-16 text (it starts with a UTF-16 byte order mark); save it as UTF-8");
    const size_t nul = text.find('\0');
    if (nul != std::string::npos)
        fail(path, "byte " + std::to_string(nul) + " is NUL: not UTF-8 text (UTF-16 without a byte order mark, or a binary file)");
}

}  // namespace lp
