#include "Presets.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace snaresim
{

namespace
{
using P = ParamId;
using V = std::pair<ParamId, double>;

constexpr std::array<V, 0> kStudio {};
constexpr std::array<V, 4> kTightFunk { { { P::batterTension, 4800.0 }, { P::snareTension, 55.0 }, { P::damping, 45.0 },
                                         { P::malletStiffness, 3.0e8 } } };
constexpr std::array<V, 6> kFatRock { { { P::batterTension, 1800.0 }, { P::carryTension, 1600.0 }, { P::snareTension, 22.0 },
                                       { P::damping, 15.0 }, { P::malletMass, 0.04 }, { P::shellDepth, 0.165 } } };
constexpr std::array<V, 6> kPiccolo { { { P::batterTension, 5600.0 }, { P::carryTension, 4200.0 }, { P::shellDepth, 0.076 },
                                       { P::snareTension, 45.0 }, { P::damping, 30.0 }, { P::malletMass, 0.02 } } };
constexpr std::array<V, 2> kSnaresOff { { { P::snaresEngaged, 0.0 }, { P::damping, 20.0 } } };
constexpr std::array<V, 5> kLooseVintage { { { P::batterTension, 1500.0 }, { P::carryTension, 1200.0 }, { P::snareTension, 14.0 },
                                            { P::damping, 8.0 }, { P::highDamping, 2.0e-3 } } };
constexpr std::array<V, 3> kMuffledDry { { { P::damping, 85.0 }, { P::highDamping, 2.5e-3 }, { P::snareTension, 40.0 } } };
constexpr std::array<V, 6> kMarching { { { P::batterTension, 6000.0 }, { P::carryTension, 5000.0 }, { P::snareTension, 90.0 },
                                        { P::malletMass, 0.05 }, { P::malletStiffness, 1.0e9 }, { P::damping, 20.0 } } };
constexpr std::array<V, 4> kSoftMallet { { { P::malletExponent, 2.5 }, { P::malletStiffness, 3.0e6 },
                                          { P::malletContactRadius, 0.015 }, { P::malletMass, 0.04 } } };

constexpr std::array<Preset, 9> kPresets { {
    { "Studio Default", kStudio },
    { "Tight Funk", kTightFunk },
    { "Fat Rock", kFatRock },
    { "Piccolo", kPiccolo },
    { "Snares Off", kSnaresOff },
    { "Loose Vintage", kLooseVintage },
    { "Muffled Dry", kMuffledDry },
    { "Marching", kMarching },
    { "Soft Mallet", kSoftMallet },
} };

bool equalNoCase(std::string_view a, std::string_view b)
{
    return a.size() == b.size()
        && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower((unsigned char) x) == std::tolower((unsigned char) y);
           });
}
} // namespace

std::span<const Preset> factoryPresets() { return kPresets; }

bool applyPreset(std::string_view name, ParameterSet& params)
{
    for (const auto& p : kPresets)
    {
        if (! equalNoCase(p.name, name))
            continue;
        params = ParameterSet {};
        for (const auto& [id, value] : p.values)
            params.set(id, value);
        return true;
    }
    return false;
}

} // namespace snaresim
