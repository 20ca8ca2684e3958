#include "Renderer.h"

#include "DrumConfig.h"

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

void gatherEvents(const RenderPlan& plan, std::int64_t position, int n, std::optional<int> note, std::size_t& nextStrike,
                  std::size_t& nextChange, std::vector<PlayerEvent>& events)
{
    events.clear();
    const auto& strikes = plan.strikes;
    const auto& changes = plan.changes;
    for (;;)
    {
        const bool change = nextChange < changes.size() && changes[nextChange].sample < position + n;
        const bool strike = nextStrike < strikes.size() && strikes[nextStrike].sample < position + n;
        if (change && (! strike || changes[nextChange].sample <= strikes[nextStrike].sample))
        {
            const auto& c = changes[nextChange++];
            events.push_back(PlayerEvent::parameterChange((int) std::max<std::int64_t>(0, c.sample - position), c.id, c.value));
        }
        else if (strike)
        {
            const auto& s = strikes[nextStrike++];
            const int at = (int) std::max<std::int64_t>(0, s.sample - position);
            events.push_back(note ? PlayerEvent::noteOn(at, *note, s.velocity) : PlayerEvent::strikeAt(at, s.velocity));
        }
        else
            break;
    }
}

RenderStats renderDrum(DrumSession& session, const RenderPlan& plan, std::span<const Channel> mics, const RenderSinks& sinks)
{
    using Clock = std::chrono::steady_clock;

    auto& player = session.drumPlayer();
    const bool trackEnergy = player.drum() != nullptr && player.drum()->energyTracking();

    const std::size_t numChannels = mics.size();
    std::vector<std::vector<float>> blocks(numChannels, std::vector<float>((std::size_t) kRenderBlockSize));
    std::vector<float> mixBlock((std::size_t) kRenderBlockSize);
    std::vector<std::span<const float>> channels(numChannels);
    std::vector<EnergyLedger> ledgers;
    ledgers.reserve((std::size_t) kRenderBlockSize);
    std::vector<PlayerEvent> events;

    std::size_t nextStrike = 0, nextChange = 0;

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

    // The drum's lag behind its strikes (the interpolation to the host's rate,
    // Drum::latencySamples) taken off: audio sample i is the engine's sample i + lag, so a strike
    // sounds when it does on a drum simulated at the host's rate. The energy and the state stay
    // on the engine's samples, which are the strikes' own times. The lag is the first drum's.
    const std::int64_t lag = player.drum() != nullptr ? std::lround(player.drum()->latencySamples()) : 0;
    const std::int64_t engineSamples = plan.numSamples + lag;

    for (std::int64_t position = 0; position < engineSamples;)
    {
        const int n = (int) std::min<std::int64_t>(kRenderBlockSize, engineSamples - position);

        // Every strike and change scheduled in this block, on its sample (before the step that computes it).
        gatherEvents(plan, position, n, std::nullopt, nextStrike, nextChange, events);

        const auto start = Clock::now();
        ledgers.clear();
        indexInBlock = 0;
        session.process(mixBlock.data(), n, events, &observer);
        engineTime += Clock::now() - start;

        const auto skip = (std::size_t) std::clamp<std::int64_t>(lag - position, 0, n); // the lag's samples in this block
        if (skip < (std::size_t) n)
        {
            for (std::size_t c = 0; c < numChannels; ++c)
            {
                if (mics[c] == Channel {})
                    std::copy_n(mixBlock.begin(), n, blocks[c].begin());
                channels[c] = std::span<const float>(blocks[c].data() + skip, (std::size_t) n - skip);
                statistics.addAudio(channels[c]);
            }
            if (sinks.audio)
                sinks.audio(channels);
        }
        const auto rows = (std::size_t) std::clamp<std::int64_t>(plan.numSamples - position, 0, n); // the plan's samples in this block
        if (trackEnergy && rows > 0)
        {
            const std::span<const EnergyLedger> kept(ledgers.data(), rows);
            statistics.addEnergy(kept);
            if (sinks.energy)
                sinks.energy(position, kept);
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
