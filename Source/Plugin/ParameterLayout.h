#pragma once
// The plug-in's parameters, built from the engine's parameter table (Parameters.h): one JUCE
// parameter per entry, keyed by its ID, with its range, skew, unit and default.

#include <juce_audio_processors/juce_audio_processors.h>

#include "Parameters.h"

namespace snaresim::plugin
{

juce::AudioProcessorValueTreeState::ParameterLayout createParameterLayout();

// A value from a host or a saved state, made safe for the engine: finite, in range, whole
// for toggles, choices and integers (non-finite values give the default).
double sanitise (const ParameterSpec& spec, double raw) noexcept;

} // namespace snaresim::plugin
