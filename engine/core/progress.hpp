#pragma once
// Progress of work that takes seconds (multi-frame renders, the IBL bake, bench and sweep), on
// stderr: on a terminal one line redrawn in place (bar, percentage, count, time left); elsewhere (CI,
// a pipe) one plain line per tenth of the work (or per step, where a step is seconds of work); nothing with -q, and nothing for work done within
// the first seconds.
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace lp {

// Seconds on a monotonic clock; tests pass a fake one.
using ProgressClock = std::function<double()>;

struct ProgressStyle {
    bool terminal = false;           // redraw one line in place; otherwise plain lines
    bool quiet = false;              // show nothing at all
    double showAfterSeconds = 2.0;   // work that finishes sooner shows nothing; 0: from the first step
    double redrawSeconds = 0.1;      // a terminal line is redrawn at most this often (the last step always)
    bool plainLinePerStep = false;   // plain lines: one per step (bench variants, sweep values), not per tenth
    bool sharesLogStream = false;    // drawn on stderr, where the log writes: a log line clears an open bar first
};

// Seconds left at the average rate so far; negative when unknown (nothing done yet).
double progressSecondsLeft(double elapsedSeconds, size_t done, size_t total);
// The reporter's estimate: the first step carries one-off costs (shader compiles, the first frame's
// IBL bake), so from the second step on the rate is that of the steps after it.
double progressSecondsLeftAfterFirstStep(double elapsedSeconds, double firstStepSeconds, size_t done, size_t total);

// "about 12 s left", "about 3 min 05 s left"; empty when unknown.
std::string progressTimeLeftText(double secondsLeft);

// The text of one progress line: "LABEL  45% 9/20, about 3 s left: NOTE" (plain), with a
// "[#########...........]" bar before the percentage when `bar`; no estimate when secondsLeft < 0.
std::string progressLineText(const std::string& label, size_t done, size_t total, double secondsLeft,
                             const std::string& note, bool bar);

// One piece of work of `total` steps. step() after each; the destructor finishes it.
class ProgressReporter {
public:
    ProgressReporter(std::string label, size_t total, std::ostream& out, ProgressStyle style, ProgressClock clock);
    ~ProgressReporter();
    ProgressReporter(const ProgressReporter&) = delete;
    ProgressReporter& operator=(const ProgressReporter&) = delete;

    // One more step done; `note` says which (a variant's flags, a mip level).
    void step(const std::string& note = {});
    // The last line: on a terminal the finished bar and a newline, in plain lines "LABEL done in T s
    // (N/N)"; nothing when nothing was shown (unless shown from the start), and no "done" for work cut
    // short (an exception). Called again (or by the destructor) it does nothing.
    void finish();
    bool shown() const { return shown_; }

private:
    void draw(const std::string& note);
    std::string label_;
    size_t total_, done_ = 0;
    std::ostream* out_;
    ProgressStyle style_;
    ProgressClock clock_;
    double start_, firstStepEnd_ = 0.0, lastDraw_ = -1.0;
    bool shown_ = false, finished_ = false;
    size_t lastTenth_ = 0;  // plain lines: the tenth of the work the last line reported
};

// How stderr's progress looks here: a terminal or not (isatty), quiet when the log shows errors only
// (-q), and from the first step when setProgressFromStart(true) (--progress).
ProgressStyle stderrProgressStyle();
void setProgressFromStart(bool fromStart);
// A monotonic clock in seconds (std::chrono::steady_clock).
double steadySeconds();

}  // namespace lp
