#pragma once
// Drum configurations shared by the engine tests.

#include "Drum.h"

#include <cmath>

namespace snaresim::test
{

// The physics tests' drums run the double-precision heads, the reference that holds the energy
// to double round-off (HeadPrecisionTests.cpp holds the single-precision ones against it).
inline DrumConfig doubleHeads(DrumConfig c)
{
    c.batter.precision = c.carry.precision = HeadPrecision::double_precision;
    return c;
}

// The default 14-inch batter alone (no air, snares off) and the paper's mallet
// (M = 0.028 kg) at 44.1 kHz, with the grid at the stability bound (eq. 39) of the actual
// tension, every loss off.
inline DrumConfig losslessHead()
{
    DrumConfig c = doubleHeads(DrumConfig {});
    c.sampleRate_Hz = 44100.0;
    c.batter.gridTension_N_per_m = 0.0;
    c.batter.gridSigma1_m2_per_s = -1.0;
    c.batter.gridCoarseness = 1.0;
    c.cavity.model = AirModel::none;
    c.snares.engaged = false;
    return c.lossless();
}

inline DrumConfig lossyHead()
{
    DrumConfig c = losslessHead();
    c.batter.sigma0_per_s = 3.0 * std::log(10.0) / 1.0; // T60 = 1 s
    c.batter.sigma1_m2_per_s = 1.0e-3;
    return c;
}

} // namespace snaresim::test

namespace snaresim::test
{

// The whole default drum (the schema's defaults: both heads, 20 snares engaged, cavity,
// the quadratised snare solve, Quality 2) at 44.1 kHz, its heads in double precision.
inline DrumConfig wholeDrum()
{
    DrumConfig c = doubleHeads(DrumConfig {});
    c.sampleRate_Hz = 44100.0;
    return c;
}

} // namespace snaresim::test
