#pragma once
// Wall time per stage of a command (`compare`'s set-up, shader compile, rendering, ...), exclusive:
// entering a stage pauses the one it is nested in, so the stages' times add up to the time
// measured. One process-wide clock, driven from the thread that runs the command; code deep in
// the renderer marks its stages without the clock being passed down (a ScopedStage with no clock
// started is free and records nothing).
#include <array>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace gbl {

enum class Stage {
    Setup,          // arguments, scene and environment files, Vulkan device
    ShaderCompile,  // GLSL -> SPIR-V (glslang) and the driver's pipeline compile
    Precompute,     // IBL maps (cache or computed), scene and environment upload
    Render,         // the submitted frame: G-buffer, (material,) lighting passes, waited for
    Readback,       // G-buffer decode pass, images copied to the host
    Metrics,        // attribute errors, image errors, FLIP
    Report,         // PNG / EXR images, crops, report.json / .csv / .html
    Other,          // anything between marked stages
};
inline constexpr size_t kStageCount = 8;
const char* stageName(Stage s);

struct StageTimes {
    std::array<double, kStageCount> ms{};
    double totalMs = 0.0;  // since start(): the sum of ms[]
    double operator[](Stage s) const { return ms[size_t(s)]; }
};

class StageClock {
public:
    // The process-wide clock.
    static StageClock& global();
    // Starts (or restarts) timing; time until the first push() counts as Stage::Other.
    void start();
    // True on the thread that called start(): stages are marked from that thread only, so work
    // handed to other threads is charged to the stage that waits for it.
    bool running() const { return running_ && std::this_thread::get_id() == owner_; }
    void push(Stage s);
    void pop();
    // Times so far (the stage in progress included, up to now).
    StageTimes read() const;

private:
    using Clock = std::chrono::steady_clock;
    void charge(Clock::time_point now);
    bool running_ = false;
    std::thread::id owner_{};
    std::vector<Stage> stack_;
    Clock::time_point start_{}, last_{};
    std::array<double, kStageCount> ms_{};
};

// Marks the enclosing scope as stage `s` on the global clock (if it is running).
class ScopedStage {
public:
    explicit ScopedStage(Stage s);
    ~ScopedStage();
    ScopedStage(const ScopedStage&) = delete;
    ScopedStage& operator=(const ScopedStage&) = delete;

private:
    bool active_;
};

}  // namespace gbl
