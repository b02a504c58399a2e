#pragma once
// Logging to stderr. Warnings are counted so tests and the CLI can tell a clean load from a fallback.
#include <string>

namespace lp {

enum class LogLevel { Debug = 0, Info = 1, Warn = 2, Error = 3, Quiet = 4 };

void setLogLevel(LogLevel level);
LogLevel logLevel();
void logDebug(const std::string& message);
void logInfo(const std::string& message);
void logWarn(const std::string& message);
void logError(const std::string& message);
// Number of warnings logged since start (or since the last reset); lets tests assert "warned".
int warningCount();
void resetWarningCount();

}  // namespace lp
