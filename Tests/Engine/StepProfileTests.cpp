// The drum's step profile (Drum::setProfiling, StepProfile.h): the same numbers with it on and
// off, on the cavity path and in the air box, and phases that add up to no more than the time
// around the steps. Nothing here depends on the machine's speed.

#include "Report.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

using namespace snaresim;

namespace
{

// The default drum in a small air box (the threads test's, DrumAirTests.cpp).
DrumConfig inSmallAirBox()
{
    DrumConfig c = test::wholeDrum();
    c.cavity.model = AirModel::airbox;
    c.airBox.size_m = { 0.48, 0.48, 0.4 };
    return c;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every number a step leaves for the outside: the mix, each microphone, the energy, the air mics.
std::vector<double> play(Drum& drum, int steps)
{
    std::vector<double> out;
    for (int n = 0; n < steps; ++n)
    {
        if (n % 700 == 0)
            drum.playNote(38, n == 0 ? 127 : 90);
        out.push_back(drum.step());
        const auto& s = drum.lastSignals();
        out.insert(out.end(), { s.top_Pa, s.bottom_Pa, s.room_Pa, drum.energy().total(), drum.energy().balance() });
        for (int i = 0; i < drum.numAirMics(); ++i)
            out.push_back(drum.airMicPressure(i));
    }
    return out;
}

} // namespace

TEST_CASE("the drum plays the same numbers bit for bit with its step profile on and off", "[drum][profile]")
{
    const bool airBox = GENERATE(false, true);
    const bool energy = GENERATE(false, true);
    const DrumConfig cfg = airBox ? inSmallAirBox() : test::wholeDrum();
    const int steps = airBox ? 400 : 2000;
    INFO((airBox ? "air box" : "cavity") << (energy ? ", energy tracked" : ""));

    Drum plain(cfg), profiled(cfg);
    REQUIRE(profiled.airBox().active() == airBox);
    plain.setEnergyTracking(energy);
    profiled.setEnergyTracking(energy);
    profiled.setProfiling(true);
    REQUIRE(profiled.isProfiling());
    REQUIRE(! plain.isProfiling());

    const auto a = play(plain, steps), b = play(profiled, steps);
    REQUIRE(a.size() == b.size());
    int differ = 0;
    for (size_t i = 0; i < a.size(); ++i)
        differ += sameBits(a[i], b[i]) ? 0 : 1;
    CHECK(differ == 0);
    CHECK(plain.profile().steps == 0);
    CHECK(plain.profile().total() == 0.0);
    CHECK(profiled.profile().steps == steps);
    CHECK(profiled.solverStats().maxIterations == plain.solverStats().maxIterations);
}

TEST_CASE("the step profile's phases are never negative and add up to no more than the time around the steps", "[drum][profile]")
{
    const bool airBox = GENERATE(false, true);
    INFO((airBox ? "air box" : "cavity"));
    Drum drum(airBox ? inSmallAirBox() : test::wholeDrum());
    drum.setEnergyTracking(true);
    drum.setProfiling(true);
    const auto& p = drum.profile();
    CHECK(p.path == (airBox ? StepPath::airBox : StepPath::cavity));

    const int steps = airBox ? 300 : 1500;
    drum.playNote(38, 127);
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
        drum.step();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    CHECK(p.steps == steps);
    double listed = 0.0;
    for (const auto phase : StepProfile::phasesOf(p.path))
    {
        INFO(StepProfile::name(phase));
        CHECK(p[phase] >= 0.0);
        listed += p[phase];
    }
    // The path's phases hold all of it: the others were never timed.
    CHECK(listed == Approx(p.total()).epsilon(1e-12));
    for (int i = 0; i < StepProfile::numPhases; ++i)
    {
        const auto phases = StepProfile::phasesOf(p.path);
        if (std::find(phases.begin(), phases.end(), (StepPhase) i) == phases.end())
            CHECK(p.seconds[(size_t) i] == 0.0);
    }
    CHECK(p.total() > 0.0);
    CHECK(p.total() <= wall + 1e-6); // the phases lie between the clock reads around the loop
    CHECK(p[StepPhase::energy] > 0.0);
    CHECK(p[StepPhase::batterFree] > 0.0);
    snaresim::test::reportf("step profile, %s: phases %.4g s of %.4g s around the steps (%.1f%%)\n", airBox ? "air box" : "cavity",
                            p.total(), wall, 100.0 * p.total() / wall);

    // Off: the profile stays as it was; reset: empty, the path kept.
    const StepProfile before = p;
    drum.setProfiling(false);
    for (int n = 0; n < 10; ++n)
        drum.step();
    CHECK(p.steps == before.steps);
    CHECK(p.seconds == before.seconds);
    drum.resetProfile();
    CHECK(p.steps == 0);
    CHECK(p.total() == 0.0);
    CHECK(p.path == before.path);
}

TEST_CASE("the step profile lists each path's phases once, with distinct names", "[drum][profile]")
{
    for (const auto path : { StepPath::cavity, StepPath::airBox })
    {
        const auto phases = StepProfile::phasesOf(path);
        for (size_t i = 0; i < phases.size(); ++i)
            for (size_t j = i + 1; j < phases.size(); ++j)
            {
                CHECK(phases[i] != phases[j]);
                CHECK(StepProfile::name(phases[i]) != StepProfile::name(phases[j]));
            }
    }
    CHECK(StepProfile::phasesOf(StepPath::cavity).size() == 10);
    CHECK(StepProfile::phasesOf(StepPath::airBox).size() == 11);
    CHECK(StepProfile::name(StepPhase::snareContact) == "snare_contact");
    CHECK(StepProfile::name(StepPhase::advance) == "advance");
}
