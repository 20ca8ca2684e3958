#pragma once
// Drum configurations shared by the engine tests and the lab's figures.

#include "Drum.h"
#include "Parameters.h"

#include <algorithm>
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

// The drum of physics-notes section 2 as the physics tests measure it: the default geometry and
// tensions with light losses, so that modes ring long enough to be measured (T60 of the lowest
// modes 1.8 s, damping 25 %; sigma1 = 1e-3 m^2/s), snares at 30 N and the paper's stick
// (kappa = 1e8 N/m^1.5), in the paper's air: the cavity without the outside air, which the tests
// that need it switch on (OutsideAirTests.cpp, NearFieldTests.cpp). The schema's defaults (the
// Studio Default preset) damp the heads far more, as a studio snare is.
// The tests' drums at 44.1 kHz keep the grids of their own step (twice the bounds of eq. 39-40
// at 1 / 44100 s), as their tables in docs/MODEL.md were measured; the product's grids are
// designed at 48 kHz (MembraneSpec::gridTimeStep_s) for its Quality's bandwidth.
inline DrumConfig gridsOfOwnStep(DrumConfig c)
{
    c.batter.gridTimeStep_s = c.carry.gridTimeStep_s = c.snares.gridTimeStep_s = 0.0;
    c.batter.gridCoarseness = c.carry.gridCoarseness = c.snares.gridCoarseness = 2.0;
    return c;
}

inline DrumConfig physicsDrum(DrumConfig c)
{
    c.batter.sigma0_per_s = c.carry.sigma0_per_s = 3.0 * std::log(10.0) / dampingT60(25.0);
    c.batter.sigma1_m2_per_s = c.carry.sigma1_m2_per_s = 1.0e-3;
    c.snares.tension_N = 30.0;
    c.mallet.stiffness = 1.0e8;
    c.outside.enabled = false;
    return c;
}

// The default 14-inch batter alone (no air, snares off) and the paper's mallet
// (M = 0.028 kg) at 44.1 kHz, with the grid at the stability bound (eq. 39) of the actual
// tension, every loss off.
inline DrumConfig losslessHead()
{
    DrumConfig c = gridsOfOwnStep(physicsDrum(doubleHeads(DrumConfig {})));
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

// The largest relative change of a tracked drum's energy balance over `steps` steps, against its
// total energy before them; each() after every step.
template <class Each>
double balanceDrift(Drum& drum, int steps, Each each)
{
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    double drift = 0.0;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        drift = std::max(drift, std::abs(drum.energy().balance() - b0) / e0);
        each();
    }
    return drift;
}
inline double balanceDrift(Drum& drum, int steps)
{
    return balanceDrift(drum, steps, [] {});
}

// A float state's energy identity over n steps: each step rounds w at every node by up to 2^-24
// of it, a random walk of relative changes of that order: 2^-24 sqrt(n).
inline double floatDriftBound(int steps) { return 0x1p-24 * std::sqrt((double) steps); }

// The drum of cfg with both heads in single precision and every loss off, struck at 5 m/s at
// (0.3 R, 0.1 R): its balanceDrift over `steps` steps.
inline double singlePrecisionDrift(DrumConfig cfg, int steps)
{
    cfg.batter.precision = cfg.carry.precision = HeadPrecision::single_precision;
    Drum drum(cfg.lossless());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    return balanceDrift(drum, steps);
}

// Over `steps` steps of a tracked drum with losses: the largest rise of its energy from one step
// to the next and the largest change of its balance (energy + losses), both against its total
// energy before them.
struct Passivity
{
    double worstRise = 0.0, worstBalance = 0.0;
};
inline Passivity passivity(Drum& drum, int steps)
{
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    double previous = e0;
    Passivity p;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        const double e = drum.energy().total();
        p.worstRise = std::max(p.worstRise, (e - previous) / e0);
        p.worstBalance = std::max(p.worstBalance, std::abs(drum.energy().balance() - b0) / e0);
        previous = e;
    }
    return p;
}

} // namespace snaresim::test

namespace snaresim::test
{

// The whole default drum (both heads, 20 snares engaged, cavity, the quadratised snare solve,
// Quality 2) with physicsDrum's losses, snares and stick, at 44.1 kHz, its heads in double
// precision.
inline DrumConfig wholeDrum()
{
    DrumConfig c = gridsOfOwnStep(physicsDrum(doubleHeads(DrumConfig {})));
    c.sampleRate_Hz = 44100.0;
    return c;
}

} // namespace snaresim::test
