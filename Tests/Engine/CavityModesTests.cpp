// The enclosed air's own modes (CavityModes.h): the rigid cylinder's frequencies from the zeros
// of J_m', the lossless whole drum with them, and their coupling's symmetry.

#include "Bessel.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace snaresim;

namespace
{
DrumConfig withModes(DrumConfig c, double upTo_Hz)
{
    c.cavity.modesUpTo_Hz = upTo_Hz;
    return c;
}
} // namespace

TEST_CASE("Bessel: the zeros of J_m and J_m' are the tabulated ones", "[cavitymodes][nearfield]")
{
    // Abramowitz and Stegun, table 9.5 (j_{m,n}; j'_{m,n}, the zero at 0 of J_0' not counted)
    CHECK(besselZero(0, 1) == Approx(2.40483).epsilon(1e-5));
    CHECK(besselZero(1, 1) == Approx(3.83171).epsilon(1e-5));
    CHECK(besselZero(2, 1) == Approx(5.13562).epsilon(1e-5));
    CHECK(besselZero(0, 2) == Approx(5.52008).epsilon(1e-5));
    CHECK(besselZero(3, 1) == Approx(6.38016).epsilon(1e-5));
    CHECK(besselZero(2, 2) == Approx(8.41724).epsilon(1e-5));
    CHECK(besselPrimeZero(1, 1) == Approx(1.84118).epsilon(1e-5));
    CHECK(besselPrimeZero(2, 1) == Approx(3.05424).epsilon(1e-5));
    CHECK(besselPrimeZero(0, 1) == Approx(3.83171).epsilon(1e-5));
    CHECK(besselPrimeZero(3, 1) == Approx(4.20119).epsilon(1e-5));
    CHECK(besselPrimeZero(1, 2) == Approx(5.33144).epsilon(1e-5));
    CHECK(besselPrimeZero(0, 2) == Approx(7.01559).epsilon(1e-5));
}

TEST_CASE("cavity modes: the default drum's, by frequency", "[cavitymodes]")
{
    const DrumConfig cfg = withModes(DrumConfig {}, 1400.0);
    const CavityModes modes(cfg.cavity, cfg.cavityModesUpTo_Hz(), cfg.batter.radius_m, 1.0 / cfg.sampleRate_Hz);
    const double R = cfg.batter.radius_m, H = cfg.cavity.shellDepth_m, c = cfg.cavity.soundSpeed_m_per_s;
    // to 1400 Hz: (1,1,0) twice, (2,1,0) twice, (0,1,0), (0,0,1), (3,1,0) twice, (1,1,1) twice;
    // the next, (2,1,1), lies at 1543 Hz
    REQUIRE(modes.size() == 10);
    CHECK(modes.mode(0).m == 1);
    CHECK(modes.mode(1).m == 1);
    CHECK(modes.mode(0).sine != modes.mode(1).sine);
    CHECK(modes.frequency_Hz(0) == Approx(1.84118 * c / (2.0 * std::numbers::pi * R)).epsilon(1e-5));
    CHECK(modes.frequency_Hz(2) == Approx(3.05424 * c / (2.0 * std::numbers::pi * R)).epsilon(1e-5));
    CHECK(modes.frequency_Hz(4) == Approx(3.83171 * c / (2.0 * std::numbers::pi * R)).epsilon(1e-5));
    CHECK(modes.frequency_Hz(6) == Approx(4.20119 * c / (2.0 * std::numbers::pi * R)).epsilon(1e-5));
    // (1,1,1): the (1,1) radial shape and half a wavelength across the depth
    const double k111 = std::hypot(1.84118 / R, std::numbers::pi / H);
    CHECK(modes.mode(8).m == 1);
    CHECK(modes.frequency_Hz(8) == Approx(k111 * c / (2.0 * std::numbers::pi)).epsilon(1e-5));
    CHECK(modes.frequency_Hz(9) == Approx(modes.frequency_Hz(8)).epsilon(1e-12));
    bool axial = false;
    for (int i = 0; i < modes.size(); ++i)
    {
        CHECK(modes.frequency_Hz(i) <= 1400.0);
        if (i > 0)
            CHECK(modes.frequency_Hz(i) >= modes.frequency_Hz(i - 1));
        if (modes.mode(i).m == 0 && modes.mode(i).n == 0)
        {
            axial = true;
            CHECK(modes.frequency_Hz(i) == Approx(c / (2.0 * H)).epsilon(1e-9));
        }
    }
    CHECK(axial);
}

TEST_CASE("cavity modes: the lossless whole drum with them conserves energy to round-off", "[cavitymodes][energy]")
{
    DrumConfig cfg = withModes(test::wholeDrum(), 2500.0); // 20 wires, double heads
    cfg.outside.enabled = GENERATE(false, true);
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    Drum drum(cfg.lossless());
    REQUIRE(drum.cavityModes().size() > 10);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    double largest = 0.0;
    const double drift =
        test::balanceDrift(drum, 10000, [&] { largest = std::max(largest, std::abs(drum.energy().value("cavity_modes"))); });
    INFO("relative variation " << drift << ", the modes' largest energy " << largest / e0 << " of the strike's");
    CHECK(drift < 1e-11);
    CHECK(largest > 1e-4 * e0); // the modes really hold energy
}

TEST_CASE("cavity modes: with single-precision heads the lossless drum holds its energy to float round-off",
          "[cavitymodes][energy][precision]")
{
    // The product's heads: the modes' pressures go into the float free update node by node
    // (Membrane::addBlockPressure). Bound as for the heads alone (HeadPrecisionTests.cpp):
    // 2^-24 sqrt(n) for n steps.
    const double drift = test::singlePrecisionDrift(withModes(test::wholeDrum(), 2500.0), 20000), bound = test::floatDriftBound(20000);
    INFO("relative energy variation " << drift << " (bound " << bound << ")");
    CHECK(drift < bound);
}
