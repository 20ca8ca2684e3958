#pragma once
// The editor's "Load..." and "Save..." of preset files (snaresim PresetFile.h, ".snarepreset"):
// the same files the renderer's --preset FILE reads and the factory presets are made of.

#include <juce_core/juce_core.h>

class SnareSimAudioProcessor;

namespace snaresim::ui
{

// Message thread. Sets every parameter but keep_up (the machine's) from the file: its values,
// the defaults for the rest.
// Returns what went wrong (one line naming the file, and the line of it), empty on success;
// on failure no parameter changes.
juce::String loadPresetFile(SnareSimAudioProcessor& processor, const juce::File& file);

// Writes the parameters as the host holds them (those that differ from their defaults), named
// after the file. The file is replaced whole or not at all. Returns what went wrong, empty on
// success.
juce::String savePresetFile(const SnareSimAudioProcessor& processor, const juce::File& file);

} // namespace snaresim::ui
