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

constexpr std::array<V, 0> kDefault {};
constexpr std::array<V, 3> kTight { { { P::batterTension, 4800.0 }, { P::batterDecay, 0.6 }, { P::malletStiffness, 3.0e8 } } };
constexpr std::array<V, 3> kFat { { { P::batterTension, 1800.0 }, { P::batterDecay, 2.5 }, { P::malletMass, 0.04 } } };

constexpr std::array<Preset, 3> kPresets { {
    { "Default", kDefault },
    { "Tight Funk", kTight },
    { "Fat Rock", kFat },
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
