#include "Renderer.h"

#include "DrumConfig.h"
#include "DrumPlayer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
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
    std::vector<std::pair<std::string, double>> energyMax; // per term, then the total

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
            if (energyMax.empty())
            {
                for (const auto& term : e.terms())
                    energyMax.emplace_back(EnergyLedger::columnName(term.name), std::numeric_limits<double>::quiet_NaN());
                energyMax.emplace_back(EnergyLedger::columnName("total"), std::numeric_limits<double>::quiet_NaN());
            }
            for (int t = 0; t <= e.size(); ++t)
            {
                const double v = t < e.size() ? e[t] : e.total();
                auto& largest = energyMax[(std::size_t) t].second;
                if (std::isfinite(v) && ! (v <= largest))
                    largest = v;
            }

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

RenderStats renderDrum(std::unique_ptr<Drum> drumToPlay, const ParameterSet& params, const RenderPlan& plan, std::span<const Channel> mics,
                       bool trackEnergy, const RenderSinks& sinks)
{
    using Clock = std::chrono::steady_clock;

    drumToPlay->setEnergyTracking(trackEnergy);
    drumToPlay->resetStats();

    // The same player as the plug-in's, with this drum as it was built (--lossless included).
    DrumPlayer player([params] { return params; });
    player.startWith(std::move(drumToPlay), params);

    const std::size_t numChannels = mics.size();
    std::vector<std::vector<float>> blocks(numChannels, std::vector<float>((std::size_t) kBlockSize));
    std::vector<float> mixBlock((std::size_t) kBlockSize);
    std::vector<std::span<const float>> channels(numChannels);
    std::vector<EnergyLedger> ledgers;
    ledgers.reserve((std::size_t) kBlockSize);
    std::vector<PlayerEvent> events;

    const auto& strikes = plan.strikes;
    std::size_t nextStrike = 0;

    Statistics statistics;
    Clock::duration engineTime {};
    Clock::duration stateTime {}; // spent in sinks.state, inside the timed section

    // After every step: the other microphones, the energy and, in range, the drum's state.
    struct Observer final : StepObserver
    {
        std::function<void(const Drum&)> after;
        void afterStep(const Drum& drum) override { after(drum); }
    } observer;

    std::int64_t sample = 0; // the sample the drum has just computed
    int indexInBlock = 0;
    observer.after = [&](const Drum& drum) {
        for (std::size_t c = 0; c < numChannels; ++c)
            if (mics[c].air >= 0)
                blocks[c][(std::size_t) indexInBlock] =
                    (float) (drum.config().outputGain * kAirMicGain_per_Pa * drum.airMicPressure(mics[c].air));
            else if (mics[c].mic != Mic::mix)
                blocks[c][(std::size_t) indexInBlock] = (float) drum.output(mics[c].mic);
        if (trackEnergy)
            ledgers.push_back(drum.energy());
        if (sinks.state && sample >= sinks.stateFrom && sample < sinks.stateTo)
        {
            const auto start = Clock::now();
            sinks.state(sample, drum);
            stateTime += Clock::now() - start;
        }
        ++sample;
        ++indexInBlock;
    };

    for (std::int64_t position = 0; position < plan.numSamples;)
    {
        const int n = (int) std::min<std::int64_t>(kBlockSize, plan.numSamples - position);

        // Every strike scheduled in this block, on its sample (before the step that computes it).
        events.clear();
        while (nextStrike < strikes.size() && strikes[nextStrike].sample < position + n)
        {
            const auto& strike = strikes[nextStrike++];
            events.push_back(PlayerEvent::strikeAt((int) std::max<std::int64_t>(0, strike.sample - position), strike.velocity));
        }

        const auto start = Clock::now();
        ledgers.clear();
        indexInBlock = 0;
        player.process(mixBlock.data(), n, events, &observer);
        engineTime += Clock::now() - start;

        for (std::size_t c = 0; c < numChannels; ++c)
        {
            if (mics[c] == Channel {})
                std::copy_n(mixBlock.begin(), n, blocks[c].begin());
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
    stats.nonfiniteResets = player.nonFiniteResets();
    stats.strikes = (int) nextStrike;
    if (trackEnergy)
    {
        stats.energyRelativeDriftMax = statistics.relativeDrift();
        stats.energyMax_J = statistics.energyMax;
    }
    if (const auto* drum = player.drum())
        stats.solver = drum->solverStats();
    return stats;
}

} // namespace snaresim::render
