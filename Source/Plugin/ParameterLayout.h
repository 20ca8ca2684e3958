#pragma once
// The plug-in's parameters, built from the engine's parameter table (Parameters.h): one JUCE
// parameter per entry, keyed by its ID, with its range, skew, unit and default.

#include <juce_audio_processors/juce_audio_processors.h>

#include "Parameters.h"

namespace snaresim::plugin
{

juce::AudioProcessorValueTreeState::ParameterLayout createParameterLayout();

} // namespace snaresim::plugin
