#pragma once
// What a drum is built with besides its parameters: the settings an offline client (the
// renderer) gives that are not the instrument's, such as the air box's size, walls and
// microphones, its threads, a lossless drum for energy checks; and the real-time clients' one
// latency.

#include "DrumConfig.h"
#include "Parameters.h"

#include <array>
#include <optional>

namespace snaresim
{

struct BuildOptions
{
    // The air box (AirModel::airbox only; the other models ignore these).
    std::array<AirPoint, DrumAirSpec::maxMics> airMics {}; // pressure microphones in the box
    int numAirMics = 0;                                    // none: DrumConfig::airMicPoints' defaults
    std::optional<AirWalls> walls;
    std::optional<std::array<double, 3>> boxSize_m; // sides; or
    std::optional<double> boxMargin_m;              // the drum's extent plus twice this
    std::optional<int> threads;                     // AirBox::setThreads

    bool lossless = false;    // every loss off (DrumConfig::lossless): the energy is conserved
    bool trackEnergy = false; // the drum keeps its energy ledger every step (Drum::setEnergyTracking)
    // Every drum's output lags its strikes by the longest lag at its rate
    // (longestLatencySamples): one latency whatever Quality or air model plays (the plug-in's).
    bool constantLatency = false;

    // The options over a mapped config: the air box's settings, then lossless.
    void applyTo(DrumConfig& config) const noexcept;
};

// mapParameters with the options applied: not validated, allocates nothing (the audio thread's).
DrumConfig mapParameters(const ParameterSet& params, double sampleRate_Hz, const BuildOptions& options) noexcept;

// makeDrumConfig with the options applied, validated (throws std::invalid_argument).
DrumConfig makeDrumConfig(const ParameterSet& params, double sampleRate_Hz, const BuildOptions& options);

} // namespace snaresim
