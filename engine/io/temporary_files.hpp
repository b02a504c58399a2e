#pragma once
// Temporary output files ("out.png.tmp-<pid>", written beside their target and renamed over it when
// whole) removed when a signal ends the process: SIGINT (Ctrl-C), SIGTERM (kill) or SIGHUP (a closed
// terminal) arriving while one exists used to leave it behind.
#include <filesystem>

namespace lp {

// Called once at start (main): for SIGINT, SIGTERM and SIGHUP whose action is the default, a handler
// that removes every registered temporary (unlink only: async-signal-safe) and raises the signal again
// with its default action, so the process ends as it would have (killed by that signal). A signal the
// parent set to be ignored (nohup, a background job) stays ignored. SIGXFSZ (a write past the file-size
// limit, RLIMIT_FSIZE), whose default ends the process on the spot, is ignored instead: the write then
// fails with EFBIG, which the writer reports ("out.png: cannot write: File too large") after removing
// its temporary. Idempotent.
void installTemporaryFileCleanup();

struct TemporaryFileEntry;

// While it lives, `path` is removed if one of those signals ends the process. Registering takes a lock;
// the handler takes none (it walks a list that only grows, reading each entry's flag).
class TemporaryFileGuard {
public:
    explicit TemporaryFileGuard(const std::filesystem::path& path);
    ~TemporaryFileGuard();
    TemporaryFileGuard(TemporaryFileGuard&& other) noexcept : entry_(other.entry_) { other.entry_ = nullptr; }
    TemporaryFileGuard& operator=(TemporaryFileGuard&& other) noexcept;
    TemporaryFileGuard(const TemporaryFileGuard&) = delete;
    TemporaryFileGuard& operator=(const TemporaryFileGuard&) = delete;

private:
    TemporaryFileEntry* entry_ = nullptr;
};

// Number of paths registered now (tests).
size_t registeredTemporaryFiles();

}  // namespace lp
