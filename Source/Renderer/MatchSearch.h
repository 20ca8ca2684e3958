#pragma once
// The search of --match, on the unit cube [0, 1]^n (Match.cpp maps each coordinate to a
// parameter): deterministic and bounded by a number of evaluations.
//
//   1. the start point and a Latin hypercube of about a third of the budget (fixed seed): the
//      global stage, which finds the right basin whatever the start;
//   2. a compass (coordinate pattern) search from the best point so far: every coordinate
//      moved by +-h at once (a batch the objective may evaluate in parallel), the best
//      improvement taken, h halved when none improves, from h = 1/8 down to 1/256; while
//      budget remains, another from the best hypercube point a quarter of the cube away from
//      every earlier start (another basin);
//   3. a few of the best points (the objective decides how many) handed back for a final
//      comparison that can smooth the noise of a single evaluation (Match.cpp).
//
// The objective counts its own cost (a cached point costs nothing), so the budget bounds the
// renders, not the calls.

#include <cstdint>
#include <functional>
#include <vector>

namespace snaresim::render
{

using UnitPoint = std::vector<double>;

class SearchObjective
{
public:
    virtual ~SearchObjective() = default;
    // The distances of the points, in order.
    virtual std::vector<double> evaluate(const std::vector<UnitPoint>& points) = 0;
    // The evaluations paid for so far (the budget counts these).
    virtual int cost() const = 0;
};

struct SearchSettings
{
    int budget = 200;              // evaluations this search may pay for (the objective's cost() from its start)
    std::uint64_t seed = 20240611; // --match-seed
    double globalShare = 0.35;     // of the budget, for the Latin hypercube
    double firstStep = 0.125;
    double lastStep = 1.0 / 256.0;
    double restartSeparation = 0.25; // a new compass search starts this far (max norm) from the others
};

struct SearchPoint
{
    UnitPoint point;
    double distance = 0.0;
};

// Every point evaluated, best first (ties: the earlier), at most `keep` of them distinct.
std::vector<SearchPoint> searchMinimum(const UnitPoint& start, SearchObjective& objective, const SearchSettings& settings, int keep);

} // namespace snaresim::render
