#pragma once
// Logging to stderr. Warnings are counted so tests and the CLI can tell a clean load from a fallback.
#include <string>

namespace lp {

enum class LogLevel { Debug = 0, Info = 1, Warn = 2, Error = 3, Quiet = 4 };

void setLogLevel(LogLevel level);
LogLevel logLevel();
void logDebug(const std::string& message);
void logInfo(const std::string& message);
// Warnings and errors are printed as one line (oneLineMessage: control characters escaped, cut after
// 600 characters). A warning identical to the one logged just before is not printed again, only counted; the count is
// printed ("<warning> (repeated N more times)") before the next other message or by the flush below.
void logWarn(const std::string& message);
// Prints a pending repeat count; the CLI calls it before its last line.
void flushRepeatedWarnings();
void logError(const std::string& message);
// Whether stderr's last line is an unfinished progress line (engine/core/progress.hpp): the next
// message first clears it, so it starts on a clean line (the bar is drawn again at its next step).
void setProgressLineOpen(bool open);
// Number of warnings logged since start (or since the last reset); lets tests assert "warned".
int warningCount();
void resetWarningCount();

}  // namespace lp
