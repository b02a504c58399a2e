#pragma once
// Per-pass GPU time from GL timestamp queries, kept in a ring of frames so reading a result never
// waits for the GPU: frame N's queries are read when frame N + kFramesInFlight begins.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "engine/gl/handles.hpp"

namespace lp::gl {

class GpuTimerRing {
public:
    static constexpr int kFramesInFlight = 4;

    void beginFrame();
    void beginPass(const std::string& name);
    void endPass();
    void endFrame();
    // Adds a time measured elsewhere (CUDA events) to the current frame's record.
    void addExternal(const std::string& name, double ms);
    // Waits for every outstanding query (end of a headless run).
    void flush();
    // CPU ms the last beginFrame() waited for the results of the frame kFramesInFlight before: how
    // far the GPU lags the CPU (0 when the CPU is the bottleneck).
    double lastWaitMs() const { return lastWaitMs_; }

    // Samples in ms per pass name, in first-seen order; "frame" is the whole frame.
    const std::vector<std::string>& passOrder() const { return order_; }
    const std::vector<double>& samples(const std::string& name) const;
    double median(const std::string& name) const;
    void clear();
    // Keep only the newest `count` samples per pass (the viewer's rolling window).
    void trim(size_t count);

private:
    struct Pending {
        std::string name;
        Query begin, end;
    };
    struct Slot {
        std::vector<Pending> passes;
        std::vector<std::pair<std::string, double>> external;
        bool used = false;
    };
    void collect(Slot& slot);
    Pending& newPending(const std::string& name);

    std::array<Slot, kFramesInFlight> slots_;
    std::vector<Pending> freeQueries_;
    int current_ = 0;
    double lastWaitMs_ = 0.0;
    std::map<std::string, std::vector<double>> samples_;
    std::vector<std::string> order_;
};

double median(std::vector<double> values);

}  // namespace lp::gl
