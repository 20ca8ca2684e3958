#pragma once
// Turning strike times into sample indices and choosing the render length.

#include "RenderJob.h"

#include "Parameters.h"

#include <cstdint>
#include <string>
#include <vector>

namespace snaresim::render
{

struct ScheduledStrike
{
    std::int64_t sample = 0; // round(time * sampleRate)
    int velocity = 100;
};

struct ScheduledChange
{
    std::int64_t sample = 0; // round(time * sampleRate)
    ParamId id {};
    double value = 0.0;
    std::string text; // as typed (--set-at), for messages
};

struct RenderPlan
{
    double sampleRate_Hz = kDefaultSampleRate_Hz;
    std::int64_t numSamples = 0;          // round(seconds * sampleRate)
    std::vector<ScheduledStrike> strikes; // sorted by sample; only those inside the render
    int strikesOutside = 0;               // strikes at or after the end (not played)
    std::vector<ScheduledChange> changes; // --set-at, sorted by sample (stable); only those inside the render
};

// The length: job.seconds if given; otherwise, with a MIDI file, the latest strike + 2 s;
// otherwise 2 s. midiStrikes are those of job.midiFile (empty without one). Throws
// UserError when the length is shorter than one sample or longer than kMaxSeconds.
RenderPlan makeRenderPlan(const RenderJob& job, const std::vector<Strike>& midiStrikes);

} // namespace snaresim::render
