#pragma once
// Streaming a 32-bit IEEE-float WAV file (juce::WavAudioFormat) into an AtomicFile's
// temporary file. The caller commits the AtomicFile after finish().

#include "AtomicFile.h"

#include <cstdint>
#include <memory>

namespace juce
{
class AudioFormatWriter;
class FileOutputStream;
} // namespace juce

namespace snaresim::render
{

class WavWriter
{
public:
    // Opens file.temporary() and writes the header. Throws UserError.
    WavWriter(const AtomicFile& file, double sampleRate_Hz, int numChannels);
    ~WavWriter();

    WavWriter(const WavWriter&) = delete;
    WavWriter& operator=(const WavWriter&) = delete;

    // One pointer per channel, numSamples each. Throws UserError on a write failure.
    void write(const float* const* channels, int numSamples);

    // Completes the header, flushes and closes; checks that everything reached the file.
    // Throws UserError.
    void finish();

    std::int64_t samplesWritten() const { return written; }

private:
    [[noreturn]] void writeFailed() const;

    const AtomicFile& file;
    int channels;
    juce::FileOutputStream* stream = nullptr; // owned by writer
    std::unique_ptr<juce::AudioFormatWriter> writer;
    std::int64_t written = 0;
};

} // namespace snaresim::render
