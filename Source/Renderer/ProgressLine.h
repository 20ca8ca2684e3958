#pragma once
// The progress of a long render on a terminal: one line on stderr, rewritten in place ("\r"),
// with the share done, the audio seconds rendered, the speed and the time left. Shown only
// when stderr is a terminal, never with --json, and only once a render has taken more than
// two seconds of wall time; ended with a newline when the render ends.

#include <chrono>
#include <cstdint>

namespace snaresim::render
{

class ProgressLine
{
public:
    // enabled: the caller's decision (not --json); the terminal check is made here.
    ProgressLine(bool enabled, std::int64_t totalSamples, double sampleRate_Hz);
    ~ProgressLine();
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    // samplesDone of totalSamples are rendered (cheap: prints at most five times a second).
    void update(std::int64_t samplesDone);

    // Ends the line, if one was shown, with the render complete.
    void finish();

    static constexpr double kDelaySeconds = 2.0;

private:
    using Clock = std::chrono::steady_clock;

    bool active;
    bool shown = false;
    std::int64_t total;
    double rate;
    Clock::time_point start = Clock::now();
    Clock::time_point lastPrint {};
};

} // namespace snaresim::render
