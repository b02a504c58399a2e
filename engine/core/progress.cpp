#include "engine/core/progress.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <unistd.h>

#include "engine/core/log.hpp"

namespace lp {
namespace {
std::atomic<bool> gFromStart{false};
constexpr int kBarWidth = 24;
}  // namespace

double progressSecondsLeft(double elapsedSeconds, size_t done, size_t total) {
    if (done == 0 || total == 0) return -1.0;
    if (done >= total) return 0.0;
    return elapsedSeconds / double(done) * double(total - done);
}

double progressSecondsLeftAfterFirstStep(double elapsedSeconds, double firstStepSeconds, size_t done, size_t total) {
    if (done < 2 || total < 2) return progressSecondsLeft(elapsedSeconds, done, total);
    return progressSecondsLeft(elapsedSeconds - firstStepSeconds, done - 1, total - 1);
}

std::string progressTimeLeftText(double secondsLeft) {
    if (!(secondsLeft >= 0.0)) return "";
    const long s = std::lround(std::ceil(secondsLeft));
    char text[64];
    if (s < 60) std::snprintf(text, sizeof text, "about %ld s left", s);
    else std::snprintf(text, sizeof text, "about %ld min %02ld s left", s / 60, s % 60);
    return text;
}

std::string progressLineText(const std::string& label, size_t done, size_t total, double secondsLeft,
                             const std::string& note, bool bar) {
    const size_t shownDone = std::min(done, total);
    const int percent = total ? int(100 * shownDone / total) : 100;
    std::string line = label + " ";
    if (bar) {
        const int filled = total ? int(kBarWidth * shownDone / total) : kBarWidth;
        line += "[" + std::string(size_t(filled), '#') + std::string(size_t(kBarWidth - filled), '.') + "] ";
    }
    char count[64];
    std::snprintf(count, sizeof count, "%3d%% %zu/%zu", percent, shownDone, total);
    line += count;
    const std::string left = shownDone < total ? progressTimeLeftText(secondsLeft) : "";
    if (!left.empty()) line += ", " + left;
    if (!note.empty()) line += ": " + note;
    return line;
}

ProgressReporter::ProgressReporter(std::string label, size_t total, std::ostream& out, ProgressStyle style,
                                   ProgressClock clock)
    : label_(std::move(label)), total_(total), out_(&out), style_(style), clock_(std::move(clock)), start_(clock_()) {}

ProgressReporter::~ProgressReporter() { finish(); }

void ProgressReporter::draw(const std::string& note) {
    const double now = clock_();
    const double left = progressSecondsLeftAfterFirstStep(now - start_, firstStepEnd_ - start_, done_, total_);
    const std::string line = progressLineText(label_, done_, total_, left, note, style_.terminal);
    if (style_.terminal) *out_ << "\r\033[K" << line << std::flush;  // the same line, redrawn
    else *out_ << line << "\n" << std::flush;
    if (style_.terminal && style_.sharesLogStream) setProgressLineOpen(true);
    lastDraw_ = now;
    shown_ = true;
}

void ProgressReporter::step(const std::string& note) {
    if (finished_) return;
    ++done_;
    if (style_.quiet) return;
    const double now = clock_();
    if (done_ == 1) firstStepEnd_ = now;
    const double elapsed = now - start_;
    const size_t tenth = total_ ? std::min<size_t>(10, 10 * std::min(done_, total_) / total_) : 10;
    const bool last = done_ >= total_;
    // Work that ends within the first seconds shows nothing; longer work shows from the step that
    // passes them.
    if (!shown_ && (elapsed < style_.showAfterSeconds || (last && style_.showAfterSeconds > 0.0))) return;
    if (last) {  // finish() draws the finished bar or the done line; a per-step log has this step's line too
        if (!style_.terminal && style_.plainLinePerStep) draw(note);
        return;
    }
    const bool due = !shown_ || (style_.terminal ? now - lastDraw_ >= style_.redrawSeconds
                                                 : style_.plainLinePerStep || tenth > lastTenth_);
    if (!due) return;
    lastTenth_ = tenth;
    draw(note);
}

void ProgressReporter::finish() {
    if (finished_) return;
    finished_ = true;
    if (style_.quiet || !(shown_ || style_.showAfterSeconds <= 0.0)) return;
    if (style_.sharesLogStream) setProgressLineOpen(false);  // ended below with a newline
    if (done_ < total_) {  // cut short (an error): end the bar's line where it stopped, claim nothing
        if (shown_ && style_.terminal) *out_ << "\n" << std::flush;
        return;
    }
    const double elapsed = clock_() - start_;
    char took[48];
    std::snprintf(took, sizeof took, "done in %.1f s", elapsed);
    if (style_.terminal)
        *out_ << "\r\033[K" << progressLineText(label_, done_, total_, 0.0, took, true) << "\n" << std::flush;
    else
        *out_ << label_ << " " << took << " (" << std::min(done_, total_) << "/" << total_ << ")\n" << std::flush;
}

ProgressStyle stderrProgressStyle() {
    ProgressStyle style;
    style.terminal = isatty(fileno(stderr)) != 0;
    style.quiet = logLevel() >= LogLevel::Error;
    style.sharesLogStream = true;
    if (gFromStart.load()) style.showAfterSeconds = 0.0;
    return style;
}

void setProgressFromStart(bool fromStart) { gFromStart = fromStart; }

double steadySeconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace lp
