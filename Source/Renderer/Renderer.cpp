#include "Renderer.h"

#include "DrumConfig.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace snaresim::render
{
namespace
{

constexpr int kBlockSize = 1024;

// Running audio and energy statistics (kept out of the timed section).
struct Statistics
{
    double peak = 0.0;
    double sumSquares = 0.0;
    std::int64_t finite = 0;
    std::int64_t nonfinite = 0;

    bool haveReference = false;
    double referenceBalance = 0.0;
    double maxDeviation = 0.0;
    double maxTotal = 0.0;
    bool energyNonfinite = false;

    void addAudio(std::span<const float> block)
    {
        for (const float x : block)
        {
            if (! std::isfinite(x))
            {
                ++nonfinite;
                continue;
            }
            const double v = x;
            peak = std::max(peak, std::abs(v));
            sumSquares += v * v;
            ++finite;
        }
    }

    void addEnergy(std::span<const EnergyLedger> rows)
    {
        for (const auto& e : rows)
        {
            const double balance = e.balance();
            const double total = e.total();
            if (! std::isfinite(balance) || ! std::isfinite(total))
            {
                energyNonfinite = true;
                continue;
            }
            if (! haveReference)
            {
                haveReference = true;
                referenceBalance = balance;
            }
            maxDeviation = std::max(maxDeviation, std::abs(balance - referenceBalance));
            maxTotal = std::max(maxTotal, std::abs(total));
        }
    }

    double relativeDrift() const
    {
        if (energyNonfinite)
            return std::numeric_limits<double>::quiet_NaN();
        return maxTotal > 0.0 ? maxDeviation / maxTotal : 0.0;
    }
};

} // namespace

RenderStats renderDrum(Drum& drum, const RenderPlan& plan, std::span<const Mic> mics, bool trackEnergy,
                       const RenderSinks& sinks)
{
    using Clock = std::chrono::steady_clock;

    drum.setEnergyTracking(trackEnergy);
    drum.resetStats();

    const std::size_t numChannels = mics.size();
    std::vector<std::vector<float>> blocks(numChannels, std::vector<float>((std::size_t) kBlockSize));
    std::vector<std::span<const float>> channels(numChannels);
    std::vector<EnergyLedger> ledgers;
    ledgers.reserve((std::size_t) kBlockSize);

    const auto& strikes = plan.strikes;
    const double maxSpeed = drum.config().strikeSpeedMax_m_per_s;
    std::size_t nextStrike = 0;

    // Plays every strike scheduled at this sample (before the step that computes it).
    auto strikeAt = [&](std::int64_t sample) {
        while (nextStrike < strikes.size() && strikes[nextStrike].sample <= sample)
            drum.strikeAtDefaultPoint(strikeSpeedFromVelocity(strikes[nextStrike++].velocity, maxSpeed));
    };

    Statistics statistics;
    Clock::duration engineTime {};
    Clock::duration stateTime {}; // spent in sinks.state, inside the timed section

    // Hands the drum after the step of this sample to sinks.state when the sample is in range.
    auto readState = [&](std::int64_t sample) {
        if (! sinks.state || sample < sinks.stateFrom || sample >= sinks.stateTo)
            return;
        const auto start = Clock::now();
        sinks.state(sample, std::as_const(drum));
        stateTime += Clock::now() - start;
    };

    for (std::int64_t position = 0; position < plan.numSamples;)
    {
        const int n = (int) std::min<std::int64_t>(kBlockSize, plan.numSamples - position);
        const auto start = Clock::now();

        ledgers.clear();
        for (int i = 0; i < n; ++i)
        {
            strikeAt(position + i);
            const double mix = drum.step();
            readState(position + i);
            for (std::size_t c = 0; c < numChannels; ++c)
                blocks[c][(std::size_t) i] = (float) (mics[c] == Mic::mix ? mix : drum.output(mics[c]));
            if (trackEnergy)
                ledgers.push_back(drum.energy());
        }

        engineTime += Clock::now() - start;

        for (std::size_t c = 0; c < numChannels; ++c)
        {
            channels[c] = std::span<const float>(blocks[c].data(), (std::size_t) n);
            statistics.addAudio(channels[c]);
        }
        if (sinks.audio)
            sinks.audio(channels);
        if (trackEnergy)
        {
            statistics.addEnergy(ledgers);
            if (sinks.energy)
                sinks.energy(position, ledgers);
        }
        position += n;
    }

    RenderStats stats;
    stats.samples = plan.numSamples;
    stats.channels = (int) numChannels;
    stats.wallSeconds = std::chrono::duration<double>(engineTime - stateTime).count();
    stats.peak = statistics.peak;
    stats.rms = statistics.finite > 0 ? std::sqrt(statistics.sumSquares / (double) statistics.finite) : 0.0;
    stats.nonfiniteSamples = statistics.nonfinite;
    stats.strikes = (int) nextStrike;
    if (trackEnergy)
        stats.energyRelativeDriftMax = statistics.relativeDrift();
    stats.solver = drum.solverStats();
    return stats;
}

} // namespace snaresim::render
