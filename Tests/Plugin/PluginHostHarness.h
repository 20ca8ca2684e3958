#pragma once
// A minimal plug-in host for the tests: loads a plug-in through one of JUCE's hosting formats
// and renders MIDI through it. Built into snaresim_test_host_juce, the test's own JUCE library
// (with JUCE_PLUGINHOST_VST3 and JUCE_PLUGINHOST_LV2).

#include <juce_audio_processors/juce_audio_processors.h>

#include <functional>
#include <memory>
#include <vector>

namespace snaresim::testhost
{

struct LoadedPlugin
{
    std::unique_ptr<juce::AudioPluginInstance> instance;
    juce::PluginDescription description;
    juce::String error; // why loading failed (instance == nullptr)
};

// Finds the (single) plug-in in fileOrIdentifier (a VST3 bundle path or an LV2 URI) and
// instantiates it.
LoadedPlugin loadPlugin(juce::AudioPluginFormat& format, const juce::String& fileOrIdentifier, double sampleRate, int blockSize);

struct RenderResult
{
    int numOutputChannels = 0;
    int numSamples = 0;
    bool allFinite = true;
    bool anySubnormal = false; // a non-zero |sample| below FLT_MIN
    bool channelsIdentical = true;
    float peak = 0.0f;
    float maxStep = 0.0f;       // largest |y[n] - y[n-1]| of channel 0
    std::vector<float> samples; // channel 0
};

// Prepares the plug-in, sends a note-on (channel 10, key 38) at the start of the first block and
// renders numSamples samples in blocks of blockSize.
RenderResult renderNote(juce::AudioPluginInstance& plugin, double sampleRate, int blockSize, int numSamples, int velocity = 100);

struct TimedMidi
{
    int sample = 0; // absolute sample position
    juce::MidiMessage message;
};

struct RenderRequest
{
    double sampleRate = 48000.0;
    int maxBlockSize = 512; // announced in prepareToPlay
    int numSamples = 0;
    std::vector<TimedMidi> midi;

    // The size of block number i (1 .. maxBlockSize); empty: always maxBlockSize.
    std::function<int(int blockIndex)> blockSize;
    // Called before each block with its first sample (for parameter changes).
    std::function<void(int startSample)> beforeBlock;

    bool prepare = true; // call prepareToPlay first
    bool release = true; // and releaseResources at the end
};

// Renders through plugin.processBlock on the calling thread; every channel is checked.
RenderResult render(juce::AudioPluginInstance& plugin, const RenderRequest& request);

// Names of all the plug-in's parameters, as the host sees them.
juce::StringArray parameterNames(const juce::AudioPluginInstance& plugin);

// The plug-in's parameter with this name (nullptr when there is none).
juce::AudioProcessorParameter* findParameter(juce::AudioPluginInstance& plugin, const juce::String& name);

} // namespace snaresim::testhost
