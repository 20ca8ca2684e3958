// The plug-in's golden render: the processor plays a fixed scenario through processBlock, compared
// sample by sample with plugin-48k.wav on the deterministic path (CMakeLists.txt here), as the
// renderer's goldens are (GoldenRenderTests.cpp).
//
// Regenerate after an intended change of sound (and say so in the commit):
//   SNARESIM_UPDATE_GOLDENS=1 ctest --test-dir build -L golden

#include "GoldenSupport.h"
#include "PluginProcessor.h"
#include "RendererTestSupport.h"

#include <catch2/catch.hpp>

#include <iostream>
#include <utility>
#include <vector>

using namespace rendertest;
using golden::compare;
using golden::goldenDir;
using golden::report;
using golden::requireDeterministicPath;
using golden::updating;
using golden::writeFloatWav;

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
