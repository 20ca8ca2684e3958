#pragma once
// Reading the strikes of a Standard MIDI file (juce::MidiFile).

#include "RenderJob.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace juce
{
class InputStream;
}

namespace snaresim::render
{

// Every note-on with velocity > 0 of every track, at its time in seconds (tempo map
// honoured), sorted by time. Note numbers and channels are ignored: each note-on is one
// strike at the default point. Throws UserError when the file cannot be read or is not a
// valid Standard MIDI file, or when a note-on lies beyond kMaxSeconds.
std::vector<Strike> readMidiStrikes(const std::filesystem::path& file);

// The same from bytes in memory or a stream; messages name the source as `name` (quoted).
std::vector<Strike> readMidiStrikes(const void* data, std::size_t size, const std::string& name);
std::vector<Strike> readMidiStrikes(juce::InputStream& stream, const std::string& name);

} // namespace snaresim::render
