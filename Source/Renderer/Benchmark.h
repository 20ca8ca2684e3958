#pragma once
// --bench: the render timed as the plug-in runs it. The drum is played through a DrumSession
// (the engine's one door) exactly as the plug-in's processBlock calls it: the model built from
// the parameters (no --lossless), every parameter handed to the session at each block of
// --block-size samples, each strike a note-on of note 38 (the articulation path) and each
// --set-at change at its sample, energy tracking off and denormals flushed to zero
// (juce::ScopedNoDenormals, as in processBlock). The session plays as the renderer's
// (DrumSession::Mode::render): the parameters as given, with no keep-up fallback. Every block, parameters and events included, is timed with
// std::chrono::steady_clock; the audio statistics and the WAV are handled outside the timed
// section.

#include "RenderJob.h"
#include "RenderPlan.h"
#include "Renderer.h"

#include "BuildOptions.h"
#include "Parameters.h"

#include <functional>
#include <memory>
#include <span>
#include <string_view>

namespace snaresim::render
{

inline constexpr int kBenchNote = 38; // GM acoustic snare: the centre strike
inline constexpr double kDefaultScenarioInterval_s = 0.5;
inline constexpr int kRollStrikes = 16;
inline constexpr double kRollStart_s = 0.1;
inline constexpr double kRollInterval_s = 0.06;
inline constexpr double kRollSeconds = 1.5;
inline constexpr int kBenchVelocity = 127;

// "default", "roll"; "custom" when --hit / --midi replace the scenario's strikes. Of the job
// as given on the command line (not of benchmarkJob's result, which holds the strikes as hits).
std::string_view scenarioName(const RenderJob& job);

// The job as benchmarked: without --hit / --midi, the scenario's strikes; without --seconds,
// the scenario's length (--bench-short: 0.25 s; with --midi: the usual last note + 2 s).
RenderJob benchmarkJob(const RenderJob& job);

// Renders the plan `repeats` times, each on a new session and drum, as described above.
// audio (may be empty) receives every block of the first run's mix. The result's `bench`
// holds the block timings (each block's fastest run, and the raw extremes), the grid
// figures and the process's peak resident size; the other figures are of the first run.
// After the timed runs the plan is played once more the same way with the drum's step
// profile on (Drum::setProfiling): bench->profile, and that run's time beside the fastest
// timed run's (what the profiling itself costs).
// The drums are built with `options` (the air box's, --threads among them); `config` is the
// first drum's configuration. With the air box, after the runs the air box's update is timed
// against a bare 7-point stencil on the same grid (bench->air).
RenderStats benchmarkDrum(const ParameterSet& params, const BuildOptions& options, const DrumConfig& config, const RenderPlan& plan,
                          int blockSize, int repeats, const std::function<void(std::span<const float>)>& audio);

} // namespace snaresim::render
