#pragma once
// What snaresim-render prints after a successful render: one JSON object (--json) or a
// short human-readable summary.

#include "Distance.h"
#include "RenderJob.h"
#include "RenderPlan.h"
#include "Renderer.h"

#include <filesystem>
#include <optional>
#include <string>

namespace snaresim::render
{

struct RenderReport
{
    const RenderJob& job;
    const RenderPlan& plan;
    const RenderStats& stats;
    std::optional<std::filesystem::path> output;      // absolute (none: --bench without -o)
    std::optional<std::filesystem::path> energyCsv;   // absolute
    std::optional<std::filesystem::path> energyPlot;  // absolute
    std::optional<std::filesystem::path> spectrogram; // absolute
    std::optional<std::filesystem::path> snarePlot;   // absolute
    const DistanceReport* distance;                   // --ref: the rendered strike's (none: nullptr)
};

// One line, ends with a newline. Non-finite numbers are written as null. With --bench
// (stats.bench) it adds mean_block_ms, worst_block_ms, block_budget_ms, worst_block_share,
// block_size, blocks, bench_scenario, bench_short, the grid figures,
// compute_seconds_per_audio_second and peak_resident_mb; with the air box also air_points,
// air_spacing_m, air_threads, air_precision, air_updates_per_second (one thread),
// air_updates_per_second_threads, bare_stencil_updates_per_second (double, one thread, the
// same grid), bare_stencil_float_updates_per_second, air_to_bare_ratio and
// air_to_bare_ratio_threads; and "profile": the step profile of one more run (Benchmark.h):
// path, steps, phases (each phase of the path, StepProfile.h, with its
// compute_seconds_per_audio_second and share of the phases' sum),
// compute_seconds_per_audio_second (the phases' sum), run_compute_seconds_per_audio_second
// (that run's blocks), fastest_run_compute_seconds_per_audio_second (the fastest timed run's)
// and overhead (the profiled run's time over the fastest timed run's, less one). With --ref it
// adds "distance" (Distance.h's distanceJson).
std::string formatJson(const RenderReport& report);

// A few lines, ends with a newline; with --ref the rendered strike's distances after them.
std::string formatSummary(const RenderReport& report);

} // namespace snaresim::render
