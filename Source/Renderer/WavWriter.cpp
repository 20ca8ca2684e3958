#include "WavWriter.h"

#include "Errors.h"

#include <juce_audio_formats/juce_audio_formats.h>

#include <filesystem>
#include <string>

namespace snaresim::render
{
namespace
{

juce::File toJuceFile(const std::filesystem::path& path) { return juce::File(juce::String(std::filesystem::absolute(path).string())); }

} // namespace

WavWriter::WavWriter(const AtomicFile& target, double sampleRate_Hz, int numChannels) : file(target), channels(numChannels)
{
    auto output = std::make_unique<juce::FileOutputStream>(toJuceFile(file.temporary()));
    if (! output->openedOk())
        throw UserError("cannot write " + file.displayName() + ": " + output->getStatus().getErrorMessage().toStdString());

    // The temporary was created empty by AtomicFile; make sure (FileOutputStream appends).
    output->setPosition(0);
    output->truncate();

    juce::WavAudioFormat wav;
    writer.reset(wav.createWriterFor(output.get(), sampleRate_Hz, (unsigned) numChannels, 32, {}, 0));
    if (writer == nullptr)
        throw UserError("cannot write " + file.displayName() + ": the WAV format does not take " + std::to_string(numChannels) +
                        " channel(s) of 32-bit float");
    stream = output.release(); // now owned by the writer
    if (! stream->getStatus().wasOk())
        writeFailed();
}

WavWriter::~WavWriter() = default;

void WavWriter::writeFailed() const
{
    const auto reason = stream != nullptr && stream->getStatus().failed() ? stream->getStatus().getErrorMessage().toStdString()
                                                                          : std::string("write error");
    throw UserError("cannot write " + file.displayName() + ": " + reason);
}

void WavWriter::write(const float* const* data, int numSamples)
{
    if (numSamples <= 0)
        return;
    if (! writer->writeFromFloatArrays(data, channels, numSamples))
        writeFailed();
    written += numSamples;
}

void WavWriter::finish()
{
    // The WAV writer patches the header on flush() and again (identically) when deleted.
    const bool headerWritten = writer->flush();
    stream->flush();
    if (! headerWritten || stream->getStatus().failed())
        writeFailed();
    writer.reset();
    stream = nullptr;

    // Everything must be on disk: at least the sample data (the header comes on top).
    std::error_code ec;
    const auto size = std::filesystem::file_size(file.temporary(), ec);
    const auto dataBytes = (std::uintmax_t) written * (std::uintmax_t) channels * 4u;
    if (ec || size < dataBytes)
        throw UserError("cannot write " + file.displayName() + ": the file is incomplete" +
                        (ec ? " (" + ec.message() + ")" : std::string()));
}

} // namespace snaresim::render
