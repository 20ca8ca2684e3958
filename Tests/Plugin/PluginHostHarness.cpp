#include "PluginHostHarness.h"

#include <cmath>

namespace snaresim::testhost
{

LoadedPlugin loadPlugin (juce::AudioPluginFormat& format,
                         const juce::String& fileOrIdentifier,
                         double sampleRate,
                         int blockSize)
{
    LoadedPlugin result;

    if (! format.fileMightContainThisPluginType (fileOrIdentifier))
    {
        result.error = format.getName() + " does not recognise " + fileOrIdentifier;
        return result;
    }

    juce::OwnedArray<juce::PluginDescription> types;
    format.findAllTypesForFile (types, fileOrIdentifier);

    if (types.size() != 1)
    {
        result.error = format.getName() + " found " + juce::String (types.size())
                     + " plug-ins in " + fileOrIdentifier + " (expected 1)";
        return result;
    }

    result.description = *types[0];
    result.instance = format.createInstanceFromDescription (result.description, sampleRate, blockSize, result.error);

    if (result.instance == nullptr && result.error.isEmpty())
        result.error = "createInstanceFromDescription failed without a message";

    return result;
}

RenderResult renderNote (juce::AudioPluginInstance& plugin,
                         double sampleRate,
                         int blockSize,
                         int numSamples,
                         int velocity)
{
    RenderResult result;

    plugin.enableAllBuses();
    plugin.setRateAndBufferSizeDetails (sampleRate, blockSize);
    plugin.prepareToPlay (sampleRate, blockSize);

    result.numOutputChannels = plugin.getTotalNumOutputChannels();
    const int numChannels = juce::jmax (plugin.getTotalNumInputChannels(), plugin.getTotalNumOutputChannels());

    juce::AudioBuffer<float> buffer (numChannels, blockSize);
    juce::MidiBuffer midi;

    for (int start = 0; start < numSamples; start += blockSize)
    {
        buffer.clear();
        midi.clear();

        if (start == 0)
            midi.addEvent (juce::MidiMessage::noteOn (10, 38, (juce::uint8) velocity), 0);

        plugin.processBlock (buffer, midi);

        for (int ch = 0; ch < plugin.getTotalNumOutputChannels(); ++ch)
        {
            const float* samples = buffer.getReadPointer (ch);

            for (int i = 0; i < blockSize; ++i)
            {
                if (! std::isfinite (samples[i]))
                    result.allFinite = false;
                else
                    result.peak = juce::jmax (result.peak, std::abs (samples[i]));
            }
        }

        result.numSamples += blockSize;
    }

    plugin.releaseResources();
    return result;
}

juce::StringArray parameterNames (const juce::AudioPluginInstance& plugin)
{
    juce::StringArray names;

    for (const auto* p : plugin.getParameters())
        names.add (p->getName (1024));

    return names;
}

} // namespace snaresim::testhost
