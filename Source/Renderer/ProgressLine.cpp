#include "ProgressLine.h"

#include <cstdio>
#include <unistd.h>

namespace snaresim::render
{

ProgressLine::ProgressLine(bool enabled, std::int64_t totalSamples, double sampleRate_Hz)
    : active(enabled && ::isatty(STDERR_FILENO) == 1 && totalSamples > 0 && sampleRate_Hz > 0.0), total(totalSamples), rate(sampleRate_Hz)
{}

ProgressLine::~ProgressLine()
{
    // Left unfinished (an error or an interruption): end the line, claim nothing.
    if (shown)
        std::fputc('\n', stderr);
}

void ProgressLine::update(std::int64_t done)
{
    if (! active)
        return;

    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (elapsed < kDelaySeconds || now - lastPrint < std::chrono::milliseconds(200))
        return;
    lastPrint = now;

    const double audioDone = (double) done / rate, audioTotal = (double) total / rate;
    const double speed = elapsed > 0.0 ? audioDone / elapsed : 0.0;
    const double left = speed > 0.0 ? (audioTotal - audioDone) / speed : 0.0;
    std::fprintf(stderr, "\rsnaresim-render: %3d%%  %.1f of %.1f s of audio  %.2fx real time  %.0f s left \033[K",
                 (int) (100.0 * (double) done / (double) total), audioDone, audioTotal, speed, left);
    std::fflush(stderr);
    shown = true;
}

void ProgressLine::finish()
{
    if (! shown)
        return;
    std::fprintf(stderr, "\rsnaresim-render: 100%%  %.1f s of audio rendered\033[K\n", (double) total / rate);
    std::fflush(stderr);
    shown = false;
}

} // namespace snaresim::render
