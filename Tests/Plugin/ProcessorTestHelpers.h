#pragma once
// Helpers for the in-process processor tests: set parameters by the engine's table, render
// blocks with MIDI, wait for a background model.

#include "PluginProcessor.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "ModelExchange.h"

#include <juce_audio_processors/juce_audio_processors.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace snaresim::testing
{

inline juce::RangedAudioParameter& parameter(SnareSimAudioProcessor& proc, ParamId id)
{
    auto* p = proc.getValueTreeState().getParameter(juce::String(std::string(spec(id).key)));
    jassert(p != nullptr);
    return *p;
}

// Sets a parameter as a host would (normalised, through setValueNotifyingHost).
inline void set(SnareSimAudioProcessor& proc, ParamId id, double value)
{
    auto& p = parameter(proc, id);
    p.setValueNotifyingHost(p.convertTo0to1((float) value));
}

inline void prepare(juce::AudioProcessor& proc, double sampleRate, int blockSize)
{
    proc.setRateAndBufferSizeDetails(sampleRate, blockSize);
    proc.prepareToPlay(sampleRate, blockSize);
}

// Coarse grid and few wires: faster than real time, for tests where detail does not matter.
inline void fastSettings(SnareSimAudioProcessor& proc)
{
    set(proc, ParamId::bandwidth, 5093.8628);
    set(proc, ParamId::snareCount, 5.0);
}

struct Event
{
    int sample;
    juce::MidiMessage message;
};

struct Rendered
{
    std::vector<float> samples; // channel 0
    bool allFinite = true;
    bool anySubnormal = false;
    bool channelsIdentical = true;
    float peak = 0.0f;
    float maxStep = 0.0f;

    float peakFrom(int start) const
    {
        float p = 0.0f;
        for (size_t i = (size_t) std::max(0, start); i < samples.size(); ++i)
            p = std::max(p, std::abs(samples[i]));
        return p;
    }
};

// Renders numSamples in blocks of blockSize (the last may be shorter); beforeBlock(start) runs
// before each block. The buffer is filled with garbage first, to prove every sample is written.
inline Rendered render(juce::AudioProcessor& proc, int blockSize, int numSamples, std::vector<Event> events = {},
                       const std::function<void(int)>& beforeBlock = {}, float garbage = 123.0f)
{
    Rendered r;
    const int numChannels = juce::jmax(1, proc.getTotalNumInputChannels(), proc.getTotalNumOutputChannels());
    juce::AudioBuffer<float> buffer(numChannels, blockSize);
    juce::MidiBuffer midi;
    std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) { return a.sample < b.sample; });
    size_t next = 0;
    float previous = std::numeric_limits<float>::quiet_NaN(); // no step into the first sample

    for (int start = 0; start < numSamples; start += blockSize)
    {
        const int n = juce::jmin(blockSize, numSamples - start);
        if (beforeBlock)
            beforeBlock(start);

        buffer.setSize(numChannels, n, false, false, true);
        for (int ch = 0; ch < numChannels; ++ch)
            juce::FloatVectorOperations::fill(buffer.getWritePointer(ch), garbage, n);

        midi.clear();
        while (next < events.size() && events[next].sample < start + n)
        {
            midi.addEvent(events[next].message, juce::jmax(0, events[next].sample - start));
            ++next;
        }

        proc.processBlock(buffer, midi);

        for (int i = 0; i < n; ++i)
        {
            const float s = buffer.getSample(0, i);
            if (! std::isfinite(s))
                r.allFinite = false;
            else
            {
                r.peak = std::max(r.peak, std::abs(s));
                if (std::isfinite(previous))
                    r.maxStep = std::max(r.maxStep, std::abs(s - previous));
            }
            if (s != 0.0f && std::abs(s) < FLT_MIN)
                r.anySubnormal = true;
            for (int ch = 1; ch < numChannels; ++ch)
                if (buffer.getSample(ch, i) != s)
                    r.channelsIdentical = false;
            previous = s;
            r.samples.push_back(s);
        }
    }

    return r;
}

inline juce::MidiMessage note(int velocity, int key = 38) { return juce::MidiMessage::noteOn(10, key, (juce::uint8) velocity); }

// What the processor must output for these parameters at this rate: the engine's drum built
// from them (makeDrumConfig, as the model builder does), each note played before the step of
// its sample (Drum::playNote), the mix as float with |x| < 1e-30 written as 0 (the output
// guard), denormals flushed as in processBlock, behind the silence that brings its lag to the
// longest at this rate (the plug-in's one latency: DrumSession.h). Pass the processor's
// currentParameters(): the parameters hold floats.
struct EngineNote
{
    int sample, key, velocity;
};

// silentBefore: host samples of silence the drum plays first (a drum at rest that has played
// them stands at that phase of its simulated steps: HostRateInterpolator.h)
inline std::vector<float> engineRender(const snaresim::ParameterSet& params, double sampleRate, int numSamples,
                                       std::vector<EngineNote> notes, long silentBefore = 0)
{
    const juce::ScopedNoDenormals noDenormals;
    snaresim::Drum drum(snaresim::makeDrumConfig(params, sampleRate));
    for (long n = 0; n < silentBefore; ++n)
        drum.step();
    std::stable_sort(notes.begin(), notes.end(), [](const EngineNote& a, const EngineNote& b) { return a.sample < b.sample; });
    std::vector<float> out((size_t) std::clamp(snaresim::latencyPadFor(drum), 0, numSamples), 0.0f);
    numSamples -= (int) out.size();
    size_t next = 0;
    for (int n = 0; n < numSamples; ++n)
    {
        while (next < notes.size() && notes[next].sample <= n)
        {
            drum.playNote(notes[next].key, notes[next].velocity);
            ++next;
        }
        const float x = (float) drum.step();
        out.push_back(std::abs(x) >= 1.0e-30f ? x : 0.0f);
    }
    return out;
}

inline double rms(const std::vector<float>& x, size_t from = 0, size_t to = SIZE_MAX)
{
    to = std::min(to, x.size());
    double sum = 0.0;
    for (size_t i = from; i < to; ++i)
        sum += (double) x[i] * x[i];
    return to > from ? std::sqrt(sum / (double) (to - from)) : 0.0;
}

} // namespace snaresim::testing
