// Energy checks of the scheme (eq. 34-38): conservation to round-off when
// lossless, monotone decay with losses.

#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace snaresim;

TEST_CASE("lossless head and mallet conserve the discrete energy to round-off", "[energy]")
{
    Drum drum(test::losslessHead());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1); // 5 m/s, as in the paper's energy test

    const double e0 = drum.energy().total();
    const double b0 = drum.energy().balance();
    REQUIRE(e0 == Approx(0.5 * 0.028 * 25.0).epsilon(1e-9)); // all of it is the mallet's kinetic energy

    // Across the contact the total is conserved; once the mallet has risen 1 cm it is taken
    // back, its energy counted as leaving (balance() = total - injected stays constant).
    double maxDrift = 0.0, peakHead = 0.0;
    bool retrieved = false;
    for (int n = 0; n < 20000; ++n)
    {
        drum.step();
        retrieved = retrieved || ! drum.mallet(0).inPlay();
        if (! retrieved)
            maxDrift = std::max(maxDrift, std::abs(drum.energy().total() - e0) / e0);
        maxDrift = std::max(maxDrift, std::abs(drum.energy().balance() - b0) / e0);
        peakHead = std::max(peakHead, drum.energy().value("batter"));
    }
    INFO("max relative energy variation " << maxDrift);
    CHECK(maxDrift < 1e-12);
    CHECK(retrieved);
    CHECK(peakHead > 0.05 * e0);                       // the contact really moved energy into the head
    CHECK(drum.solverStats().maxIterations > 0);       // and the contact solve ran
    CHECK(drum.solverStats().fallbacks == 0);
}

TEST_CASE("overlapping mallets (a flam on one spot) conserve energy too", "[energy]")
{
    Drum drum(test::losslessHead());
    drum.setEnergyTracking(true);
    drum.strike(4.0, 0.3, 0.1);
    double maxDrift = 0.0, scale = 0.0;
    const double b0 = drum.energy().balance();
    for (int n = 0; n < 8000; ++n)
    {
        if (n == 20) // second mallet lands on the same patch while the first is still in contact
            drum.strike(3.0, 0.3, 0.1);
        drum.step();
        scale = std::max(scale, drum.energy().total());
        maxDrift = std::max(maxDrift, std::abs(drum.energy().balance() - b0));
    }
    INFO("max balance drift " << maxDrift / scale);
    CHECK(maxDrift / scale < 1e-12);
    CHECK(drum.solverStats().fallbacks == 0);
}

TEST_CASE("with losses the energy never rises and energy + losses is constant", "[energy]")
{
    Drum drum(test::lossyHead());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    const double b0 = drum.energy().balance();
    double previous = e0, worstRise = 0.0, worstBalance = 0.0, peakHead = 0.0;
    for (int n = 0; n < 20000; ++n)
    {
        drum.step();
        const double e = drum.energy().total();
        worstRise = std::max(worstRise, (e - previous) / e0);
        peakHead = std::max(peakHead, drum.energy().value("batter"));
        worstBalance = std::max(worstBalance, std::abs(drum.energy().balance() - b0) / e0);
        previous = e;
    }
    INFO("largest step-to-step rise " << worstRise << ", balance drift " << worstBalance);
    CHECK(worstRise < 1e-14);
    CHECK(worstBalance < 1e-12);
    // T60 = 1 s: after 0.45 s the head keeps well under a tenth of its peak energy.
    CHECK(drum.energy().value("batter") < 0.1 * peakHead);
}
