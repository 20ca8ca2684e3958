#pragma once
// The air box around the drum (DrumAir.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

#include "AirBox.h"
#include "AirPoint.h"

#include <array>

namespace snaresim
{

// The air box of AirModel::airbox (density and sound speed from CavitySpec; the shell is rigid,
// its depth CavitySpec::shellDepth_m). Not a parameter: set by the config's owner.
struct DrumAirSpec
{
    // Box sides (x, y, z), centred on the drum. A side <= 0: the drum's extent plus twice margin_m.
    std::array<double, 3> size_m { 0.6, 0.6, 0.6 };
    double margin_m = 0.12;
    AirWalls walls = AirWalls::absorbing;
    double sigma_m = 0.0;        // sigma_a, eq. (5) (from the schema)
    double gridCoarseness = 1.0; // h_a = coarseness * bound of eq. (41); >= 1
    int threads = 1;             // AirBox::setThreads
    // Pressure microphones rho_a dt Psi; none given: airMicPoints() gives the defaults.
    static constexpr int maxMics = 8;
    std::array<AirPoint, maxMics> mics {};
    int numMics = 0;
};

} // namespace snaresim
