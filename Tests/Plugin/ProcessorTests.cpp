// The SnareSim processor, linked from the plug-in's shared code (snaresim_juce).

#include <catch2/catch.hpp>

#include "PluginProcessor.h"
#include "PluginState.h"
#include "ProcessorTestHelpers.h"
#include "Report.h"
#include "ToggleParameter.h"

#include <juce_audio_processors/juce_audio_processors.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <vector>

// Defined in PluginProcessor.cpp; the plug-in wrappers call it to create the processor.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter();

namespace
{
struct RenderStats
{
    bool allFinite = true;
    float peak = 0.0f;
    float peakBeforeOnset = 0.0f; // largest |sample| before the note-on
    bool channelsIdentical = true;
    std::vector<float> samples; // channel 0
};

// Renders `totalSamples` samples in blocks of `blockSize`, with a note-on (velocity) at
// absolute sample `noteAt`.
RenderStats render(juce::AudioProcessor& proc, int blockSize, int totalSamples, int noteAt, int velocity = 100)
{
    RenderStats stats;
    const int numChannels = juce::jmax(proc.getTotalNumInputChannels(), proc.getTotalNumOutputChannels());
    juce::AudioBuffer<float> buffer(numChannels, blockSize);
    juce::MidiBuffer midi;

    for (int start = 0; start < totalSamples; start += blockSize)
    {
        const int n = juce::jmin(blockSize, totalSamples - start);
        buffer.setSize(numChannels, n, false, false, true);
        buffer.clear();
        // Fill with garbage to prove the processor writes every sample.
        for (int ch = 0; ch < numChannels; ++ch)
            juce::FloatVectorOperations::fill(buffer.getWritePointer(ch), 123.0f, n);

        midi.clear();
        if (noteAt >= start && noteAt < start + n)
            midi.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) velocity), noteAt - start);

        proc.processBlock(buffer, midi);

        for (int i = 0; i < n; ++i)
        {
            const float s = buffer.getSample(0, i);
            if (! std::isfinite(s))
                stats.allFinite = false;
            stats.peak = juce::jmax(stats.peak, std::abs(s));
            if (start + i < noteAt)
                stats.peakBeforeOnset = juce::jmax(stats.peakBeforeOnset, std::abs(s));
            stats.samples.push_back(s);
            for (int ch = 1; ch < numChannels; ++ch)
                if (buffer.getSample(ch, i) != s)
                    stats.channelsIdentical = false;
        }
    }

    return stats;
}

void prepare(juce::AudioProcessor& proc, double sampleRate, int blockSize)
{
    proc.setRateAndBufferSizeDetails(sampleRate, blockSize);
    proc.prepareToPlay(sampleRate, blockSize);
}
} // namespace

TEST_CASE("parameters mirror the engine's parameter table", "[processor]")
{
    SnareSimAudioProcessor proc;
    const auto& params = proc.getParameters();
    REQUIRE((size_t) params.size() == snaresim::kNumParameters);

    for (const auto& spec : snaresim::parameterSpecs())
    {
        const juce::String key(std::string(spec.key));
        INFO("parameter " << key);
        auto* p = proc.getValueTreeState().getParameter(key);
        REQUIRE(p != nullptr);
        CHECK(p->getName(100) == juce::String(std::string(spec.name)));
        CHECK(p->getLabel() == juce::String(std::string(spec.unit)));

        const auto& range = p->getNormalisableRange();
        CHECK(range.start == Approx((float) spec.minValue));
        CHECK(range.end == Approx((float) spec.maxValue));
        CHECK(p->convertFrom0to1(p->getDefaultValue()) == Approx((float) spec.defaultValue).margin(1e-9));
        CHECK(*proc.getValueTreeState().getRawParameterValue(key) == Approx((float) spec.defaultValue).margin(1e-9));

        switch (spec.kind)
        {
            case snaresim::ParamKind::toggle: CHECK(dynamic_cast<snaresim::plugin::ToggleParameter*>(p) != nullptr); break;
            case snaresim::ParamKind::integer: CHECK(dynamic_cast<juce::AudioParameterInt*>(p) != nullptr); break;
            case snaresim::ParamKind::choice: CHECK(dynamic_cast<juce::AudioParameterChoice*>(p) != nullptr); break;
            case snaresim::ParamKind::continuous:
            default: CHECK(dynamic_cast<juce::AudioParameterFloat*>(p) != nullptr); break;
        }

        if (spec.kind == snaresim::ParamKind::continuous && spec.scale == snaresim::ParamScale::logarithmic)
        {
            // Half way on the control is the geometric mean of the range.
            const auto mid = p->convertFrom0to1(0.5f);
            CHECK(mid == Approx(std::sqrt(spec.minValue * spec.maxValue)).epsilon(1e-4));
        }
    }
}

TEST_CASE("a note-on at 48 kHz gives finite, non-silent audio", "[processor]")
{
    SnareSimAudioProcessor proc;
    prepare(proc, 48000.0, 512);
    REQUIRE(proc.getDrum() != nullptr);
    CHECK_FALSE(proc.usedFallbackParameters());
    CHECK(proc.getTotalNumInputChannels() == 0);
    CHECK(proc.getTotalNumOutputChannels() == 2);

    const auto stats = render(proc, 512, 48000 / 2, 100);
    CHECK(stats.allFinite);
    CHECK(stats.peakBeforeOnset == 0.0f);
    CHECK(stats.peak > 1.0e-4f);
    CHECK(stats.peak < 100.0f);
    CHECK(stats.channelsIdentical);
    // Sample for sample the engine's drum with the note at sample 100.
    CHECK(stats.samples == snaresim::testing::engineRender(proc.currentParameters(), 48000.0, 48000 / 2, { { 100, 38, 100 } }));
}

TEST_CASE("one latency at a rate whatever Quality plays: a host's compensation lines every strike up", "[processor]")
{
    // The default's grids are simulated at 32 kHz and interpolated to the host's rate, about 2 ms
    // late; finer grids, simulated at the host's rate (or its half), wait as long behind a pure
    // delay (DrumSession.h). The reported latency is that lag: at 32 kHz the default plays
    // uninterpolated, and the host's samples that fall on its steps, the latency later, hold its
    // samples up to the interpolation's band (-22 dB; three host samples off, -4 to -8 dB); the finer drum's
    // output is the engine's, the latency later.
    struct Played
    {
        int latency;
        std::vector<float> samples; // from the note on
        snaresim::ParameterSet params;
    };
    auto play = [](double rate, double bandwidth) {
        SnareSimAudioProcessor proc;
        snaresim::testing::set(proc, snaresim::ParamId::bandwidth, bandwidth);
        prepare(proc, rate, 256);
        REQUIRE(proc.getDrum() != nullptr);
        const int noteAt = (int) (0.01 * rate);
        const auto stats = render(proc, 256, (int) (0.08 * rate), noteAt);
        REQUIRE(stats.peak > 0.0f);
        return Played { proc.getLatencySamples(), std::vector<float>(stats.samples.begin() + noteAt, stats.samples.end()),
                        proc.currentParameters() };
    };
    const auto simulated = play(32000.0, 7839.5127);
    CHECK(simulated.latency == 0); // every grid is simulated at 32 kHz
    for (const auto& [hostRate, stepPerSample] : std::vector<std::pair<double, size_t>> { { 48000.0, 2 }, { 96000.0, 1 } })
    {
        const double rate = hostRate;
        const size_t step = stepPerSample;
        const auto reduced = play(rate, 7839.5127), finer = play(rate, 8300.0);
        const int latency = reduced.latency;
        CHECK(latency == std::lround(snaresim::longestLatencySamples(rate)));
        CHECK(latency > 0.0019 * rate);
        CHECK(finer.latency == latency);

        auto errorAt = [&](int shift) { // dB of the difference, the host's samples `shift` later
            double error = 0.0, signal = 0.0;
            for (size_t k = 0; k * 3 + (size_t) (latency + shift) < reduced.samples.size() && k * step < simulated.samples.size(); ++k)
            {
                const double want = simulated.samples[k * step], got = reduced.samples[k * 3 + (size_t) (latency + shift)];
                error += (got - want) * (got - want);
                signal += want * want;
            }
            return 10.0 * std::log10(error / signal);
        };
        INFO(rate << " Hz, latency " << latency << ": " << errorAt(0) << " dB, a step off " << errorAt(-3) << " / " << errorAt(3) << " dB");
        CHECK(errorAt(0) < -15.0);
        CHECK(errorAt(-3) > -10.0);
        CHECK(errorAt(3) > -10.0);

        // the finer drum: silence for the latency, then the engine's drum
        snaresim::Drum drum(snaresim::makeDrumConfig(finer.params, rate));
        REQUIRE(drum.latencySamples() < latency);
        drum.playNote(38, 100);
        const int pad = latency - (int) std::lround(drum.latencySamples()); // the pad, from the latency reported
        bool same = true;
        for (size_t n = 0; n < finer.samples.size(); ++n)
        {
            const float want = n < (size_t) pad ? 0.0f : (float) drum.step();
            same = same && finer.samples[n] == (std::abs(want) >= 1.0e-30f ? want : 0.0f);
        }
        CHECK(same);
    }
    // at 44.1 kHz the lag is 85.7 samples (33.075 kHz, interpolated by 4 / 3)
    CHECK(play(44100.0, 7839.5127).latency == 86);
    CHECK(play(44100.0, 8300.0).latency == 86);
}

TEST_CASE("blocks larger than announced are rendered in chunks", "[processor]")
{
    SnareSimAudioProcessor proc;
    prepare(proc, 48000.0, 64);

    const auto stats = render(proc, 4000, 12000, 2500);
    CHECK(stats.allFinite);
    CHECK(stats.peakBeforeOnset == 0.0f);
    CHECK(stats.peak > 1.0e-4f);
    CHECK(stats.channelsIdentical);
    CHECK(stats.samples == snaresim::testing::engineRender(proc.currentParameters(), 48000.0, 12000, { { 2500, 38, 100 } }));
}

TEST_CASE("mono output and 44.1 kHz are supported", "[processor]")
{
    SnareSimAudioProcessor proc;

    juce::AudioProcessor::BusesLayout mono;
    mono.outputBuses.add(juce::AudioChannelSet::mono());
    REQUIRE(proc.setBusesLayout(mono));

    juce::AudioProcessor::BusesLayout withInput = mono;
    withInput.inputBuses.add(juce::AudioChannelSet::stereo());
    CHECK_FALSE(proc.checkBusesLayoutSupported(withInput));

    prepare(proc, 44100.0, 256);
    CHECK(proc.getTotalNumOutputChannels() == 1);
    const auto stats = render(proc, 256, 22050, 0, 127);
    CHECK(stats.allFinite);
    CHECK(stats.peak > 1.0e-4f);
    CHECK(stats.samples == snaresim::testing::engineRender(proc.currentParameters(), 44100.0, 22050, { { 0, 38, 127 } }));
}

TEST_CASE("louder MIDI velocity strikes harder", "[processor]")
{
    auto peakFor = [](int velocity) {
        SnareSimAudioProcessor proc;
        prepare(proc, 48000.0, 480);
        return render(proc, 480, 9600, 0, velocity).peak;
    };

    // The documented velocity curve, speed = v_max 10^(-1.6 (127 - v) / 126), makes velocity 127
    // strike 22.8 times as fast as velocity 20. The heads respond linearly; the Hertz contact,
    // stiffer the harder it is struck, shortens the pulse: the microphones hear pressure (the
    // heads' acceleration), whose peak grows with the contact force, between the speed and its
    // 6/5 power (the Hertz force's growth on a rigid body).
    const double speedRatio = std::pow(10.0, 1.6 * (127 - 20) / 126.0);
    const float loud = peakFor(127), soft = peakFor(20);
    INFO("peaks " << loud << " and " << soft << ", speed ratio " << speedRatio);
    CHECK(loud > soft);
    CHECK(loud / soft > 0.95 * speedRatio);
    CHECK(loud / soft < std::pow(speedRatio, 1.2));
}

TEST_CASE("processing before prepareToPlay outputs silence", "[processor]")
{
    SnareSimAudioProcessor proc;
    proc.setRateAndBufferSizeDetails(48000.0, 128);
    const auto stats = render(proc, 128, 512, 10);
    CHECK(stats.allFinite);
    CHECK(stats.peak == 0.0f);
}

TEST_CASE("state save and restore round-trips every parameter exactly", "[processor][state]")
{
    SnareSimAudioProcessor proc;
    auto& params = proc.getParameters();

    // A non-default value for every parameter, set as a host would (normalised), on a legal
    // value of the parameter (whole numbers for toggles, choices and integers).
    auto& tree = proc.getValueTreeState();
    std::vector<float> saved, savedRaw;
    for (int i = 0; i < params.size(); ++i)
    {
        auto* p = dynamic_cast<juce::RangedAudioParameter*>(params[i]);
        REQUIRE(p != nullptr);
        auto target = p->convertFrom0to1(std::fmod(0.137f + 0.161f * (float) i, 1.0f));
        if (target == p->convertFrom0to1(p->getDefaultValue()))
            target = p->convertFrom0to1(p->getDefaultValue() < 0.5f ? 1.0f : 0.0f);
        p->setValueNotifyingHost(p->convertTo0to1(target));
        saved.push_back(p->getValue());
        savedRaw.push_back(tree.getRawParameterValue(p->paramID)->load());
    }

    juce::MemoryBlock state;
    proc.getStateInformation(state);
    REQUIRE(state.getSize() > 0);

    // The saved XML carries a version attribute.
    const auto xml = juce::AudioProcessor::getXmlFromBinary(state.getData(), (int) state.getSize());
    REQUIRE(xml != nullptr);
    CHECK(xml->getIntAttribute(snaresim::plugin::PluginState::versionAttribute, -1) == snaresim::plugin::PluginState::version);

    // Move everything away, then restore into the same and into a fresh processor.
    for (auto* p : params)
        p->setValueNotifyingHost(p->getDefaultValue());

    SnareSimAudioProcessor fresh;
    for (auto* target : { &proc, &fresh })
    {
        target->setStateInformation(state.getData(), (int) state.getSize());
        const auto& restored = target->getParameters();
        REQUIRE(restored.size() == params.size());

        for (int i = 0; i < restored.size(); ++i)
        {
            auto* p = dynamic_cast<juce::RangedAudioParameter*>(restored[i]);
            REQUIRE(p != nullptr);
            INFO("parameter " << p->paramID);
            CHECK(p->getValue() == saved[(size_t) i]);
            CHECK(target->getValueTreeState().getRawParameterValue(p->paramID)->load() == savedRaw[(size_t) i]);
            CHECK(savedRaw[(size_t) i] != p->convertFrom0to1(p->getDefaultValue()));
        }
    }

    // The engine sees the restored values.
    const auto engineParams = fresh.currentParameters();
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const juce::String key(std::string(spec.key));
        INFO("parameter " << key);
        const auto* raw = fresh.getValueTreeState().getRawParameterValue(key);
        REQUIRE(raw != nullptr);
        CHECK((float) engineParams.get(spec.id) == raw->load());
    }

    // The restored parameters play (the grid ones from the next prepareToPlay or model build):
    // the processor sounds as the engine's drum built from them.
    prepare(fresh, 48000.0, 256);
    CHECK(fresh.getDrum() != nullptr);
    REQUIRE_FALSE(fresh.usedFallbackParameters());
    const auto stats = render(fresh, 256, 4800, 0);
    CHECK(stats.allFinite);
    CHECK(stats.peak > 0.0f);
    CHECK(stats.samples == snaresim::testing::engineRender(fresh.currentParameters(), 48000.0, 4800, { { 0, 38, 100 } }));
}

TEST_CASE("a state restores every parameter exactly, whatever values a host set before", "[processor][state]")
{
    // As a validating host does it: random normalised values (off the steps of toggles,
    // choices and integers too), save, other random values, restore, compare.
    SnareSimAudioProcessor proc;
    auto& params = proc.getParameters();
    juce::Random random(20261123);
    int compared = 0;
    float worstError = 0.0f;

    for (int round = 0; round < 100; ++round)
    {
        for (auto* p : params)
            p->setValueNotifyingHost(random.nextFloat());

        std::vector<float> original;
        for (auto* p : params)
            original.push_back(p->getValue());

        juce::MemoryBlock state;
        proc.getStateInformation(state);

        for (auto* p : params)
            p->setValueNotifyingHost(random.nextFloat());

        proc.setStateInformation(state.getData(), (int) state.getSize());

        for (int i = 0; i < params.size(); ++i)
        {
            // Discrete parameters exactly; continuous ones to float precision (the state holds
            // the value in the parameter's units, the host reads it normalised).
            INFO("round " << round << ", parameter " << params[i]->getName(64));
            const float error = std::abs(params[i]->getValue() - original[(size_t) i]);
            if (params[i]->isDiscrete())
                CHECK(error == 0.0f);
            else
                CHECK(error <= 1.0e-6f);
            worstError = std::max(worstError, error);
            ++compared;
        }
    }

    snaresim::test::report() << "state round trips over random host values: 100 rounds, " << compared
                             << " values compared, largest normalised difference " << worstError << "\n";
}

TEST_CASE("a toggle holds 0 or 1 whatever normalised value a host sends", "[processor][state]")
{
    SnareSimAudioProcessor proc;
    auto& p = *proc.getValueTreeState().getParameter("snares_engaged");

    for (const float sent : { 0.655505f, 0.5f, 1.0f, 0.99f })
    {
        p.setValueNotifyingHost(sent);
        CHECK(p.getValue() == 1.0f);
        CHECK(proc.currentParameters().get(snaresim::ParamId::snaresEngaged) == 1.0);
    }
    for (const float sent : { 0.4999f, 0.0f, 0.2f, std::numeric_limits<float>::quiet_NaN() })
    {
        p.setValueNotifyingHost(sent);
        CHECK(p.getValue() == 0.0f);
        CHECK(proc.currentParameters().get(snaresim::ParamId::snaresEngaged) == 0.0);
    }
    CHECK(p.getText(0.7f, 0) == "On");
    CHECK(p.getValueForText("off") == 0.0f);
    CHECK(p.getNumSteps() == 2);
    CHECK(p.isBoolean());
}

TEST_CASE("garbage or foreign state is ignored", "[processor][state]")
{
    SnareSimAudioProcessor proc;
    auto* p = proc.getParameters()[0];
    p->setValueNotifyingHost(0.25f);
    const float before = p->getValue();

    const char garbage[] = "definitely not a state";
    proc.setStateInformation(garbage, (int) sizeof(garbage));
    CHECK(p->getValue() == before);

    juce::MemoryBlock foreign;
    juce::AudioProcessor::copyXmlToBinary(juce::XmlElement("SomethingElse"), foreign);
    proc.setStateInformation(foreign.getData(), (int) foreign.getSize());
    CHECK(p->getValue() == before);

    proc.setStateInformation(nullptr, 0);
    CHECK(p->getValue() == before);
}

TEST_CASE("the plug-in factory creates the processor, which has an editor", "[processor]")
{
    std::unique_ptr<juce::AudioProcessor> proc(createPluginFilter());
    REQUIRE(proc != nullptr);
    CHECK(proc->getName() == "SnareSim");
    CHECK(proc->acceptsMidi());
    CHECK_FALSE(proc->producesMidi());
    CHECK(proc->hasEditor());
}

TEST_CASE("a sample rate the model cannot take never crashes", "[processor]")
{
    for (const double rate : { 0.0, 1000.0, 8000.0 })
    {
        INFO("sample rate " << rate);
        SnareSimAudioProcessor proc;
        REQUIRE_NOTHROW(prepare(proc, rate, 256));
        // No drum, not even the default one: at 8 kHz and below the default grid (Quality 2)
        // would have fewer than 4 nodes per radius. So the note plays nothing.
        CHECK(proc.getDrum() == nullptr);
        CHECK_THROWS_AS(snaresim::makeDrumConfig(snaresim::ParameterSet {}, rate), std::invalid_argument);
        const auto stats = render(proc, 256, 2048, 10);
        CHECK(stats.allFinite);
        CHECK(stats.peakBeforeOnset == 0.0f);
        CHECK(stats.peak == 0.0f);
    }
}
