#pragma once
// What one invocation of snaresim-render asks for, as parsed from the command line
// (CommandLine.h). Plain data; nothing here has been checked against the engine yet.

#include "Parameters.h"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace snaresim::render
{

inline constexpr double kDefaultSampleRate_Hz = 48000.0;
inline constexpr double kMinSampleRate_Hz = 8000.0;
inline constexpr double kMaxSampleRate_Hz = 384000.0;
inline constexpr double kDefaultSeconds = 2.0;  // --hit only, no --seconds
inline constexpr double kMidiTailSeconds = 2.0; // --midi, no --seconds: last note-on + this
inline constexpr double kMaxSeconds = 3600.0;   // longest render (and latest strike time)

// --bench: blocks of --block-size samples through Drum::process, as the plug-in renders.
inline constexpr int kDefaultBlockSize = 64;
inline constexpr int kMinBlockSize = 1;
inline constexpr int kMaxBlockSize = 8192;
inline constexpr double kBenchShortSeconds = 0.25; // --bench-short: the default scenario, this long
inline constexpr int kDefaultBenchRepeats = 5;     // --bench-repeat (--bench-short: 1)
inline constexpr int kMaxBenchRepeats = 50;

// One strike: when, and how hard (MIDI velocity 1..127).
struct Strike
{
    double time_s = 0.0;
    int velocity = 100;
};

// --mic: which signal the WAV holds; `all` writes four channels (top, bottom, far, mix).
enum class MicOutput
{
    top,
    bottom,
    far,
    mix,
    all,
    air // one channel per air microphone (air box; its default)
};

// --bench-scenario: the strikes a benchmark plays when no --hit / --midi is given.
//   standard ("default"): one strike at velocity 127 every 0.5 s from 0 (length: --seconds, 2 s)
//   roll:                 16 strikes at velocity 127, 60 ms apart from 0.1 s (length 1.5 s)
enum class BenchScenario
{
    standard,
    roll
};

// --walls: the air box's walls.
enum class Walls
{
    absorbing,
    reflecting
};

// A point in metres from the drum's centre (x, y in the batter's plane, z up along the axis).
struct Point3
{
    double x = 0.0, y = 0.0, z = 0.0;
};

// One --set ID=VALUE (ID already resolved; the range is checked by ParameterSet::set).
struct ParameterOverride
{
    ParamId id {};
    double value = 0.0;
    std::string text; // as typed, for error messages
};

// One --set-at TIME:ID=VALUE: the parameter takes the value from that time on, as a host's
// automation does (smoothed, or a new drum crossfaded in where the parameter needs one).
struct TimedOverride
{
    double time_s = 0.0;
    ParameterOverride change;
};

// One coordinate --match searches: a parameter, or (no id) the strike's MIDI velocity.
struct MatchCoordinate
{
    std::optional<ParamId> id;
    bool operator==(const MatchCoordinate&) const = default;
};

// One --ref KITDIR:GLOB: the recordings of one kit a strike is measured against.
struct ReferenceSpec
{
    std::filesystem::path kitDir;
    std::string pattern; // a glob(7) pattern under kitDir
    std::string text;    // as typed, for messages
};

inline constexpr int kDefaultMatchBudget = 800; // --match-budget: renders (two searches of about 390)
inline constexpr int kMinMatchBudget = 12;
inline constexpr int kMaxMatchBudget = 100000;

struct RenderJob
{
    std::optional<std::filesystem::path> output;             // -o (WAV); always given unless bench
    std::optional<std::filesystem::path> energyCsv;          // --energy-csv
    std::optional<std::filesystem::path> energyPlot;         // --energy-plot (PNG)
    std::optional<std::filesystem::path> spectrogram;        // --spectrogram (PNG)
    std::optional<std::filesystem::path> snarePlot;          // --snare-plot (PNG)
    std::optional<std::filesystem::path> midiFile;           // --midi
    std::vector<Strike> hits;                                // --hit, in command-line order
    std::optional<double> seconds;                           // --seconds
    double sampleRate_Hz = kDefaultSampleRate_Hz;            // --sample-rate (integer, checked range)
    std::optional<std::string> preset;                       // --preset
    std::optional<int> airModel;                             // --model: index into air_model's choices
    std::optional<MicOutput> mic;                            // --mic (default: mix)
    std::vector<ParameterOverride> overrides;                // --set, applied in order after the preset
    std::vector<TimedOverride> automation;                   // --set-at, in command-line order
    bool lossless = false;                                   // --lossless
    bool json = false;                                       // --json
    bool bench = false;                                      // --bench
    std::optional<int> blockSize;                            // --block-size (bench only, checked range)
    std::optional<BenchScenario> benchScenario;              // --bench-scenario (bench only)
    bool benchShort = false;                                 // --bench-short (bench only)
    std::optional<int> benchRepeats;                         // --bench-repeat (bench only, checked range)
    std::vector<Point3> airMics;                             // --air-mic X,Y,Z (air box), in order
    std::optional<Walls> walls;                              // --walls (air box; --lossless: reflecting)
    std::optional<Point3> boxSize;                           // --box X,Y,Z or --box S (air box, metres)
    std::optional<double> boxMargin;                         // --box-margin M (air box, metres)
    std::optional<int> threads;                              // --threads N (air box; default: all cores)
    std::optional<std::filesystem::path> match;              // --match RECORDING (-o is then the preset file)
    std::optional<std::vector<MatchCoordinate>> matchParams; // --match-params ID,ID,... (checked IDs)
    std::optional<int> matchBudget;                          // --match-budget N (renders)
    std::optional<int> matchSeed;                            // --match-seed N (the search's random numbers)
    std::vector<std::filesystem::path> distanceFiles;        // --distance FILE, in order (nothing rendered)
    std::vector<ReferenceSpec> references;                   // --ref KITDIR:GLOB, in order

    MicOutput selectedMic() const { return mic.value_or(MicOutput::mix); }
    int selectedBlockSize() const { return blockSize.value_or(kDefaultBlockSize); }
    int selectedRepeats() const { return benchRepeats.value_or(benchShort ? 1 : kDefaultBenchRepeats); }
    BenchScenario selectedScenario() const { return benchScenario.value_or(BenchScenario::standard); }

    // The first option given that only a render of a file uses (its strikes, length, outputs,
    // microphone, bench and air box), or nullptr: --match and --distance refuse them.
    const char* firstRenderOption() const
    {
        const std::pair<bool, const char*> options[] {
            { ! hits.empty(), "--hit" },
            { ! automation.empty(), "--set-at" },
            { midiFile.has_value(), "--midi" },
            { seconds.has_value(), "--seconds" },
            { energyCsv.has_value(), "--energy-csv" },
            { energyPlot.has_value(), "--energy-plot" },
            { spectrogram.has_value(), "--spectrogram" },
            { snarePlot.has_value(), "--snare-plot" },
            { lossless, "--lossless" },
            { bench, "--bench" },
            { mic.has_value(), "--mic" },
            { ! airMics.empty(), "--air-mic" },
            { walls.has_value(), "--walls" },
            { boxSize.has_value(), "--box" },
            { boxMargin.has_value(), "--box-margin" },
            { threads.has_value(), "--threads" },
        };
        for (const auto& [given, option] : options)
            if (given)
                return option;
        return nullptr;
    }
};

} // namespace snaresim::render
