// Energy checks of the scheme (eq. 34-38): conservation to round-off when
// lossless, monotone decay with losses; the ledger's terms and what moves each of them.

#include "EnergyLedger.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

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
    CHECK(peakHead > 0.05 * e0);                 // the contact really moved energy into the head
    CHECK(drum.solverStats().maxIterations > 0); // and the contact solve ran
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
    const DrumConfig cfg = test::lossyHead();
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    const double b0 = drum.energy().balance();
    const int steps = 20000;
    double previous = e0, worstRise = 0.0, worstBalance = 0.0, kept = -1.0;
    int keptAt = 0;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        const double e = drum.energy().total();
        worstRise = std::max(worstRise, (e - previous) / e0);
        worstBalance = std::max(worstBalance, std::abs(drum.energy().balance() - b0) / e0);
        previous = e;
        if (kept < 0.0 && ! drum.mallet(0).inPlay())
        {
            kept = drum.energy().value("batter");
            keptAt = n;
        }
    }
    // Once the mallet is taken back nothing feeds the head: each of its modes loses energy at
    // 2 sigma0 or faster on average (half of it kinetic; sigma1 only adds), so it keeps at most
    // exp(-2 sigma0 t) of what the strike left (sigma0 from T60 = 1 s: 6.9 /s).
    const double end = drum.energy().value("batter");
    const double bound = std::exp(-2.0 * cfg.batter.sigma0_per_s * (steps - 1 - keptAt) / cfg.sampleRate_Hz);
    INFO("largest step-to-step rise " << worstRise << ", balance drift " << worstBalance << "; kept " << kept << " J at step " << keptAt
                                      << ", " << end << " J at the end (bound " << bound * kept << " J)");
    CHECK(worstRise < 1e-14);
    CHECK(worstBalance < 1e-12);
    REQUIRE(kept > 0.0);
    CHECK(end < bound * kept);
}

namespace
{
std::vector<std::string> termNames(const EnergyLedger& e)
{
    std::vector<std::string> names;
    for (const auto& t : e.terms())
        names.emplace_back(t.name);
    return names;
}

// Every term's largest |value| over `steps` steps after a 5 m/s strike (with tracking on).
std::map<std::string, double> largestTerms(Drum& drum, int steps)
{
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    std::map<std::string, double> largest;
    const auto& e = drum.energy();
    for (const auto& t : e.terms())
        largest[std::string(t.name)] = std::abs(t.value_J);
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        for (const auto& t : e.terms())
            largest[std::string(t.name)] = std::max(largest[std::string(t.name)], std::abs(t.value_J));
    }
    return largest;
}
} // namespace

TEST_CASE("the ledger holds the drum's terms in eq. (34)'s order, and reset keeps them with their values cleared", "[energy]")
{
    Drum drum(test::wholeDrum());
    const std::vector<std::string> expected { "batter", "carry", "mallets", "snares", "cavity" };
    CHECK(termNames(drum.energy()) == expected);
    CHECK(EnergyLedger::columnName("batter") == "batter_J");

    const auto largest = largestTerms(drum, 2000);
    for (const auto& name : expected)
    {
        INFO("term " << name);
        CHECK(largest.at(name) > 0.0); // the whole drum: every term holds energy after a strike
    }
    CHECK(drum.energy().dissipated_J > 0.0);
    CHECK(drum.energy().injected_J > 0.0);

    drum.reset();
    CHECK(termNames(drum.energy()) == expected);
    for (const auto& t : drum.energy().terms())
        CHECK(t.value_J == 0.0);
    CHECK(drum.energy().dissipated_J == 0.0);
    CHECK(drum.energy().injected_J == 0.0);
    CHECK(drum.energy().total() == 0.0);
    CHECK_THROWS_AS(drum.energy().value("airbox"), std::out_of_range);
}

TEST_CASE("each ledger term moves only when its component is in play", "[energy]")
{
    SECTION("snares off, no air: the batter and the mallet, nothing else")
    {
        Drum drum(test::losslessHead());
        const auto largest = largestTerms(drum, 4000);
        CHECK(largest.at("batter") > 0.05 * 0.35); // the contact moved energy into the head
        CHECK(largest.at("mallets") > 0.0);
        CHECK(largest.at("carry") == 0.0); // no air: nothing reaches the carry head
        CHECK(largest.at("snares") == 0.0);
        CHECK(largest.at("cavity") == 0.0);
        CHECK(drum.energy().dissipated_J == 0.0); // lossless
    }
    SECTION("no air, snares on: the wires rest on a carry head nothing moves")
    {
        DrumConfig cfg = test::losslessHead();
        cfg.snares.engaged = true;
        Drum drum(cfg);
        const auto largest = largestTerms(drum, 4000);
        CHECK(largest.at("batter") > 0.0);
        CHECK(largest.at("mallets") > 0.0);
        CHECK(largest.at("carry") == 0.0);
        CHECK(largest.at("snares") == 0.0);
        CHECK(largest.at("cavity") == 0.0);
    }
    SECTION("the cavity, snares off: the air carries the batter's motion to the carry head")
    {
        DrumConfig cfg = test::losslessHead();
        cfg.cavity.model = AirModel::cavity;
        Drum drum(cfg);
        const auto largest = largestTerms(drum, 4000);
        CHECK(largest.at("batter") > 0.0);
        CHECK(largest.at("cavity") > 0.0);
        CHECK(largest.at("carry") > 0.0);
        CHECK(largest.at("snares") == 0.0);
    }
    SECTION("the snares thrown off and put back: their term drops to exactly 0 and what they held leaves through injected_J")
    {
        Drum drum(test::wholeDrum());
        largestTerms(drum, 400);
        const auto& e = drum.energy();
        const double held = e.value("snares"), injected = e.injected_J, balance = e.balance();
        REQUIRE(held != 0.0);
        drum.setSnaresEngaged(false);
        CHECK(e.value("snares") == 0.0);
        const double scale = injected; // the strike's energy (balance itself is about 0)
        CHECK(e.injected_J == Approx(injected - held).margin(1e-12 * scale));
        CHECK(e.balance() == Approx(balance).margin(1e-12 * scale));
        for (int n = 0; n < 200; ++n)
        {
            drum.step();
            REQUIRE(e.value("snares") == 0.0);
        }
        const double offBalance = e.balance();
        drum.setSnaresEngaged(true); // laid on the head as it moves: they bring the energy of that motion
        CHECK(e.value("snares") != 0.0);
        CHECK(e.balance() == Approx(offBalance).margin(1e-12 * scale));
        drum.step();
        CHECK(e.value("snares") != 0.0);
    }
}

TEST_CASE("the ledger's total adds its terms, its balance books the losses and the player's energy", "[energy]")
{
    // Binary fractions, so every sum is exact whatever the order.
    EnergyLedger e;
    const int a = e.addTerm("a"), b = e.addTerm("b");
    CHECK(e.total() == 0.0);
    e.set(a, 0.5);
    e.set(b, 0.25);
    e.change(b, 0.125);
    e.dissipated_J = 0.0625;
    e.injected_J = 1.0;
    CHECK(e[b] == 0.375);
    CHECK(e.value("b") == 0.375);
    CHECK(e.total() == 0.875);
    CHECK(e.balance() == 0.875 + 0.0625 - 1.0);
    CHECK_THROWS_AS(e.value("c"), std::out_of_range);
    e.clearValues();
    CHECK(e.size() == 2);
    CHECK(e.total() == 0.0);
    CHECK(e.balance() == 0.0);
    for (int i = e.size(); i < EnergyLedger::capacity; ++i)
        e.addTerm("more");
    CHECK_THROWS_AS(e.addTerm("one too many"), std::length_error);
}
