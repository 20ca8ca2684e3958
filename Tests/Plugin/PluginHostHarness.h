#pragma once
// A minimal plug-in host for the tests: loads a plug-in through one of JUCE's hosting formats
// and renders a note through it. Built into snaresim_test_host_juce, the test's own JUCE
// library (with JUCE_PLUGINHOST_VST3 and JUCE_PLUGINHOST_LV2).

#include <juce_audio_processors/juce_audio_processors.h>

#include <memory>

namespace snaresim::testhost
{

struct LoadedPlugin
{
    std::unique_ptr<juce::AudioPluginInstance> instance;
    juce::PluginDescription description;
    juce::String error;     // why loading failed (instance == nullptr)
};

// Finds the (single) plug-in in fileOrIdentifier (a VST3 bundle path or an LV2 URI) and
// instantiates it.
LoadedPlugin loadPlugin (juce::AudioPluginFormat& format,
                         const juce::String& fileOrIdentifier,
                         double sampleRate,
                         int blockSize);

struct RenderResult
{
    int numOutputChannels = 0;
    int numSamples = 0;
    bool allFinite = true;
    float peak = 0.0f;
};

// Prepares the plug-in, sends a note-on (channel 10, key 38) at the start of the first block and
// renders numSamples samples in blocks of blockSize.
RenderResult renderNote (juce::AudioPluginInstance& plugin,
                         double sampleRate,
                         int blockSize,
                         int numSamples,
                         int velocity = 100);

// Names of all the plug-in's parameters, as the host sees them.
juce::StringArray parameterNames (const juce::AudioPluginInstance& plugin);

} // namespace snaresim::testhost
