#pragma once
// Named factory presets: each is a set of parameter values over the defaults.

#include "Parameters.h"

#include <span>
#include <string_view>
#include <utility>

namespace snaresim
{

struct Preset
{
    std::string_view name;
    std::span<const std::pair<ParamId, double>> values; // the rest stay at their defaults
};

std::span<const Preset> factoryPresets();

// Resets params to the defaults and applies the named preset (case-insensitive).
// Returns false, leaving params untouched, when no preset has that name.
bool applyPreset(std::string_view name, ParameterSet& params);

} // namespace snaresim
