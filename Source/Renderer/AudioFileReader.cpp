#include "AudioFileReader.h"

#include "Errors.h"

#include <FLAC/stream_decoder.h>
#include <juce_audio_formats/juce_audio_formats.h>

#include <array>
#include <fstream>
#include <memory>
#include <string>

namespace snaresim::render
{
namespace
{

[[noreturn]] void cannotRead(const std::filesystem::path& file, const std::string& why)
{
    throw UserError("cannot read " + file.string() + ": " + why);
}

// A WAV or AIFF file through JUCE's reader of that format.
MonoAudio readWithJuce(const std::filesystem::path& file, juce::AudioFormat& format, const std::string& name)
{
    std::unique_ptr<juce::AudioFormatReader> reader(format.createReaderFor(new juce::FileInputStream(juce::File(file.string())), true));
    if (reader == nullptr)
        cannotRead(file, "not a " + name + " file JUCE can read");
    if (reader->lengthInSamples <= 0 || reader->numChannels < 1)
        cannotRead(file, "no samples");
    if (reader->lengthInSamples > (juce::int64) 1 << 31)
        cannotRead(file, "longer than 2^31 samples");

    const int channels = (int) reader->numChannels, length = (int) reader->lengthInSamples;
    juce::AudioBuffer<float> buffer(channels, length);
    if (! reader->read(&buffer, 0, length, 0, true, true))
        cannotRead(file, "the samples cannot be read");
    MonoAudio audio;
    audio.sampleRate_Hz = reader->sampleRate;
    audio.channels = channels;
    audio.samples.assign((std::size_t) length, 0.0);
    for (int c = 0; c < channels; ++c)
        for (int i = 0; i < length; ++i)
            audio.samples[(std::size_t) i] += (double) buffer.getSample(c, i) / channels;
    return audio;
}

// libFLAC's stream decoder, its callbacks filling a MonoAudio.
struct FlacState
{
    MonoAudio audio;
    bool failed = false;
};

FLAC__StreamDecoderWriteStatus onFrame(const FLAC__StreamDecoder*, const FLAC__Frame* frame, const FLAC__int32* const buffer[], void* data)
{
    auto& state = *static_cast<FlacState*>(data);
    const unsigned channels = frame->header.channels;
    const double scale = 1.0 / (double) (1LL << (frame->header.bits_per_sample - 1)) / channels;
    state.audio.channels = (int) channels;
    state.audio.sampleRate_Hz = frame->header.sample_rate;
    for (unsigned i = 0; i < frame->header.blocksize; ++i)
    {
        double sum = 0.0;
        for (unsigned c = 0; c < channels; ++c)
            sum += (double) buffer[c][i];
        state.audio.samples.push_back(sum * scale);
    }
    return FLAC__STREAM_DECODER_WRITE_STATUS_CONTINUE;
}

void onMetadata(const FLAC__StreamDecoder*, const FLAC__StreamMetadata*, void*) {}

void onError(const FLAC__StreamDecoder*, FLAC__StreamDecoderErrorStatus, void* data) { static_cast<FlacState*>(data)->failed = true; }

MonoAudio readFlac(const std::filesystem::path& file)
{
    std::unique_ptr<FLAC__StreamDecoder, void (*)(FLAC__StreamDecoder*)> decoder(FLAC__stream_decoder_new(), FLAC__stream_decoder_delete);
    if (! decoder)
        cannotRead(file, "out of memory");
    FlacState state;
    if (FLAC__stream_decoder_init_file(decoder.get(), file.c_str(), onFrame, onMetadata, onError, &state) !=
        FLAC__STREAM_DECODER_INIT_STATUS_OK)
        cannotRead(file, "the FLAC decoder cannot open it");
    const bool decoded = FLAC__stream_decoder_process_until_end_of_stream(decoder.get()) != 0;
    FLAC__stream_decoder_finish(decoder.get());
    if (! decoded || state.failed)
        cannotRead(file, "not a valid FLAC stream");
    if (state.audio.samples.empty())
        cannotRead(file, "no samples");
    return std::move(state.audio);
}

} // namespace

MonoAudio readMonoAudio(const std::filesystem::path& file)
{
    std::error_code ec;
    if (! std::filesystem::is_regular_file(file, ec))
        cannotRead(file, std::filesystem::exists(file, ec) ? "not a regular file" : "no such file");
    std::array<char, 4> magic {};
    std::ifstream in(file, std::ios::binary);
    if (! in.read(magic.data(), (std::streamsize) magic.size()))
        cannotRead(file, "not a WAV, AIFF or FLAC file (too short)");
    const std::string head(magic.data(), magic.size());
    if (head == "fLaC")
        return readFlac(file);
    if (head == "RIFF" || head == "RF64")
    {
        juce::WavAudioFormat wav;
        return readWithJuce(file, wav, "WAV");
    }
    if (head == "FORM")
    {
        juce::AiffAudioFormat aiff;
        return readWithJuce(file, aiff, "AIFF");
    }
    cannotRead(file, "not a WAV, AIFF or FLAC file");
}

} // namespace snaresim::render
