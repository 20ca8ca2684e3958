// The search of --match (Source/Renderer/MatchSearch.h) on functions whose minimum is known.

#include "MatchSearch.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <map>

using namespace snaresim::render;

namespace
{

// A function on the unit cube that counts its evaluations, a repeated point for free.
class Counted final : public SearchObjective
{
public:
    explicit Counted(std::function<double(const UnitPoint&)> f) : f(std::move(f)) {}
    std::vector<double> evaluate(const std::vector<UnitPoint>& points) override
    {
        std::vector<double> result;
        for (const auto& p : points)
        {
            if (! seen.count(p))
                seen[p] = f(p);
            result.push_back(seen[p]);
        }
        return result;
    }
    int cost() const override { return (int) seen.size(); }

private:
    std::function<double(const UnitPoint&)> f;
    std::map<UnitPoint, double> seen;
};

} // namespace

TEST_CASE("match search: a smooth bowl's minimum, within the budget, the same every time", "[renderer][match][search]")
{
    const UnitPoint centre { 0.71, 0.23, 0.48 };
    auto bowl = [&](const UnitPoint& p) {
        double sum = 0.0;
        for (std::size_t i = 0; i < p.size(); ++i)
            sum += (p[i] - centre[i]) * (p[i] - centre[i]) * (1.0 + (double) i);
        return std::sqrt(sum);
    };
    SearchSettings settings;
    settings.budget = 150;
    UnitPoint found;
    for (int run = 0; run < 2; ++run)
    {
        Counted objective(bowl);
        const auto ranked = searchMinimum({ 0.0, 1.0, 0.0 }, objective, settings, 3);
        CHECK(objective.cost() <= settings.budget);
        REQUIRE(ranked.size() == 3);
        CHECK(ranked[0].distance <= ranked[1].distance);
        CHECK(ranked[1].distance <= ranked[2].distance);
        for (std::size_t i = 0; i < centre.size(); ++i)
            CHECK(ranked[0].point[i] == Approx(centre[i]).margin(0.01));
        if (run == 1)
            CHECK(ranked[0].point == found);
        found = ranked[0].point;
    }
}

TEST_CASE("match search: the global stage finds the deep basin, not the one at the start", "[renderer][match][search]")
{
    // A shallow basin around the start and a deep narrow one elsewhere.
    auto twoBasins = [](const UnitPoint& p) {
        const double near = std::hypot(p[0] - 0.1, p[1] - 0.1), far = std::hypot(p[0] - 0.8, p[1] - 0.65);
        return std::min(0.5 + near, 4.0 * far);
    };
    Counted objective(twoBasins);
    SearchSettings settings;
    settings.budget = 60;
    const auto ranked = searchMinimum({ 0.1, 0.1 }, objective, settings, 1);
    CHECK(ranked[0].distance < 0.2); // the shallow basin's floor is 0.5
    CHECK(ranked[0].point[0] == Approx(0.8).margin(0.05));
    CHECK(ranked[0].point[1] == Approx(0.65).margin(0.05));
    CHECK(objective.cost() <= 60);
}
