#pragma once
// Reading the strikes of a Standard MIDI file (juce::MidiFile).

#include "RenderJob.h"

#include <filesystem>
#include <vector>

namespace snaresim::render
{

// Every note-on with velocity > 0 of every track, at its time in seconds (tempo map
// honoured), sorted by time. Note numbers and channels are ignored: each note-on is one
// strike at the default point. Throws UserError when the file cannot be read or is not a
// valid Standard MIDI file, or when a note-on lies beyond kMaxSeconds.
std::vector<Strike> readMidiStrikes(const std::filesystem::path& file);

} // namespace snaresim::render
