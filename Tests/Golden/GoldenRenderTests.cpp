// Golden renders: fixed scenarios played by the renderer (goldens.txt) and by the plug-in's
// processor, compared sample by sample with the references in this folder. They run on the
// path every x86-64 processor computes the same (CMakeLists.txt here: the baseline vector
// target and glibc's baseline maths, set by ctest), so a change of code that is not meant to
// change the sound must leave them identical, on any machine; the test states every
// difference in dB below the signal. A one-ulp change of a coefficient fails them (the last
// test here).
//
// Regenerate after an intended change of sound (and say so in the commit):
//   SNARESIM_UPDATE_GOLDENS=1 ctest --test-dir build -L golden

#include <catch2/catch.hpp>

#include "DrumConfig.h"
#include "GoldenSupport.h"
#include "Parameters.h"
#include "PluginProcessor.h"
#include "RendererTestSupport.h"
#include "Report.h"
#include "VectorTarget.h"

#include <juce_audio_formats/juce_audio_formats.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace rendertest;
using golden::compare;
using golden::Difference;
using golden::updating;

namespace
{
const fs::path goldenDir { SNARESIM_GOLDEN_DIR };

// The goldens are made and compared on the deterministic path only: ctest sets it for this
// executable (Tests/Golden/CMakeLists.txt); run by hand, it needs the same environment.
void requireDeterministicPath()
{
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    INFO("the golden tests run with SNARESIM_VECTOR_TARGET=baseline and GLIBC_TUNABLES=" SNARESIM_GOLDEN_TUNABLES
         " (ctest sets both); here the vector target is "
         << snaresim::vectorTargetName(snaresim::vectorTarget()) << " and GLIBC_TUNABLES is "
         << (tunables != nullptr ? tunables : "unset"));
    REQUIRE(snaresim::vectorTarget() == snaresim::VectorTarget::baseline);
    REQUIRE(tunables != nullptr);
    REQUIRE(std::string(tunables) == SNARESIM_GOLDEN_TUNABLES);
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

// A render that differs is printed (the test fails); one that is identical only while reporting.
void report(const std::string& name, const Difference& d)
{
    if (d.differing == 0)
        snaresim::test::report() << "golden " << name << ": identical\n";
    else
        std::cout << "golden " << name << ": " << d.differing << " samples differ, largest by " << d.maxAbs << ", difference "
                  << d.dbBelowSignal << " dB below the signal\n";
}

void writeFloatWav(const fs::path& file, const std::vector<float>& samples, double sampleRate)
{
    fs::remove(file);
    juce::WavAudioFormat format;
    std::unique_ptr<juce::OutputStream> stream = std::make_unique<juce::FileOutputStream>(juce::File(file.string()));
    std::unique_ptr<juce::AudioFormatWriter> writer(format.createWriterFor(stream.get(), sampleRate, 1, 32, {}, 0));
    REQUIRE(writer != nullptr);
    stream.release();
    const float* channels[] = { samples.data() };
    REQUIRE(writer->writeFromFloatArrays(channels, 1, (int) samples.size()));
}
} // namespace

TEST_CASE("the renderer's golden renders are unchanged", "[golden]")
{
    requireDeterministicPath();
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
    requireDeterministicPath();
    // 48 kHz, blocks of 64: a centre strike, an off-centre one, the damping raised while the
    // drum rings (the smoothing), a near-rim strike, a roll of three.
    constexpr double rate = 48000.0;
    constexpr int block = 64, length = 24000;
    SnareSimAudioProcessor proc;
    // The chosen Quality in real time too: the golden is the default drum's, however fast this
    // machine measures ("Lower Quality when slow" off).
    auto* keepUp = proc.getValueTreeState().getParameter("keep_up");
    keepUp->setValueNotifyingHost(0.0f);
    proc.setRateAndBufferSizeDetails(rate, block);
    proc.prepareToPlay(rate, block);

    const std::vector<std::pair<int, juce::MidiMessage>> notes {
        { 0, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 100) },     { 4800, juce::MidiMessage::noteOn(10, 40, (juce::uint8) 80) },
        { 9630, juce::MidiMessage::noteOn(10, 37, (juce::uint8) 110) },  { 14400, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) },
        { 16000, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) }, { 17601, juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127) },
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

TEST_CASE("a one-ulp change of one coefficient of the default drum fails the goldens", "[golden]")
{
    // The default golden's strike played in-process as the renderer plays it: the same bits as
    // the reference's mix channel (--mic all: top, bottom, room, mix); then the same with one
    // of the drum's coefficients moved by one unit in the last place, which must not pass.
    requireDeterministicPath();
    if (updating())
        return; // it reads the references being written
    const auto ref = readWav(goldenDir / "default-48k-all-mics.wav");
    REQUIRE(ref.opened);
    REQUIRE(ref.channels == 4);
    REQUIRE(ref.sampleRate == 48000.0);
    const auto& mix = ref.channelSamples[3];
    const auto playWith = [&](auto&& change) {
        auto config = snaresim::makeDrumConfig(snaresim::ParameterSet {}, 48000.0);
        change(config);
        return playInProcess(config, { { 0, 100 } }, (long long) mix.size()).mix;
    };

    const auto same = compare({ mix }, { playWith([](snaresim::DrumConfig&) {}) });
    report("default-48k-all-mics (mix, in-process)", same);
    REQUIRE(same.differing == 0);

    // One unit in the last place of a double, or of a float where the engine computes in float
    // (the default batter: its coefficients are floats, which a double's last bit of the
    // tension does not reach).
    const auto up = [](double& v) { v = std::nextafter(v, INFINITY); };
    const auto upFloat = [](double& v) { v = (double) std::nextafter((float) v, INFINITY); };
    SECTION("the snares' contact stiffness")
    {
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { up(c.snares.stiffness); }) });
        report("snare stiffness + 1 ulp", d);
        CHECK(d.differing > 0);
    }
    SECTION("the wires' tension")
    {
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { up(c.snares.tension_N); }) });
        report("wire tension + 1 ulp", d);
        CHECK(d.differing > 0);
    }
    SECTION("the batter's tension, by one unit of its float coefficients")
    {
        REQUIRE(snaresim::makeDrumConfig(snaresim::ParameterSet {}, 48000.0).batter.precision == snaresim::HeadPrecision::single_precision);
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { upFloat(c.batter.tension_N_per_m); }) });
        report("batter tension + 1 float ulp", d);
        CHECK(d.differing > 0);
    }
}
