// Golden renders: fixed scenarios played by the renderer (goldens.txt) and by the plug-in's
// processor, compared sample by sample with the references in this folder. On the
// double-precision engine a change of code that is not meant to change the sound must leave
// them identical; the test states every difference in dB below the signal.
//
// Regenerate after an intended change of sound (and say so in the commit):
//   SNARESIM_UPDATE_GOLDENS=1 ctest --test-dir build -L golden

#include <catch2/catch.hpp>

#include "PluginProcessor.h"
#include "RendererTestSupport.h"

#include <juce_audio_formats/juce_audio_formats.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace rendertest;

namespace
{
const fs::path goldenDir { SNARESIM_GOLDEN_DIR };

bool updating()
{
    const char* v = std::getenv("SNARESIM_UPDATE_GOLDENS");
    return v != nullptr && std::string(v) == "1";
}

struct Golden
{
    std::string name;
    std::vector<std::string> args;
};

std::vector<Golden> goldenList()
{
    std::vector<Golden> list;
    std::ifstream in(goldenDir / "goldens.txt");
    std::string line;
    while (std::getline(in, line))
    {
        if (line.empty() || line[0] == '#')
            continue;
        const auto colon = line.find(':');
        REQUIRE(colon != std::string::npos);
        Golden g;
        g.name = line.substr(0, colon);
        std::istringstream words(line.substr(colon + 1));
        for (std::string w; words >> w;)
            g.args.push_back(w);
        list.push_back(std::move(g));
    }
    return list;
}

struct Difference
{
    long differing = 0;
    double maxAbs = 0.0;
    double dbBelowSignal = -INFINITY;   // of the RMS difference, relative to the reference's RMS
};

Difference compare(const std::vector<std::vector<float>>& reference, const std::vector<std::vector<float>>& now)
{
    Difference d;
    double signal = 0.0, error = 0.0;
    for (size_t ch = 0; ch < reference.size(); ++ch)
        for (size_t i = 0; i < reference[ch].size(); ++i)
        {
            const double r = reference[ch][i], x = now[ch][i];
            signal += r * r;
            error += (x - r) * (x - r);
            if (x != r)
                ++d.differing;
            d.maxAbs = std::max(d.maxAbs, std::abs(x - r));
        }
    if (error > 0.0)
        d.dbBelowSignal = 10.0 * std::log10(signal / error);
    return d;
}

void report(const std::string& name, const Difference& d)
{
    std::cout << "golden " << name << ": ";
    if (d.differing == 0)
        std::cout << "identical\n";
    else
        std::cout << d.differing << " samples differ, largest by " << d.maxAbs << ", difference " << d.dbBelowSignal
                  << " dB below the signal\n";
}

void writeFloatWav(const fs::path& file, const std::vector<float>& samples, double sampleRate)
{
    fs::remove(file);
    juce::WavAudioFormat format;
    std::unique_ptr<juce::OutputStream> stream = std::make_unique<juce::FileOutputStream>(juce::File(file.string()));
    std::unique_ptr<juce::AudioFormatWriter> writer(
        format.createWriterFor(stream.get(), sampleRate, 1, 32, {}, 0));
    REQUIRE(writer != nullptr);
    stream.release();
    const float* channels[] = { samples.data() };
    REQUIRE(writer->writeFromFloatArrays(channels, 1, (int) samples.size()));
}
} // namespace

TEST_CASE("the renderer's golden renders are unchanged", "[golden]")
{
    const auto list = goldenList();
    REQUIRE(list.size() >= 9);
    TempDir dir;

    for (const auto& g : list)
    {
        INFO("golden " << g.name);
        auto args = g.args;
        for (auto& a : args)
            if (a.size() > 4 && a.substr(a.size() - 4) == ".mid")
                a = (goldenDir / a).string();
        const auto output = dir.out() / (g.name + ".wav");
        args.insert(args.begin(), { "-o", output.string() });
        const auto run = runRenderer(args, dir.root());
        INFO(run.err);
        REQUIRE(run.exitCode == 0);

        const auto reference = goldenDir / (g.name + ".wav");
        if (updating())
        {
            fs::copy_file(output, reference, fs::copy_options::overwrite_existing);
            std::cout << "golden " << g.name << ": regenerated\n";
            continue;
        }

        const auto ref = readWav(reference);
        const auto now = readWav(output);
        REQUIRE(ref.opened);
        REQUIRE(now.opened);
        REQUIRE(now.sampleRate == ref.sampleRate);
        REQUIRE(now.channels == ref.channels);
        REQUIRE(now.length == ref.length);
        CHECK(peakOf(ref.samples) > 1.0e-3f);

        const auto d = compare(ref.channelSamples, now.channelSamples);
        report(g.name, d);
        CHECK(d.differing == 0);
    }
}

TEST_CASE("the plug-in's golden render is unchanged", "[golden]")
{
    // 48 kHz, blocks of 64: a centre strike, an off-centre one, the damping raised while the
    // drum rings (the smoothing), a near-rim strike, a roll of three.
    constexpr double rate = 48000.0;
    constexpr int block = 64, length = 24000;
    SnareSimAudioProcessor proc;
    proc.setRateAndBufferSizeDetails(rate, block);
    proc.prepareToPlay(rate, block);

    const std::vector<std::pair<int, juce::MidiMessage>> notes {
        { 0, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 100) },
        { 4800, juce::MidiMessage::noteOn(10, 40, (juce::uint8) 80) },
        { 9630, juce::MidiMessage::noteOn(10, 37, (juce::uint8) 110) },
        { 14400, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) },
        { 16000, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) },
        { 17601, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) },
    };

    std::vector<float> out;
    juce::AudioBuffer<float> buffer(2, block);
    juce::MidiBuffer midi;
    auto* damping = proc.getValueTreeState().getParameter("damping");
    for (int start = 0; start < length; start += block)
    {
        if (start == 7200)
            damping->setValueNotifyingHost(damping->convertTo0to1(60.0f));
        midi.clear();
        for (const auto& [at, message] : notes)
            if (at >= start && at < start + block)
                midi.addEvent(message, at - start);
        buffer.clear();
        proc.processBlock(buffer, midi);
        out.insert(out.end(), buffer.getReadPointer(0), buffer.getReadPointer(0) + block);
    }

    const auto reference = goldenDir / "plugin-48k.wav";
    if (updating())
    {
        writeFloatWav(reference, out, rate);
        std::cout << "golden plugin-48k: regenerated\n";
        return;
    }

    const auto ref = readWav(reference);
    REQUIRE(ref.opened);
    REQUIRE(ref.length == (long long) out.size());
    CHECK(peakOf(ref.samples) > 1.0e-3f);
    const auto d = compare({ ref.samples }, { out });
    report("plugin-48k", d);
    CHECK(d.differing == 0);
}
