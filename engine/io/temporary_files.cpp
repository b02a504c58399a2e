#include "engine/io/temporary_files.hpp"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>

namespace lp {

// One registered path. Entries are never freed: a handler may be walking the list at any moment, so
// an entry no longer live is reused by the next registration instead.
struct TemporaryFileEntry {
    std::atomic<bool> live{false};
    char path[PATH_MAX] = {};
    TemporaryFileEntry* next = nullptr;  // fixed before the entry is published
};

namespace {

std::atomic<TemporaryFileEntry*> gHead{nullptr};
std::mutex gRegistration;  // registering and releasing; never taken by the handler

constexpr int kCleanedSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void removeTemporariesAndReraise(int sig) {
    const int savedErrno = errno;
    for (TemporaryFileEntry* e = gHead.load(std::memory_order_acquire); e; e = e->next)
        if (e->live.load(std::memory_order_acquire)) ::unlink(e->path);
    errno = savedErrno;
    // SA_RESETHAND restored the default action; the signal, raised again, is delivered when the handler
    // returns and ends the process as it would have without the handler.
    ::raise(sig);
}

}  // namespace

void installTemporaryFileCleanup() {
    for (const int sig : kCleanedSignals) {
        struct sigaction current {};
        if (::sigaction(sig, nullptr, &current) != 0) continue;
        if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) continue;  // ignored, or ours already
        struct sigaction action {};
        action.sa_handler = removeTemporariesAndReraise;
        action.sa_flags = SA_RESETHAND;
        sigemptyset(&action.sa_mask);
        for (const int other : kCleanedSignals) sigaddset(&action.sa_mask, other);  // one cleanup at a time
        ::sigaction(sig, &action, nullptr);
    }
    struct sigaction current {};
    if (::sigaction(SIGXFSZ, nullptr, &current) == 0 && !(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_DFL) {
        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        sigemptyset(&ignore.sa_mask);
        ::sigaction(SIGXFSZ, &ignore, nullptr);
    }
}

TemporaryFileGuard::TemporaryFileGuard(const std::filesystem::path& path) {
    const std::string& p = path.native();
    if (p.empty() || p.size() >= PATH_MAX) return;  // no such file can be created either
    std::lock_guard<std::mutex> lock(gRegistration);
    TemporaryFileEntry* e = gHead.load(std::memory_order_acquire);
    while (e && e->live.load(std::memory_order_relaxed)) e = e->next;
    if (!e) {
        e = new TemporaryFileEntry;  // lives as long as the process: see TemporaryFileEntry
        e->next = gHead.load(std::memory_order_relaxed);
        std::memcpy(e->path, p.c_str(), p.size() + 1);
        e->live.store(true, std::memory_order_release);
        gHead.store(e, std::memory_order_release);
    } else {
        std::memcpy(e->path, p.c_str(), p.size() + 1);
        e->live.store(true, std::memory_order_release);
    }
    entry_ = e;
}

TemporaryFileGuard::~TemporaryFileGuard() {
    if (!entry_) return;
    std::lock_guard<std::mutex> lock(gRegistration);
    entry_->live.store(false, std::memory_order_release);
}

TemporaryFileGuard& TemporaryFileGuard::operator=(TemporaryFileGuard&& other) noexcept {
    if (this != &other) {
        if (entry_) {
            std::lock_guard<std::mutex> lock(gRegistration);
            entry_->live.store(false, std::memory_order_release);
        }
        entry_ = other.entry_;
        other.entry_ = nullptr;
    }
    return *this;
}

size_t registeredTemporaryFiles() {
    std::lock_guard<std::mutex> lock(gRegistration);
    size_t n = 0;
    for (TemporaryFileEntry* e = gHead.load(std::memory_order_acquire); e; e = e->next) n += e->live.load() ? 1 : 0;
    return n;
}

}  // namespace lp
