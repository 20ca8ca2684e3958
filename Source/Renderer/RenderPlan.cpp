#include "RenderPlan.h"

#include "Errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace snaresim::render
{

RenderPlan makeRenderPlan(const RenderJob& job, const std::vector<Strike>& midiStrikes)
{
    std::vector<Strike> all = job.hits;
    all.insert(all.end(), midiStrikes.begin(), midiStrikes.end());
    std::stable_sort(all.begin(), all.end(), [](const Strike& a, const Strike& b) { return a.time_s < b.time_s; });

    double seconds = kDefaultSeconds;
    if (job.seconds)
        seconds = *job.seconds;
    else if (job.midiFile)
        seconds = (all.empty() ? 0.0 : all.back().time_s) + kMidiTailSeconds;

    if (seconds > kMaxSeconds)
        throw UserError("the render would last " + numberText(seconds) + " s, longer than " + std::to_string((int) kMaxSeconds) +
                        " s (give --seconds)");

    RenderPlan plan;
    plan.sampleRate_Hz = job.sampleRate_Hz;
    plan.numSamples = std::llround(seconds * job.sampleRate_Hz);
    if (plan.numSamples < 1)
        throw UserError("--seconds: " + numberText(seconds) + " s is shorter than one sample");

    for (const auto& strike : all)
    {
        const auto sample = std::llround(strike.time_s * job.sampleRate_Hz);
        if (sample < plan.numSamples)
            plan.strikes.push_back({ sample, strike.velocity });
        else
            ++plan.strikesOutside;
    }

    for (const auto& [time_s, change] : job.automation)
    {
        const auto sample = std::llround(time_s * job.sampleRate_Hz);
        if (sample < plan.numSamples)
            plan.changes.push_back({ sample, change.id, change.value, change.text });
    }
    std::stable_sort(plan.changes.begin(), plan.changes.end(),
                     [](const ScheduledChange& a, const ScheduledChange& b) { return a.sample < b.sample; });
    return plan;
}

} // namespace snaresim::render
