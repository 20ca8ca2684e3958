#pragma once
// The plug-in's saved state: every parameter's value as XML (the APVTS tree) with a version
// attribute. Reading accepts every version written so far and anything else a host may hand
// over: what cannot be read as a SnareSim state changes nothing; a SnareSim state restores
// every parameter, to its stored value (sanitised) or, when missing or unreadable, its default.

#include "Parameters.h"

#include <juce_audio_processors/juce_audio_processors.h>

namespace snaresim::plugin
{

struct PluginState
{
    // Written into saved states; states without it are read as version 0. The versions and
    // their migrations are the schema's (kStateVersion, parameterMigrations(): Parameters.h).
    static constexpr int version = kStateVersion;
    static constexpr const char* versionAttribute = "stateVersion";
    static constexpr const char* treeType = "SnareSimState";

    static void write(juce::AudioProcessorValueTreeState& parameters, juce::MemoryBlock& destination);

    // True when the data was a SnareSim state and the parameters were set from it.
    static bool read(juce::AudioProcessorValueTreeState& parameters, const void* data, int sizeInBytes);
};

} // namespace snaresim::plugin
