#include "Report.h"

#include "Benchmark.h"
#include "Formatted.h"
#include "Microphones.h"
#include "VectorTarget.h"

#include <juce_core/juce_core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace snaresim::render
{
namespace
{

double secondsRendered(const RenderReport& r) { return (double) r.stats.samples / r.plan.sampleRate_Hz; }

double realtimeFactor(const RenderReport& r)
{
    return r.stats.wallSeconds > 0.0 ? secondsRendered(r) / r.stats.wallSeconds : std::numeric_limits<double>::infinity();
}

juce::var text(const std::string& s) { return juce::String(juce::CharPointer_UTF8(s.c_str())); }

juce::var pathOrNull(const std::optional<std::filesystem::path>& path) { return path ? text(path->string()) : juce::var(); }

std::string channelText(int channels) { return channels == 1 ? "mono" : std::to_string(channels) + " channels"; }

// The step profile's phases, the path's in step order: each one's compute per second of audio
// and share of the steps' total.
struct PhaseFigure
{
    std::string_view name;
    double perAudioSecond = 0.0;
    double share = 0.0;
};

std::vector<PhaseFigure> phaseFigures(const RenderReport& r, const StepProfile& p)
{
    std::vector<PhaseFigure> figures;
    const double total = p.total();
    for (const auto phase : StepProfile::phasesOf(p.path))
        figures.push_back({ StepProfile::name(phase), p[phase] / secondsRendered(r), total > 0.0 ? p[phase] / total : 0.0 });
    return figures;
}

// The profiled run's block time against the fastest timed run's, less one.
double profilingOverhead(const BenchFigures& b) { return b.fastestRun_s > 0.0 ? b.profiledRun_s / b.fastestRun_s - 1.0 : 0.0; }

juce::var profileJson(const RenderReport& r, const BenchFigures& b)
{
    auto* object = new juce::DynamicObject();
    const juce::var result(object);
    const auto& p = b.profile;
    object->setProperty("path", text(std::string(StepProfile::name(p.path))));
    object->setProperty("steps", (juce::int64) p.steps);
    auto* phases = new juce::DynamicObject();
    for (const auto& f : phaseFigures(r, p))
    {
        auto* phase = new juce::DynamicObject();
        phase->setProperty("compute_seconds_per_audio_second", f.perAudioSecond);
        phase->setProperty("share", f.share);
        phases->setProperty(juce::Identifier(juce::String(std::string(f.name))), juce::var(phase));
    }
    object->setProperty("phases", juce::var(phases));
    object->setProperty("compute_seconds_per_audio_second", p.total() / secondsRendered(r));           // the phases' sum
    object->setProperty("run_compute_seconds_per_audio_second", b.profiledRun_s / secondsRendered(r)); // its blocks, player included
    object->setProperty("fastest_run_compute_seconds_per_audio_second", b.fastestRun_s / secondsRendered(r));
    object->setProperty("overhead", profilingOverhead(b));
    return result;
}

} // namespace

std::string formatJson(const RenderReport& r)
{
    auto* object = new juce::DynamicObject();
    const juce::var root(object);

    object->setProperty("output", pathOrNull(r.output));
    object->setProperty("energy_csv", pathOrNull(r.energyCsv));
    object->setProperty("energy_plot", pathOrNull(r.energyPlot));
    object->setProperty("spectrogram", pathOrNull(r.spectrogram));
    object->setProperty("snare_plot", pathOrNull(r.snarePlot));
    object->setProperty("sample_rate", (juce::int64) std::llround(r.plan.sampleRate_Hz)); // a whole number of Hz
    object->setProperty("channels", r.stats.channels);
    object->setProperty("mic", text(std::string(micName(r.job.selectedMic()))));
    object->setProperty("vector_target", text(std::string(snaresim::vectorTargetName(snaresim::vectorTarget()))));
    object->setProperty("samples", (juce::int64) r.stats.samples);
    object->setProperty("seconds_rendered", secondsRendered(r));
    object->setProperty("wall_seconds", r.stats.wallSeconds);
    object->setProperty("realtime_factor", realtimeFactor(r));
    object->setProperty("peak", r.stats.peak);
    object->setProperty("rms", r.stats.rms);
    object->setProperty("nonfinite_samples", (juce::int64) r.stats.nonfiniteSamples);
    object->setProperty("nonfinite_resets", r.stats.nonfiniteResets);
    object->setProperty("strikes", r.stats.strikes);
    object->setProperty("strikes_outside", r.plan.strikesOutside);
    object->setProperty("preset", r.job.preset ? text(*r.job.preset) : juce::var());
    object->setProperty("lossless", r.job.lossless);
    object->setProperty("energy_tracking", r.stats.energyRelativeDriftMax.has_value());
    if (r.stats.energyRelativeDriftMax)
        object->setProperty("energy_relative_drift_max", *r.stats.energyRelativeDriftMax);
    if (! r.stats.energyMax_J.empty())
    {
        auto* maxima = new juce::DynamicObject(); // the ledger's terms and the total, as the CSV's columns
        for (const auto& [column, value] : r.stats.energyMax_J)
            maxima->setProperty(juce::Identifier(juce::String(column)), value);
        object->setProperty("energy_max_J", juce::var(maxima));
    }
    object->setProperty("solver_max_iterations", r.stats.solver.maxIterations);
    object->setProperty("snare_max_iterations", r.stats.solver.maxSnareIterations);
    object->setProperty("snare_max_penetration_m", r.stats.solver.maxSnarePenetration_m);
    object->setProperty("solver_fallbacks", (juce::int64) r.stats.solver.fallbacks);
    if (r.distance)
        object->setProperty("distance", distanceJson(*r.distance));

    if (const auto& b = r.stats.bench)
    {
        object->setProperty("bench", true);
        object->setProperty("bench_scenario", text(std::string(scenarioName(r.job))));
        object->setProperty("bench_short", r.job.benchShort);
        object->setProperty("block_size", b->blockSize);
        object->setProperty("blocks", (juce::int64) b->blocks);
        object->setProperty("mean_block_ms", 1000.0 * b->meanBlock_s);
        object->setProperty("worst_block_ms", 1000.0 * b->worstBlock_s);
        object->setProperty("worst_block_at_s", b->worstBlockAt_s);
        object->setProperty("repeats", b->repeats);
        object->setProperty("worst_block_raw_ms", 1000.0 * b->worstBlockRaw_s);
        object->setProperty("realtime_factor_slowest_run", b->slowestRun_s > 0.0 ? secondsRendered(r) / b->slowestRun_s : 0.0);
        object->setProperty("block_budget_ms", 1000.0 * b->blockBudget_s);
        object->setProperty("worst_block_share", b->worstBlock_s / b->blockBudget_s);
        object->setProperty("simulation_rate", b->simulationRate_Hz);
        object->setProperty("batter_grid_spacing_m", b->batterGridSpacing_m);
        object->setProperty("carry_grid_spacing_m", b->carryGridSpacing_m);
        object->setProperty("batter_nodes", b->batterNodes);
        object->setProperty("carry_nodes", b->carryNodes);
        object->setProperty("snare_points", b->snarePoints);
        object->setProperty("compute_seconds_per_audio_second", r.stats.wallSeconds / secondsRendered(r));
        object->setProperty("peak_resident_mb", b->peakResident_bytes / (1024.0 * 1024.0));
        if (const auto& a = b->air)
        {
            object->setProperty("air_points", (juce::int64) a->points);
            object->setProperty("air_spacing_m", a->spacing_m);
            object->setProperty("air_threads", a->threads);
            object->setProperty("air_precision", "double");
            object->setProperty("air_updates_per_second", a->airRate());
            object->setProperty("air_updates_per_second_threads", a->airThreadsRate());
            object->setProperty("bare_stencil_updates_per_second", a->bareRate());
            object->setProperty("bare_stencil_float_updates_per_second", a->bareFloatRate());
            object->setProperty("air_to_bare_ratio", a->airRate() / a->bareRate());
            object->setProperty("air_to_bare_ratio_threads", a->airThreadsRate() / a->bareRate());
        }
        object->setProperty("profile", profileJson(r, *b));
    }

    return juce::JSON::toString(root, true).toStdString() + "\n";
}

namespace
{

std::string benchSummary(const RenderReport& r, const BenchFigures& b)
{
    std::string s;
    s += formatted("benchmark: %s scenario%s, %.3f s at %.0f Hz, block size %d (%lld blocks), %d strike%s",
                   std::string(scenarioName(r.job)).c_str(), r.job.benchShort ? " (short)" : "", secondsRendered(r), r.plan.sampleRate_Hz,
                   b.blockSize, (long long) b.blocks, r.stats.strikes, r.stats.strikes == 1 ? "" : "s");
    if (r.plan.strikesOutside > 0)
        s += formatted(" (%d more at or after the end, not played)", r.plan.strikesOutside);
    s += "\n";
    const std::string target(snaresim::vectorTargetName(snaresim::vectorTarget()));
    s += formatted("realtime factor %.3gx (%.3f s of audio in %.3f s), vector target %s\n", realtimeFactor(r), secondsRendered(r),
                   r.stats.wallSeconds, target.c_str());
    s += formatted("block time (each block's fastest of %d run%s): mean %.4g ms, worst %.4g ms at %.4g s; budget %.4g ms "
                   "(worst = %.3g x the budget)\n",
                   b.repeats, b.repeats == 1 ? "" : "s", 1000.0 * b.meanBlock_s, 1000.0 * b.worstBlock_s, b.worstBlockAt_s,
                   1000.0 * b.blockBudget_s, b.worstBlock_s / b.blockBudget_s);
    if (b.repeats > 1)
        s += formatted("raw: slowest block of any run %.4g ms; slowest run %.3gx real time\n", 1000.0 * b.worstBlockRaw_s,
                       b.slowestRun_s > 0.0 ? secondsRendered(r) / b.slowestRun_s : 0.0);
    s += formatted("grid: batter h %.4g mm (%d nodes), carry h %.4g mm (%d nodes), %d snare points; simulated at %.6g Hz\n",
                   1000.0 * b.batterGridSpacing_m, b.batterNodes, 1000.0 * b.carryGridSpacing_m, b.carryNodes, b.snarePoints,
                   b.simulationRate_Hz);
    if (const auto& a = b.air)
    {
        s += formatted("air box: %lld points, h %.4g mm, %.3g s of compute per s of audio (the whole drum, %d thread%s)\n",
                       (long long) a->points, 1000.0 * a->spacing_m, r.stats.wallSeconds / secondsRendered(r), a->threads,
                       a->threads == 1 ? "" : "s");
        s += formatted("air update %.3g updates/s on 1 thread, %.3g on %d; bare 7-point stencil %.3g (double, 1 thread; float "
                       "%.3g); air / bare %.3f (%.3f on %d)\n",
                       a->airRate(), a->airThreadsRate(), a->threads, a->bareRate(), a->bareFloatRate(), a->airRate() / a->bareRate(),
                       a->airThreadsRate() / a->bareRate(), a->threads);
    }
    s += formatted("peak resident size %.1f MB\n", b.peakResident_bytes / (1024.0 * 1024.0));
    s += formatted("profile (one more run, %s path): the steps %.3g s of compute per s of audio, the blocks %.3g "
                   "(fastest timed run %.3g: profiling costs %+.1f%%)\n",
                   std::string(StepProfile::name(b.profile.path)).c_str(), b.profile.total() / secondsRendered(r),
                   b.profiledRun_s / secondsRendered(r), b.fastestRun_s / secondsRendered(r), 100.0 * profilingOverhead(b));
    auto phases = phaseFigures(r, b.profile);
    std::stable_sort(phases.begin(), phases.end(), [](const auto& x, const auto& y) { return x.share > y.share; });
    for (const auto& f : phases)
        s += formatted("  %-15s %9.4f s/s %6.1f%%\n", std::string(f.name).c_str(), f.perAudioSecond, 100.0 * f.share);
    s += formatted("peak %.6g, rms %.6g, non-finite samples %lld\n", r.stats.peak, r.stats.rms, (long long) r.stats.nonfiniteSamples);
    if (r.output)
        s += "wrote " + r.output->string() +
             formatted(" (%.3f s, %.0f Hz, mono (mix), 32-bit float)\n", secondsRendered(r), r.plan.sampleRate_Hz);
    if (r.stats.solver.fallbacks > 0)
        s += formatted("warning: the contact solver fell back %ld time(s)\n", r.stats.solver.fallbacks);
    return s;
}

} // namespace

std::string formatSummary(const RenderReport& r)
{
    if (r.stats.bench)
        return benchSummary(r, *r.stats.bench);

    std::string s;
    s += "wrote " + (r.output ? r.output->string() : std::string("(no file)")) +
         formatted(" (%.3f s, %.0f Hz, ", secondsRendered(r), r.plan.sampleRate_Hz) + channelText(r.stats.channels) + " (" +
         std::string(micName(r.job.selectedMic())) + "), 32-bit float)\n";
    if (r.energyCsv)
        s += "wrote " + r.energyCsv->string() + " (energy ledger, one row per sample)\n";
    if (r.energyPlot)
        s += "wrote " + r.energyPlot->string() + " (energy plot)\n";
    if (r.spectrogram)
        s += "wrote " + r.spectrogram->string() + " (spectrogram)\n";
    if (r.snarePlot)
        s += "wrote " + r.snarePlot->string() + " (snare plot)\n";
    s += formatted("strikes: %d", r.stats.strikes);
    if (r.plan.strikesOutside > 0)
        s += formatted(" (%d more at or after the end, not played)", r.plan.strikesOutside);
    s += "\n";
    s += formatted("peak %.6g, rms %.6g, non-finite samples %lld\n", r.stats.peak, r.stats.rms, (long long) r.stats.nonfiniteSamples);
    s += formatted("render time %.3f s, %.2fx real time\n", r.stats.wallSeconds, realtimeFactor(r));
    s += formatted("solver: max %d Newton iterations", r.stats.solver.maxIterations) +
         formatted(" (snares %d)", r.stats.solver.maxSnareIterations) +
         formatted(", max snare penetration %.3g m\n", r.stats.solver.maxSnarePenetration_m);
    if (r.stats.energyRelativeDriftMax)
        s += formatted("energy balance drift (max, relative): %.3g\n", *r.stats.energyRelativeDriftMax);
    if (r.stats.solver.fallbacks > 0)
        s += formatted("warning: the contact solver fell back %ld time(s)\n", r.stats.solver.fallbacks);
    if (r.distance)
        s += distanceSummary(*r.distance);
    return s;
}

} // namespace snaresim::render
