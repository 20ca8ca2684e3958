#include "Articulations.h"

#include <array>

namespace snaresim
{

namespace
{
using A = ArticulationAction;

constexpr std::array<Articulation, 6> kMap { {
    { 38, "Centre strike (GM acoustic snare)", A::strike, -1.0, 0.4, 1.0 },
    { 40, "Off-centre strike (GM electric snare)", A::strike, 0.55, 0.9, 1.0 },
    { 37, "Near-rim strike (GM side stick)", A::strike, 0.85, 0.6, 0.8 },
    { 39, "Edge ghost (quiet, near the rim)", A::strike, 0.75, 1.2, 0.35 },
    { 33, "Snares off", A::snaresOff, 0.0, 0.0, 0.0 },
    { 34, "Snares on", A::snaresOn, 0.0, 0.0, 0.0 },
} };

constexpr Articulation kMainStrike { -1, "Main strike", A::strike, -1.0, 0.4, 1.0 };
} // namespace

std::span<const Articulation> articulations() { return kMap; }

const Articulation& mainStrike() { return kMainStrike; }

const Articulation& articulationForNote(int note)
{
    for (const auto& a : kMap)
        if (a.note == note)
            return a;
    return kMainStrike;
}

} // namespace snaresim
