// The whole drum inside the air box (AirModel::airbox, DrumAir.h): energy to round-off with the
// heads' contacts solved jointly with their air, passivity with losses, the heads' (0,1) pair
// through the air, the paper's section 5.2 in the box, and the config's checks.

#include "SpectrumPeaks.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using namespace snaresim;

namespace
{
DrumConfig inAirBox(DrumConfig c)
{
    c.cavity.model = AirModel::airbox;
    return c;
}

const char* nameOf(CollisionScheme s) { return s == CollisionScheme::newton ? "Newton" : "quadratised"; }
} // namespace

TEST_CASE("the whole drum in a lossless, reflecting air box conserves energy to round-off", "[drum][airbox][energy]")
{
    DrumConfig cfg = inAirBox(test::wholeDrum()); // 20 wires, 44.1 kHz, 0.6 m box
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    Drum drum(cfg.lossless());
    REQUIRE(drum.airBox().active());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.0);
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    double drift = 0.0, airPeak = 0.0;
    const int steps = 10000;
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        drift = std::max(drift, std::abs(drum.energy().balance() - b0) / e0);
        airPeak = std::max(airPeak, drum.airBox().energy());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const auto& st = drum.solverStats();
    std::printf("air box, %s, 20 wires: relative energy variation %.3g over %d steps; air's largest energy %.3g J "
                "(%.2g of the strike's); most contact trials per head and step %d, capped %ld; psi resets removed %.3g; %.1f s\n",
                nameOf(cfg.snares.scheme), drift, steps, airPeak, airPeak / e0, st.maxAirTrials, st.airCapped,
                drum.energy().dissipated_J / e0, seconds);
    CHECK(airPeak > 1e-6 * e0); // the air takes part
    CHECK(st.airCapped == 0);
    CHECK(drift < 1e-11);
}
