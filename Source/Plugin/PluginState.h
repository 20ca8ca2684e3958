#pragma once
// The plug-in's saved state: every parameter's value as XML (the APVTS tree) with a version
// attribute. Reading accepts every version written so far and anything else a host may hand
// over: what cannot be read as a SnareSim state changes nothing; a SnareSim state restores
// every parameter, to its stored value (sanitised) or, when missing or unreadable, its default.

#include <juce_audio_processors/juce_audio_processors.h>

namespace snaresim::plugin
{

struct PluginState
{
    // Written into saved states; states without it are read as version 0.
    // 1: the first version's table (batter_decay, batter_high_damping, listen_position).
    // 2: today's table (damping, high_damping, mic_top_position, ...).
    static constexpr int version = 2;
    static constexpr const char* versionAttribute = "stateVersion";
    static constexpr const char* treeType = "SnareSimState";

    static void write (juce::AudioProcessorValueTreeState& parameters, juce::MemoryBlock& destination);

    // True when the data was a SnareSim state and the parameters were set from it.
    static bool read (juce::AudioProcessorValueTreeState& parameters, const void* data, int sizeInBytes);

    // Damping (%) for a version-1 batter_decay T60 (s): 100 ln(T60 / 4) / ln(0.15 / 4), 0..100.
    static double dampingFromDecay (double t60Seconds) noexcept;
};

} // namespace snaresim::plugin
