#include "stage_clock.h"

namespace gbl {

const char* stageName(Stage s) {
    switch (s) {
        case Stage::Setup: return "set-up";
        case Stage::ShaderCompile: return "shader compile";
        case Stage::Precompute: return "pre-computation";
        case Stage::Render: return "rendering";
        case Stage::Readback: return "read-back";
        case Stage::Metrics: return "metrics";
        case Stage::Report: return "report writing";
        case Stage::Other: return "other";
    }
    return "?";
}

StageClock& StageClock::global() {
    static StageClock clock;
    return clock;
}

void StageClock::start() {
    running_ = true;
    owner_ = std::this_thread::get_id();
    stack_.clear();
    ms_.fill(0.0);
    start_ = last_ = Clock::now();
}

void StageClock::charge(Clock::time_point now) {
    const Stage current = stack_.empty() ? Stage::Other : stack_.back();
    ms_[size_t(current)] += std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
}

void StageClock::push(Stage s) {
    charge(Clock::now());
    stack_.push_back(s);
}

void StageClock::pop() {
    charge(Clock::now());
    if (!stack_.empty()) stack_.pop_back();
}

StageTimes StageClock::read() const {
    StageTimes t;
    t.ms = ms_;
    if (!running_) return t;
    const Clock::time_point now = Clock::now();
    const Stage current = stack_.empty() ? Stage::Other : stack_.back();
    t.ms[size_t(current)] += std::chrono::duration<double, std::milli>(now - last_).count();
    for (double v : t.ms) t.totalMs += v;
    return t;
}

ScopedStage::ScopedStage(Stage s) : active_(StageClock::global().running()) {
    if (active_) StageClock::global().push(s);
}

ScopedStage::~ScopedStage() {
    if (active_) StageClock::global().pop();
}

}  // namespace gbl
