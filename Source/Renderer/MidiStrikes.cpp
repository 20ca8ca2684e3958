#include "MidiStrikes.h"

#include "Errors.h"

#include <juce_audio_basics/juce_audio_basics.h>

#include <algorithm>
#include <string>

namespace snaresim::render
{

std::vector<Strike> readMidiStrikes(const std::filesystem::path& file)
{
    const std::string name = inQuotes(file.string());
    std::error_code ec;

    if (std::filesystem::is_directory(file, ec))
        throw UserError("cannot read MIDI file " + name + ": it is a directory");

    const juce::File midiFile(juce::String(std::filesystem::absolute(file, ec).string()));
    juce::FileInputStream stream(midiFile);
    if (! stream.openedOk())
        throw UserError("cannot read MIDI file " + name + ": " + stream.getStatus().getErrorMessage().toStdString());

    return readMidiStrikes(stream, name);
}

std::vector<Strike> readMidiStrikes(const void* data, std::size_t size, const std::string& name)
{
    juce::MemoryInputStream stream(data, size, false);
    return readMidiStrikes(stream, name);
}

std::vector<Strike> readMidiStrikes(juce::InputStream& stream, const std::string& name)
{
    juce::MidiFile midi;
    if (! midi.readFrom(stream, false) || midi.getTimeFormat() == 0)
        throw UserError("cannot read MIDI file " + name + ": not a valid Standard MIDI file");

    midi.convertTimestampTicksToSeconds();

    std::vector<Strike> strikes;
    for (int t = 0; t < midi.getNumTracks(); ++t)
    {
        const auto* track = midi.getTrack(t);
        for (const auto* event : *track)
        {
            const auto& message = event->message;
            if (! message.isNoteOn()) // false for velocity 0 (a note-off)
                continue;

            const double time = message.getTimeStamp();
            if (! (time >= 0.0 && time <= kMaxSeconds))
                throw UserError("MIDI file " + name + ": a note-on at " + numberText(time) + " s is beyond the longest render (" +
                                std::to_string((int) kMaxSeconds) + " s)");

            strikes.push_back({ time, std::clamp((int) message.getVelocity(), 1, 127) });
        }
    }

    std::stable_sort(strikes.begin(), strikes.end(), [](const Strike& a, const Strike& b) { return a.time_s < b.time_s; });
    return strikes;
}

} // namespace snaresim::render
