#pragma once
// The render loop: plays a RenderPlan through a started DrumSession (the engine's one door, as
// the plug-in plays it), strikes and --set-at changes at their exact samples, and hands the audio of the asked microphones (and, with energy tracking, the energy
// ledger of every sample; on request, the drum itself after the steps of a range of samples)
// to the callers' sinks. Measures the time spent in the engine only.

#include "Microphones.h"
#include "RenderPlan.h"

#include "AirSpeed.h"
#include "Drum.h"
#include "DrumSession.h"
#include "EnergyLedger.h"
#include "Parameters.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace snaresim::render
{

inline constexpr int kRenderBlockSize = 1024; // the renderer's blocks (the session splits them at events)

// --bench (Benchmark.h): the timing of every block and the size of the model.
struct BenchFigures
{
    int blockSize = 0;
    std::int64_t blocks = 0;
    double meanBlock_s = 0.0;
    double worstBlock_s = 0.0;
    double worstBlockAt_s = 0.0;      // where that block starts in the render
    int repeats = 1;                  // runs; the block times above are each block's fastest run
    double worstBlockRaw_s = 0.0;     // the slowest block of any run
    double slowestRun_s = 0.0;        // the slowest run's total block time
    double fastestRun_s = 0.0;        // the fastest run's total block time
    double blockBudget_s = 0.0;       // blockSize / sample rate
    double simulationRate_Hz = 0.0;   // Drum::simulationRate(): the physics' rate
    double batterGridSpacing_m = 0.0; // Drum::batter().grid().spacing()
    double carryGridSpacing_m = 0.0;
    int batterNodes = 0; // interior nodes of the batter / carry grids
    int carryNodes = 0;
    int snarePoints = 0;             // SnareContact::numPoints(): wire points that collide
    double peakResident_bytes = 0.0; // the process's peak resident size after the runs (getrusage ru_maxrss)
    // The air box (--model airbox): its update against a bare 7-point stencil on its grid,
    // timed after the runs in the same process (AirSpeed.h).
    std::optional<AirSpeed> air;
    // One more run after the timed ones, with the drum's step profile on (StepProfile.h).
    StepProfile profile;
    double profiledRun_s = 0.0; // that run's total block time
};

struct RenderStats
{
    std::int64_t samples = 0;
    double wallSeconds = 0.0; // time inside the engine (strikes and steps) only
    int channels = 1;
    double peak = 0.0;                 // max |sample| over the finite samples of every channel
    double rms = 0.0;                  // over the finite samples of every channel
    std::int64_t nonfiniteSamples = 0; // over every channel
    int nonfiniteResets = 0;           // times the player's guard reset a drum gone non-finite
    int strikes = 0;                   // strikes played
    // With energy tracking: max_n |balance_n - balance_0| / max_n total_n (0 when the drum
    // never held energy); NaN when the ledger went non-finite.
    std::optional<double> energyRelativeDriftMax;
    // With energy tracking: the largest finite value of each ledger term and of the total, under
    // its CSV column name ("batter_J", ..., "total_J"), in the CSV's order (NaN: never finite).
    std::vector<std::pair<std::string, double>> energyMax_J;
    SolverStats solver;
    std::optional<BenchFigures> bench; // --bench only
};

struct RenderSinks
{
    // channels[c] holds the block's samples of microphone mics[c] (all of one length).
    std::function<void(std::span<const std::span<const float>> channels)> audio;
    // Called only with energy tracking; rows[i] is the ledger after sample firstSample + i.
    std::function<void(std::int64_t firstSample, std::span<const EnergyLedger> rows)> energy;
    // Called right after the step of every sample in [stateFrom, stateTo) with the drum,
    // whose state is then at time sample + 1 (read only; not counted as engine time).
    std::function<void(std::int64_t sample, const Drum& drum)> state;
    std::int64_t stateFrom = 0, stateTo = 0;
};

// Plays the plan through `session` (started: EngineSetup.h's startSession). mics: the signals
// to render, one channel each (Microphones.h: drum.output(mic) after every step, Mic::mix the
// session's output, an air microphone's pressure at audio level). The energy is tracked when
// the session's drums keep their ledger (BuildOptions::trackEnergy). The audio has the drum's
// lag (Drum::latencySamples) taken off: a strike at sample s sounds from s, at every rate.
RenderStats renderDrum(DrumSession& session, const RenderPlan& plan, std::span<const Channel> mics, const RenderSinks& sinks);

// The plan's strikes (as the main strike, or as `note` when given) and --set-at changes in
// [position, position + n), as events of that block in sample order (changes first on a shared
// sample); `nextStrike` and `nextChange` advance past them.
void gatherEvents(const RenderPlan& plan, std::int64_t position, int n, std::optional<int> note, std::size_t& nextStrike,
                  std::size_t& nextChange, std::vector<PlayerEvent>& events);

} // namespace snaresim::render
