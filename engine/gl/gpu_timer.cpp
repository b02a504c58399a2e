#include "engine/gl/gpu_timer.hpp"

#include <algorithm>
#include <chrono>

namespace lp::gl {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + mid, v.end());
    double hi = v[mid];
    if (v.size() % 2) return hi;
    double lo = *std::max_element(v.begin(), v.begin() + mid);
    return 0.5 * (lo + hi);
}

GpuTimerRing::Pending& GpuTimerRing::newPending(const std::string& name) {
    Slot& slot = slots_[current_];
    if (!freeQueries_.empty()) {
        slot.passes.push_back(std::move(freeQueries_.back()));
        freeQueries_.pop_back();
    } else {
        slot.passes.push_back(Pending{"", makeQuery(GL_TIMESTAMP), makeQuery(GL_TIMESTAMP)});
    }
    slot.passes.back().name = name;
    return slot.passes.back();
}

void GpuTimerRing::beginFrame() {
    current_ = (current_ + 1) % kFramesInFlight;
    const auto start = std::chrono::steady_clock::now();
    collect(slots_[current_]);
    lastWaitMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    slots_[current_].used = true;
    glQueryCounter(newPending("frame").begin.id(), GL_TIMESTAMP);
}

void GpuTimerRing::beginPass(const std::string& name) {
    glQueryCounter(newPending(name).begin.id(), GL_TIMESTAMP);
}

void GpuTimerRing::endPass() {
    glQueryCounter(slots_[current_].passes.back().end.id(), GL_TIMESTAMP);
}

void GpuTimerRing::endFrame() {
    glQueryCounter(slots_[current_].passes.front().end.id(), GL_TIMESTAMP);
}

void GpuTimerRing::addExternal(const std::string& name, double ms) {
    slots_[current_].external.emplace_back(name, ms);
}

void GpuTimerRing::collect(Slot& slot) {
    if (!slot.used) return;
    auto record = [this](const std::string& name, double ms) {
        auto [it, inserted] = samples_.try_emplace(name);
        if (inserted) order_.push_back(name);
        it->second.push_back(ms);
    };
    for (auto& p : slot.passes) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(p.begin.id(), GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(p.end.id(), GL_QUERY_RESULT, &t1);
        record(p.name, t1 >= t0 ? double(t1 - t0) * 1e-6 : 0.0);
        freeQueries_.push_back(std::move(p));
    }
    for (auto& [name, ms] : slot.external) record(name, ms);
    slot.passes.clear();
    slot.external.clear();
    slot.used = false;
}

void GpuTimerRing::flush() {
    for (int i = 1; i <= kFramesInFlight; ++i) collect(slots_[(current_ + i) % kFramesInFlight]);
}

const std::vector<double>& GpuTimerRing::samples(const std::string& name) const {
    static const std::vector<double> none;
    auto it = samples_.find(name);
    return it == samples_.end() ? none : it->second;
}

double GpuTimerRing::median(const std::string& name) const { return lp::gl::median(samples(name)); }

void GpuTimerRing::clear() {
    samples_.clear();
    order_.clear();
}

void GpuTimerRing::trim(size_t count) {
    for (auto& [name, v] : samples_)
        if (v.size() > count) v.erase(v.begin(), v.end() - long(count));
}

}  // namespace lp::gl
