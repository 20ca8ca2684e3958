#include "Benchmark.h"

#include "AirSpeed.h"
#include "DrumSession.h"

#include <juce_audio_basics/juce_audio_basics.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <sys/resource.h>

namespace snaresim::render
{

std::string_view scenarioName(const RenderJob& job)
{
    if (! job.hits.empty() || job.midiFile)
        return "custom";
    return job.selectedScenario() == BenchScenario::roll ? "roll" : "default";
}

RenderJob benchmarkJob(const RenderJob& job)
{
    RenderJob result = job;
    const auto scenario = job.selectedScenario();

    if (job.benchShort && ! result.seconds)
        result.seconds = kBenchShortSeconds;
    if (! result.seconds && ! job.midiFile)
        result.seconds = scenario == BenchScenario::roll ? kRollSeconds : kDefaultSeconds;

    if (! job.hits.empty() || job.midiFile)
        return result; // explicit strikes replace the scenario's

    if (scenario == BenchScenario::roll)
    {
        for (int i = 0; i < kRollStrikes; ++i)
            result.hits.push_back({ kRollStart_s + i * kRollInterval_s, kBenchVelocity });
    }
    else
    {
        // One strike every 0.5 s from 0 while inside the render (times from the index, so
        // that no rounding accumulates).
        for (int i = 0; i * kDefaultScenarioInterval_s < *result.seconds; ++i)
            result.hits.push_back({ i * kDefaultScenarioInterval_s, kBenchVelocity });
    }
    return result;
}

RenderStats benchmarkDrum(const ParameterSet& params, const BuildOptions& options, const DrumConfig& config, const RenderPlan& plan,
                          int blockSize, int repeats, const std::function<void(std::span<const float>)>& audio)
{
    using Clock = std::chrono::steady_clock;

    // The plug-in's processBlock runs with denormals flushed to zero; so does the benchmark.
    const juce::ScopedNoDenormals noDenormals;

    std::vector<float> block((std::size_t) blockSize);
    std::vector<PlayerEvent> events;
    events.reserve(plan.strikes.size() + plan.changes.size());
    const auto numBlocks = (std::size_t)((plan.numSamples + blockSize - 1) / blockSize);
    std::vector<Clock::duration> fastest(numBlocks, Clock::duration::max());
    Clock::duration rawWorst {}, slowestRun {}, fastestRun = Clock::duration::max();

    const bool airBox = config.cavity.model == AirModel::airbox;
    RenderStats stats;
    BenchFigures figures;
    double peak = 0.0, sumSquares = 0.0;
    std::int64_t finite = 0, nonfinite = 0;

    // The timed runs, then one more with the drum's step profile on (not counted in the timings).
    for (int run = 0; run <= repeats; ++run)
    {
        const bool profiled = run == repeats;
        // A new session and drum each run: every run computes the same blocks.
        DrumSession session(DrumSession::Mode::render, options);
        session.setParameters(params);
        session.prepareAndStart(plan.sampleRate_Hz, blockSize); // builds at its events only
        auto& player = session.drumPlayer();
        if (player.drum() == nullptr)
            throw std::runtime_error("the drum cannot be built at this sample rate");
        player.drum()->setProfiling(profiled);

        std::size_t nextStrike = 0, nextChange = 0, index = 0;
        Clock::duration runTotal {};

        for (std::int64_t position = 0; position < plan.numSamples; ++index)
        {
            const int n = (int) std::min<std::int64_t>(blockSize, plan.numSamples - position);
            gatherEvents(plan, position, n, kBenchNote, nextStrike, nextChange, events);

            const auto start = Clock::now();
            // As processBlock: the block with its events (the session hands every parameter to the player).
            session.process(block.data(), n, events);
            const auto elapsed = Clock::now() - start;

            runTotal += elapsed;
            if (! profiled)
            {
                rawWorst = std::max(rawWorst, elapsed);
                fastest[index] = std::min(fastest[index], elapsed);
            }

            if (run == 0)
            {
                const std::span<const float> samples(block.data(), (std::size_t) n);
                for (const float x : samples)
                {
                    if (! std::isfinite(x))
                    {
                        ++nonfinite;
                        continue;
                    }
                    peak = std::max(peak, (double) std::abs(x));
                    sumSquares += (double) x * (double) x;
                    ++finite;
                }
                if (audio)
                    audio(samples);
            }
            position += n;
        }
        if (profiled)
        {
            figures.profile = player.drum()->profile();
            figures.profiledRun_s = std::chrono::duration<double>(runTotal).count();
            break;
        }
        slowestRun = std::max(slowestRun, runTotal);
        fastestRun = std::min(fastestRun, runTotal);

        if (run == 0)
        {
            const auto& drum = *player.drum();
            stats.strikes = (int) nextStrike;
            stats.solver = drum.solverStats();
            stats.nonfiniteResets = player.nonFiniteResets();
            figures.simulationRate_Hz = drum.simulationRate();
            figures.batterGridSpacing_m = drum.batter().grid().spacing();
            figures.carryGridSpacing_m = drum.carry().grid().spacing();
            figures.batterNodes = drum.batter().grid().numInterior();
            figures.carryNodes = drum.carry().grid().numInterior();
            figures.snarePoints = drum.snareContact().numPoints();
        }
    }

    const Clock::duration total = std::accumulate(fastest.begin(), fastest.end(), Clock::duration {});
    const auto slowest = std::max_element(fastest.begin(), fastest.end()); // the first of equals
    const Clock::duration worst = slowest != fastest.end() ? *slowest : Clock::duration {};
    const auto worstIndex = (std::size_t)(slowest - fastest.begin());

    stats.samples = plan.numSamples;
    stats.channels = 1;
    stats.wallSeconds = std::chrono::duration<double>(total).count();
    stats.peak = peak;
    stats.rms = finite > 0 ? std::sqrt(sumSquares / (double) finite) : 0.0;
    stats.nonfiniteSamples = nonfinite;

    figures.blockSize = blockSize;
    figures.blocks = (std::int64_t) numBlocks;
    figures.meanBlock_s = numBlocks > 0 ? stats.wallSeconds / (double) numBlocks : 0.0;
    figures.worstBlock_s = std::chrono::duration<double>(worst).count();
    figures.worstBlockAt_s = (double) worstIndex * (double) blockSize / plan.sampleRate_Hz;
    figures.repeats = repeats;
    figures.worstBlockRaw_s = std::chrono::duration<double>(rawWorst).count();
    figures.slowestRun_s = std::chrono::duration<double>(slowestRun).count();
    figures.fastestRun_s = std::chrono::duration<double>(fastestRun).count();
    figures.blockBudget_s = (double) blockSize / plan.sampleRate_Hz;

    // The peak resident size of the runs (before the air box below is built).
    rusage usage {};
    if (getrusage(RUSAGE_SELF, &usage) == 0)
        figures.peakResident_bytes = 1024.0 * (double) usage.ru_maxrss; // kilobytes on Linux

    if (airBox)
    {
        AirBox air(config.airBoxSpec(), 1.0 / plan.sampleRate_Hz); // the drum's grid, shell and closed ends
        figures.air = measureAirSpeed(air, config.airBox.threads);
    }
    stats.bench = figures;
    return stats;
}

} // namespace snaresim::render
