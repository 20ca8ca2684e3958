// The pressure microphones (PressureMicrophones.h) against the air box's pressure at the same
// points: octave-band levels of the first 300 ms after a strike; their taps summed a block of
// steps at a time against step by step.
#include "Drum.h"
#include "Membrane.h"
#include "MicBands.h"
#include "PressureMicrophones.h"
#include "Report.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace snaresim;
using namespace snaresim::test;

TEST_CASE("pressure microphones: octave bands 125 Hz - 4 kHz within 3 dB of the air box's pressure, and the whole real-time drum to 500 Hz",
          "[mics][airbox][slow]")
{
    // The same heads' motion heard two ways: the air box's own pressure at the microphones and
    // the radiation model on the box's heads. The box's heads stand in for the real-time ones
    // here: the real-time drum's heads move otherwise above 500 Hz (printed below, and
    // docs/MODEL.md, "The real-time drum as a whole"), which is the reduced air's part, not the
    // microphones'.
    const DrumConfig cfg = micDrum();
    const double fs = cfg.sampleRate_Hz;
    const int samples = (int) std::lround(0.3 * fs);
    const Recording box = record(inBox(cfg), samples);
    CHECK(worstDifference("radiation model on the box's heads", box.model, box.drum, fs, kOctaves.back(), reportFile()) < 3.0);
    // The check can fail: a head's velocity under the microphone as a plane wave's pressure
    // (the microphones before the radiation model) is far from it.
    CHECK(worstDifference("rho c v under the microphone", box.plane, box.drum, fs, kOctaves.back(), reportFile()) > 6.0);

    // The whole real-time drum (cavity, outside air and its near field) beside the box. Its air's
    // kinetic reserves widen its grids by 1-5 %, and this stick chatters on the batter's grid, so
    // the box's heads are put on the same grids (a 2 % wider grid alone moves these bands by up
    // to 5 dB: airbox_figures whole-drum coarser=1.02 no-near-field).
    DrumConfig realTime = cfg;
    realTime.outside.enabled = realTime.outside.nearField = true;
    const Recording boxOnGrids = record(onGridsOf(inBox(cfg), realTime), samples);
    const Recording rt = record(realTime, samples);
    // Within 3 dB up to 500 Hz (above, the box's inside air carries sound the reduced cavity
    // does not: docs/MODEL.md, "The real-time drum as a whole")
    CHECK(worstDifference("the real-time drum (cavity, outside air, near field), the box on its grids", rt.drum, boxOnGrids.drum, fs, 500.0,
                          reportFile()) < 3.0);
    // Reported: without the near field the batter's (2,1) mode stands 14 % high, out of the
    // 500 Hz band; how far that band then lies from the box's depends on the strike's chatter:
    // 4.1 dB at the room mic on these grids, 4.5 dB on the channels' own.
    if (reporting())
    {
        DrumConfig channelsOnly = realTime;
        channelsOnly.outside.nearFieldUpTo_per_m = 0.0;
        const Recording rtChannels = record(onGridsOf(channelsOnly, realTime), samples); // on the same grids too
        worstDifference("the real-time drum without the near field, the box on its grids", rtChannels.drum, boxOnGrids.drum, fs,
                        kOctaves.back(), reportFile());
    }
}

TEST_CASE("pressure microphones: the taps summed a block of steps at a time give the sound summed step by step, the microphones near, far "
          "and moved",
          "[mics]")
{
    // Two listeners on the same heads' motion: one sums its taps every step, one a block of
    // steps at a time (PressureMicrophones.h), moved mid-block close to the heads and back: the
    // same samples, bit for bit. A block that held a step more than its shortest delay
    // allows, or a block cut short by a move that added the steps it had not reached, would
    // put sound into samples already heard or add older steps again: differences of the order
    // of the sound itself.
    const DrumConfig cfg = test::wholeDrum();
    const double k = 1.0 / cfg.sampleRate_Hz;
    Membrane batter(cfg.batter, k), carry(cfg.carry, k);
    const double top = 0.5 * cfg.cavity.shellDepth_m, bottom = -top;
    MicSpec far = cfg.mics; // 4 cm from each head: five whole steps, blocks of six
    far.top = { -0.02, 0.05, top + 0.04 };
    far.room = { 0.4, 0.2, 0.9 };
    MicSpec near = far;
    near.top = { 0.03, -0.02, top + 0.002 };       // 2 mm over the batter: no whole step, a step a block
    near.bottom = { -0.05, 0.01, bottom - 0.015 }; // 1.5 cm under the carry head
    PressureMicrophones blocks(far, cfg.cavity, cfg.sampleRate_Hz, batter, carry), steps = blocks;
    steps.setLongestBlock(1);

    GridDistribution stick, below;
    stick.reserve(batter.grid().distributionCapacity(0.01));
    below.reserve(carry.grid().distributionCapacity(0.01));
    REQUIRE(batter.grid().makeDistribution(0.04, 0.03, 0.01, stick));
    REQUIRE(carry.grid().makeDistribution(-0.06, 0.02, 0.01, below));
    double worst = 0.0, loudest = 0.0;
    const int samples = (int) std::lround(0.05 * cfg.sampleRate_Hz);
    for (int n = 0; n < samples; ++n)
    {
        batter.computeFree();
        carry.computeFree();
        if (n < 40) // a short push on each head, each its own shape
        {
            batter.applyForce(stick, 20.0 * std::sin(std::numbers::pi * n / 40.0));
            carry.applyForce(below, -8.0 * std::sin(std::numbers::pi * n / 40.0));
        }
        if (n == 6 * 100 + 3 || n == 1400) // in, three steps into a block of six, and out again
        {
            const MicSpec& to = n < 1000 ? near : far;
            blocks.setPositions(to, cfg.cavity.shellDepth_m);
            steps.setPositions(to, cfg.cavity.shellDepth_m);
        }
        blocks.listen(batter, carry);
        steps.listen(batter, carry);
        for (int m = 0; m < PressureMicrophones::numMics; ++m)
        {
            const auto p = (PressureMicrophones::Position) m;
            worst = std::max(worst, std::abs(blocks.pressure(p) - steps.pressure(p)));
            loudest = std::max(loudest, std::abs(steps.pressure(p)));
        }
        batter.advance();
        carry.advance();
    }
    REQUIRE(loudest > 1.0); // Pa: the heads sound
    CHECK(worst == 0.0);    // the same sums in the same order
}

TEST_CASE("pressure microphones: a strike sounds the same to the last bit however long the drum stood still before it", "[mics]")
{
    // The steps before the strike set where the blocks of steps fall; the taps' sums reach each
    // sample in the order summing step by step would give them (PressureMicrophones.h).
    DrumConfig cfg = test::wholeDrum();
    cfg.mics.mixTop = cfg.mics.mixBottom = cfg.mics.mixRoom = 1.0;
    const int samples = (int) std::lround(0.03 * cfg.sampleRate_Hz);
    auto struck = [&](int stillSteps) {
        Drum drum(cfg);
        for (int n = 0; n < stillSteps; ++n)
            drum.step();
        std::vector<double> out;
        drum.strike(3.0, 0.3, 0.2);
        for (int n = 0; n < samples; ++n)
            out.push_back(drum.step());
        return out;
    };
    const std::vector<double> fresh = struck(0);
    REQUIRE(*std::max_element(fresh.begin(), fresh.end()) > 0.0);
    for (int still : { 1, 4, 7 })
        CHECK(struck(still) == fresh);
}
