#include "BuildOptions.h"

#include <algorithm>

namespace snaresim
{

void BuildOptions::applyTo(DrumConfig& config) const noexcept
{
    if (config.cavity.model == AirModel::airbox)
    {
        auto& air = config.airBox;
        air.numMics = std::clamp(numAirMics, 0, DrumAirSpec::maxMics);
        std::copy_n(airMics.begin(), air.numMics, air.mics.begin());
        if (walls)
            air.walls = *walls;
        if (boxSize_m)
            air.size_m = *boxSize_m;
        if (boxMargin_m)
        {
            air.size_m = { 0.0, 0.0, 0.0 }; // sized from the drum and the margin
            air.margin_m = *boxMargin_m;
        }
        if (threads)
            air.threads = std::max(1, *threads);
    }
    if (lossless)
        config = config.lossless(); // with the air box: reflecting walls, sigma_a = 0
}

DrumConfig mapParameters(const ParameterSet& params, double sampleRate_Hz, const BuildOptions& options) noexcept
{
    DrumConfig config = mapParameters(params, sampleRate_Hz);
    options.applyTo(config);
    return config;
}

DrumConfig makeDrumConfig(const ParameterSet& params, double sampleRate_Hz, const BuildOptions& options)
{
    DrumConfig config = mapParameters(params, sampleRate_Hz, options);
    config.validate();
    return config;
}

} // namespace snaresim
