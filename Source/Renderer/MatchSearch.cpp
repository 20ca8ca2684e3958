#include "MatchSearch.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace snaresim::render
{
namespace
{

// Uniform in [0, 1) from 53 bits (the same on every platform, unlike the standard distributions).
double unit(std::mt19937_64& rng) { return (double) (rng() >> 11) * 0x1.0p-53; }

std::vector<UnitPoint> latinHypercube(std::size_t dimensions, int count, std::mt19937_64& rng)
{
    std::vector<UnitPoint> points((std::size_t) count, UnitPoint(dimensions));
    std::vector<int> strata((std::size_t) count);
    for (std::size_t d = 0; d < dimensions; ++d)
    {
        for (int i = 0; i < count; ++i)
            strata[(std::size_t) i] = i;
        for (int i = count - 1; i > 0; --i) // Fisher-Yates
            std::swap(strata[(std::size_t) i], strata[(std::size_t)(rng() % (std::uint64_t)(i + 1))]);
        for (int i = 0; i < count; ++i)
            points[(std::size_t) i][d] = (strata[(std::size_t) i] + unit(rng)) / count;
    }
    return points;
}

class History
{
public:
    explicit History(SearchObjective& objective) : objective(objective) {}

    // Evaluates the points, remembers them; returns their distances.
    std::vector<double> evaluate(const std::vector<UnitPoint>& points)
    {
        auto distances = objective.evaluate(points);
        for (std::size_t i = 0; i < points.size(); ++i)
            all.push_back({ points[i], distances[i] });
        return distances;
    }

    const SearchPoint& best() const
    {
        return *std::min_element(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.distance < b.distance; });
    }

    std::vector<SearchPoint> ranked(int keep) const
    {
        auto sorted = all;
        std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.distance < b.distance; });
        std::vector<SearchPoint> result;
        for (const auto& p : sorted)
        {
            if ((int) result.size() >= keep)
                break;
            if (std::none_of(result.begin(), result.end(), [&](const auto& q) { return q.point == p.point; }))
                result.push_back(p);
        }
        return result;
    }

private:
    SearchObjective& objective;
    std::vector<SearchPoint> all;
};

} // namespace

std::vector<SearchPoint> searchMinimum(const UnitPoint& start, SearchObjective& objective, const SearchSettings& settings, int keep)
{
    const std::size_t n = start.size();
    const int limit = objective.cost() + settings.budget; // what the objective may have paid at the end
    History history(objective);
    history.evaluate({ start });

    // 1. Global: a Latin hypercube.
    std::mt19937_64 rng(settings.seed);
    const int global = std::max(2, (int) std::lround(settings.globalShare * settings.budget));
    if (n > 0 && objective.cost() < limit)
    {
        auto points = latinHypercube(n, global, rng);
        points.resize((std::size_t) std::min<int>(global, limit - objective.cost()));
        history.evaluate(points);
    }

    // 2. Local: compass searches, the first from the best point so far; while budget remains,
    // again from the best point of the hypercube stage away from every earlier start.
    std::vector<UnitPoint> starts;
    const auto globalPoints = history.ranked(global + 1);
    auto farFromStarts = [&](const UnitPoint& p) {
        return std::all_of(starts.begin(), starts.end(), [&](const UnitPoint& q) {
            double far = 0.0;
            for (std::size_t d = 0; d < n; ++d)
                far = std::max(far, std::abs(p[d] - q[d]));
            return far >= settings.restartSeparation;
        });
    };
    for (std::size_t next = 0; n > 0 && objective.cost() < limit;)
    {
        UnitPoint centre;
        double centreDistance = 0.0;
        if (starts.empty())
        {
            centre = history.best().point;
            centreDistance = history.best().distance;
        }
        else
        {
            while (next < globalPoints.size() && ! farFromStarts(globalPoints[next].point))
                ++next;
            if (next == globalPoints.size())
                break;
            centre = globalPoints[next].point;
            centreDistance = globalPoints[next].distance;
        }
        starts.push_back(centre);

        for (double step = settings.firstStep; step >= settings.lastStep && objective.cost() < limit;)
        {
            std::vector<UnitPoint> polls;
            for (std::size_t d = 0; d < n; ++d)
                for (const double sign : { 1.0, -1.0 })
                {
                    auto p = centre;
                    p[d] = std::clamp(p[d] + sign * step, 0.0, 1.0);
                    if (p[d] != centre[d])
                        polls.push_back(std::move(p));
                }
            polls.resize(std::min<std::size_t>(polls.size(), (std::size_t)(limit - objective.cost())));
            const auto distances = history.evaluate(polls);
            const auto best = std::min_element(distances.begin(), distances.end());
            if (best != distances.end() && *best < centreDistance)
            {
                centre = polls[(std::size_t)(best - distances.begin())];
                centreDistance = *best;
            }
            else
                step *= 0.5;
        }
    }
    return history.ranked(keep);
}

} // namespace snaresim::render
