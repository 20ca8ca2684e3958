// The snare contact's work per step: the quadratised solve takes only the node groups where a
// point touches or may touch within the step (SnareContact.h), and that gives the numbers of
// solving every point, bit for bit.

#include "Drum.h"
#include "DrumConfig.h"
#include "Parameters.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <vector>

using namespace snaresim;

namespace
{
bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// A fortissimo roll (a strike every 60 ms for 0.5 s) and its decay, then a soft strike.
bool strikesAt(long n, int& velocity)
{
    constexpr long interval = 2880; // 60 ms at 48 kHz
    if (n < 24000 && n % interval == 0)
        return (velocity = 127), true;
    if (n == 36000)
        return (velocity = 20), true;
    return false;
}
} // namespace

TEST_CASE("snare contact: solving where the points touch gives every point's solve bit for bit, in less work", "[drum][snares][work]")
{
    DrumConfig cfg = makeDrumConfig(ParameterSet {}, 48000.0);
    const double exponent = GENERATE(1.5, 1.25); // the Hertz kernel, and the general power law
    cfg.snares.exponent = exponent;
    REQUIRE(cfg.snares.scheme == CollisionScheme::quadratised);
    Drum subset(cfg), every(cfg);
    every.snareContact().setSolveEveryPoint(true);
    const int points = subset.snareContact().numPoints();
    REQUIRE(points > 100);

    long differing = 0, steps = 0, solved = 0, overBound = 0, touchingSteps = 0;
    int mostSolved = 0;
    for (long n = 0; n < 43200; ++n) // 0.9 s
    {
        int velocity = 0;
        if (strikesAt(n, velocity))
        {
            subset.playNote(38, velocity);
            every.playNote(38, velocity);
        }
        const double a = subset.step(), b = every.step();
        const auto& gapsA = subset.snareContact().gaps();
        const auto& gapsB = every.snareContact().gaps();
        bool same = sameBits(a, b) && sameBits(subset.snareContact().quadratisedEnergy(), every.snareContact().quadratisedEnergy());
        for (int p = 0; p < points && same; ++p)
            same = sameBits(gapsA[(size_t) p], gapsB[(size_t) p]);
        differing += same ? 0 : 1;
        const int k = subset.snareContact().solvedPoints();
        overBound += k > points || every.snareContact().solvedPoints() != points ? 1 : 0;
        mostSolved = std::max(mostSolved, k);
        solved += k;
        touchingSteps += subset.solverStats().snareContacts > 0 ? 1 : 0;
        ++steps;
    }
    const double meanShare = (double) solved / ((double) steps * points);
    INFO("exponent " << exponent << ": " << points << " points; solved per step: mean " << meanShare * points << " (" << 100.0 * meanShare
                     << " %), most " << mostSolved << "; steps with a point touching " << touchingSteps << " of " << steps
                     << "; steps differing from every point's solve " << differing);
    CHECK(differing == 0);
    CHECK(overBound == 0);
    CHECK(touchingSteps > steps / 4); // the wires do touch and leave the head through the roll
    CHECK(touchingSteps < steps);
    CHECK(meanShare < 0.5); // and most of the time most points are out of reach
}
