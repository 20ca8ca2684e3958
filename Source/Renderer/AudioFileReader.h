#pragma once
// Reading a recording for --match and --distance: a WAV or AIFF file (JUCE's readers: integer
// or float samples, any rate) or a FLAC file (the system's libFLAC), its channels averaged to one.

#include <filesystem>
#include <vector>

namespace snaresim::render
{

struct MonoAudio
{
    std::vector<double> samples; // the channels' mean, full scale 1
    double sampleRate_Hz = 0.0;
    int channels = 0;
};

// Throws UserError ("cannot read FILE: ...") when the file is missing, unreadable, not a WAV,
// AIFF or FLAC file, or holds no samples.
MonoAudio readMonoAudio(const std::filesystem::path& file);

} // namespace snaresim::render
