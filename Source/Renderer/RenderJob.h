#pragma once
// What one invocation of snaresim-render asks for, as parsed from the command line
// (CommandLine.h). Plain data; nothing here has been checked against the engine yet.

#include "Parameters.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace snaresim::render
{

inline constexpr double kDefaultSampleRate_Hz = 48000.0;
inline constexpr double kMinSampleRate_Hz = 8000.0;
inline constexpr double kMaxSampleRate_Hz = 384000.0;
inline constexpr double kDefaultSeconds = 2.0;     // --hit only, no --seconds
inline constexpr double kMidiTailSeconds = 2.0;    // --midi, no --seconds: last note-on + this
inline constexpr double kMaxSeconds = 3600.0;      // longest render (and latest strike time)

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
    all
};

// One --set ID=VALUE (ID already resolved; the range is checked by ParameterSet::set).
struct ParameterOverride
{
    ParamId id {};
    double value = 0.0;
    std::string text;   // as typed, for error messages
};

struct RenderJob
{
    std::filesystem::path output;                   // -o (WAV)
    std::optional<std::filesystem::path> energyCsv; // --energy-csv
    std::optional<std::filesystem::path> energyPlot; // --energy-plot (PNG)
    std::optional<std::filesystem::path> spectrogram; // --spectrogram (PNG)
    std::optional<std::filesystem::path> snarePlot; // --snare-plot (PNG)
    std::optional<std::filesystem::path> midiFile;  // --midi
    std::vector<Strike> hits;                       // --hit, in command-line order
    std::optional<double> seconds;                  // --seconds
    double sampleRate_Hz = kDefaultSampleRate_Hz;   // --sample-rate (integer, checked range)
    std::optional<std::string> preset;              // --preset
    std::optional<int> airModel;                    // --model: index into air_model's choices
    std::optional<MicOutput> mic;                   // --mic (default: mix)
    std::vector<ParameterOverride> overrides;       // --set, applied in order after the preset
    bool lossless = false;                          // --lossless
    bool json = false;                              // --json

    MicOutput selectedMic() const { return mic.value_or(MicOutput::mix); }
};

} // namespace snaresim::render
