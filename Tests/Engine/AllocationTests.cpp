// The drum's audio-thread path allocates nothing, the energy ledger included: this test binary
// replaces the global operator new / delete and counts the allocations made on a thread while
// a thread_local flag is on, which the test sets around the calls it checks only.

#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <thread>

#include "CountingAllocator.h"

using snaresim::test::CountAllocations;
using namespace snaresim;

TEST_CASE("the allocation counter sees allocations on the counted thread only", "[energy][realtime]")
{
    const long before = snaresim::test::countedAllocations.load();
    {
        CountAllocations counting;
        auto* p = new int(3);
        delete p;
    }
    CHECK(snaresim::test::countedAllocations.load() == before + 1);
    auto* q = new int(4); // not counted
    delete q;
    CHECK(snaresim::test::countedAllocations.load() == before + 1);

    // Another thread's allocations are not counted while this one counts: a thread that
    // allocates adds what one that does not adds (the thread's own state, allocated here).
    const auto added = [](auto body) {
        CountAllocations counting;
        const long start = snaresim::test::countedAllocations.load();
        std::thread(body).join();
        return snaresim::test::countedAllocations.load() - start;
    };
    const long idle = added([] {});
    const long allocating = added([] {
        for (int i = 0; i < 100; ++i)
            delete new int(i);
    });
    CHECK(allocating == idle);
}

TEST_CASE("strikes, steps, the snares switch and reset allocate nothing, with the energy ledger kept", "[energy][realtime]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    const bool profiled = GENERATE(false, true); // the step profile (StepProfile.h) on or off
    cfg.room = { 0.4, 60.0 };                    // the room's diffuse field (DiffuseRoom.h) with them
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.setProfiling(profiled);
    EnergyLedger copy;
    double sum = 0.0;

    const long before = snaresim::test::countedAllocations.load();
    {
        CountAllocations counting;
        for (int n = 0; n < 3000; ++n)
        {
            if (n % 500 == 0)
                drum.playNote(38, 127);
            if (n == 1200)
                drum.playNote(33, 100); // snares off
            if (n == 1800)
                drum.playNote(34, 100); // snares on
            if (n == 2400)
            {
                DrumConfig larger = cfg;
                larger.room = { 1.2, 400.0 }; // a new room, played live
                drum.applyLive(larger);
            }
            sum += drum.step();
            copy = drum.energy(); // as the renderer keeps every sample's ledger
            sum += copy.balance();
        }
        drum.reset();
        sum += drum.energy().total();
        drum.resetProfile();
        drum.setProfiling(false);
        sum += drum.step();
    }
    CHECK(snaresim::test::countedAllocations.load() == before);
    CHECK(std::isfinite(sum));
    CHECK(copy.size() == 5);
}

TEST_CASE("the drum in the air box steps, and takes new head damping, without allocating", "[energy][realtime][airbox]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.cavity.model = AirModel::airbox;
    // Each scheme once and the step profile off and on (the profile's clock is the same for both
    // schemes): two air-box drums, not four.
    const auto [scheme, profiled] =
        GENERATE(table<CollisionScheme, bool>({ { CollisionScheme::newton, false }, { CollisionScheme::quadratised, true } }));
    cfg.snares.scheme = scheme;
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.setProfiling(profiled);
    DrumConfig damped = cfg; // a live change that reaches the embeddings' solves (DrumAir::refresh)
    damped.batter.sigma0_per_s = 2.0 * cfg.batter.sigma0_per_s + 1.0;
    damped.carry.sigma0_per_s = 2.0 * cfg.carry.sigma0_per_s + 1.0;
    double sum = 0.0;
    drum.step(); // the first step sizes nothing either, but keep the check on the steady state too
    const long before = snaresim::test::countedAllocations.load();
    {
        CountAllocations counting;
        for (int n = 0; n < 800; ++n)
        {
            if (n % 400 == 0)
                drum.playNote(38, 127);
            if (n == 200)
                drum.applyLive(damped);
            sum += drum.step();
            sum += drum.energy().balance() + drum.airMicPressure(0);
        }
    }
    CHECK(snaresim::test::countedAllocations.load() == before);
    CHECK(std::isfinite(sum));
    CHECK(drum.energy().size() == 6);
}
