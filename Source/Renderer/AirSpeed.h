#pragma once
// How fast the air box updates, against a bare 7-point stencil on the same grid, timed in the
// same run: for benchmarks (snaresim-render --bench --model airbox, airbox_bench). Never on the
// audio thread (allocates, spends a second or so).
//
// The bare stencil is out = a0 u + a1 (6 neighbours of u) - up over every node of arrays of the
// box's padded size: no walls, no cut links, no sigma_a, built the same way as the air box's
// loops (once per vector target, VectorTarget.h; no contraction). The kinds are timed in turns, round after
// round, each kind's figure its fastest round: what the machine does meanwhile (others' jobs on a
// shared machine) lands on every kind alike and is mostly filtered out.

#include "AirBox.h"

namespace snaresim
{

struct AirSpeed
{
    long points = 0;        // air nodes
    double spacing_m = 0.0; // h_a
    int threads = 1;        // for airThreadsStep_s
    int steps = 0;          // steps per round
    int rounds = 0;
    double bareStep_s = 0.0;       // bare stencil, double, one thread: seconds per step
    double bareFloatStep_s = 0.0;  // the same in single precision
    double airStep_s = 0.0;        // AirBox::computeNext (walls, shell, cut links, sigma_a), one thread
    double airThreadsStep_s = 0.0; // the same with `threads` threads

    static double rate(long points, double step_s) { return step_s > 0.0 ? (double) points / step_s : 0.0; }
    double bareRate() const { return rate(points, bareStep_s); }
    double bareFloatRate() const { return rate(points, bareFloatStep_s); }
    double airRate() const { return rate(points, airStep_s); }
    double airThreadsRate() const { return rate(points, airThreadsStep_s); }
};

// Times box (its state is overwritten: a smooth pulse, then whatever the steps make of it) and
// the bare stencil on its grid, `rounds` rounds of about `roundSeconds` each per kind.
AirSpeed measureAirSpeed(AirBox& box, int threads, int rounds = 7, double roundSeconds = 0.02);

} // namespace snaresim
