#pragma once
// Named factory presets: each is a set of parameter values over the defaults, read from the
// preset files in Resources/Presets (PresetFile.h), embedded in the engine at build time.

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

// In the files' order (their names' numbers): the hosts' program numbers. The first call reads
// the embedded files (allocates): make it off the audio thread.
std::span<const Preset> factoryPresets();

// Resets params to the defaults and applies the named preset (case-insensitive).
// Returns false, leaving params untouched, when no preset has that name.
bool applyPreset(std::string_view name, ParameterSet& params);

} // namespace snaresim
