#include "engine/core/log.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>

#include "engine/core/error.hpp"

namespace lp {
namespace {
std::atomic<int> gLevel{static_cast<int>(LogLevel::Info)};
std::atomic<int> gWarnings{0};
std::atomic<bool> gProgressLineOpen{false};

// A warning identical to the one just before it is counted, not printed: a broken file repeating one
// complaint 500 times gives one line and "(repeated 499 more times)" when something else is logged
// (or flushRepeatedWarnings runs). Only consecutive repeats: the same warning later, after other
// output (a shader broken again in the viewer), is news and is printed.
struct RepeatState {
    std::mutex mutex;
    std::string lastWarning;
    size_t repeats = 0;
};
RepeatState& repeatState() {
    static RepeatState state;
    return state;
}

// With the lock held: the pending count, if any, as its own line.
void printRepeatsLocked(RepeatState& r) {
    if (r.repeats && static_cast<int>(LogLevel::Warn) >= gLevel.load())
        std::fprintf(stderr, "lightpass: warning: %s (repeated %zu more times)\n", r.lastWarning.c_str(), r.repeats);
    r.repeats = 0;
}

void emit(LogLevel level, const char* tag, const std::string& text) {
    if (static_cast<int>(level) < gLevel.load()) return;  // not shown: neither a repeat nor news
    // A warning or an error is one clean line, whatever user text or library message it carries.
    const std::string message = level >= LogLevel::Warn ? oneLineMessage(text) : text;
    RepeatState& r = repeatState();
    std::lock_guard<std::mutex> lock(r.mutex);
    if (level == LogLevel::Warn && message == r.lastWarning) {
        ++r.repeats;
        return;
    }
    if (gProgressLineOpen.exchange(false)) std::fputs("\r\033[K", stderr);  // the bar's line, cleared for this one
    printRepeatsLocked(r);
    r.lastWarning = level == LogLevel::Warn ? message : std::string();
    std::fprintf(stderr, "lightpass: %s%s\n", tag, message.c_str());
}
}  // namespace

void setLogLevel(LogLevel level) { gLevel = static_cast<int>(level); }
void setProgressLineOpen(bool open) { gProgressLineOpen = open; }
LogLevel logLevel() { return static_cast<LogLevel>(gLevel.load()); }
void logDebug(const std::string& m) { emit(LogLevel::Debug, "debug: ", m); }
void logInfo(const std::string& m) { emit(LogLevel::Info, "", m); }
void logWarn(const std::string& m) {
    ++gWarnings;
    emit(LogLevel::Warn, "warning: ", m);
}
void flushRepeatedWarnings() {
    RepeatState& r = repeatState();
    std::lock_guard<std::mutex> lock(r.mutex);
    printRepeatsLocked(r);
    r.lastWarning.clear();
}
void logError(const std::string& m) { emit(LogLevel::Error, "error: ", m); }
int warningCount() { return gWarnings.load(); }
void resetWarningCount() { gWarnings = 0; }

}  // namespace lp
