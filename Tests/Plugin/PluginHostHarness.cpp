#include "PluginHostHarness.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace snaresim::testhost
{

LoadedPlugin loadPlugin(juce::AudioPluginFormat& format, const juce::String& fileOrIdentifier, double sampleRate, int blockSize)
{
    LoadedPlugin result;

    if (! format.fileMightContainThisPluginType(fileOrIdentifier))
    {
        result.error = format.getName() + " does not recognise " + fileOrIdentifier;
        return result;
    }

    juce::OwnedArray<juce::PluginDescription> types;
    format.findAllTypesForFile(types, fileOrIdentifier);

    if (types.size() != 1)
    {
        result.error = format.getName() + " found " + juce::String(types.size()) + " plug-ins in " + fileOrIdentifier + " (expected 1)";
        return result;
    }

    result.description = *types[0];
    result.instance = format.createInstanceFromDescription(result.description, sampleRate, blockSize, result.error);

    if (result.instance == nullptr && result.error.isEmpty())
        result.error = "createInstanceFromDescription failed without a message";

    return result;
}

RenderResult render(juce::AudioPluginInstance& plugin, const RenderRequest& request)
{
    RenderResult result;

    if (request.prepare)
    {
        plugin.enableAllBuses();
        plugin.setRateAndBufferSizeDetails(request.sampleRate, request.maxBlockSize);
        plugin.prepareToPlay(request.sampleRate, request.maxBlockSize);
    }

    result.numOutputChannels = plugin.getTotalNumOutputChannels();
    const int numChannels = juce::jmax(1, plugin.getTotalNumInputChannels(), plugin.getTotalNumOutputChannels());
    const int capacity = juce::jmax(1, request.maxBlockSize);

    // One allocation; every block is a view on it (any size up to the capacity).
    juce::AudioBuffer<float> storage(numChannels, capacity);
    juce::MidiBuffer midi;
    result.samples.reserve((size_t) juce::jmax(0, request.numSamples));

    auto events = request.midi;
    std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.sample < b.sample; });
    size_t nextEvent = 0;
    float previous = 0.0f;

    for (int start = 0, block = 0; start < request.numSamples; ++block)
    {
        int n = request.blockSize ? request.blockSize(block) : capacity;
        n = juce::jlimit(1, capacity, juce::jmin(n, request.numSamples - start));

        if (request.beforeBlock)
            request.beforeBlock(start);

        juce::AudioBuffer<float> buffer(storage.getArrayOfWritePointers(), numChannels, n);
        buffer.clear();

        midi.clear();
        while (nextEvent < events.size() && events[nextEvent].sample < start + n)
        {
            midi.addEvent(events[nextEvent].message, juce::jmax(0, events[nextEvent].sample - start));
            ++nextEvent;
        }

        plugin.processBlock(buffer, midi);

        for (int ch = 0; ch < result.numOutputChannels; ++ch)
        {
            const float* samples = buffer.getReadPointer(ch);

            for (int i = 0; i < n; ++i)
            {
                const float s = samples[i];

                if (! std::isfinite(s))
                    result.allFinite = false;
                else
                    result.peak = juce::jmax(result.peak, std::abs(s));

                if (s != 0.0f && std::abs(s) < FLT_MIN)
                    result.anySubnormal = true;

                if (ch > 0 && s != buffer.getSample(0, i))
                    result.channelsIdentical = false;
            }
        }

        const float* first = buffer.getReadPointer(0);
        for (int i = 0; i < n; ++i)
        {
            if (std::isfinite(first[i]) && std::isfinite(previous))
                result.maxStep = juce::jmax(result.maxStep, std::abs(first[i] - previous));
            previous = first[i];
            result.samples.push_back(first[i]);
        }

        result.numSamples += n;
        start += n;
    }

    if (request.release)
        plugin.releaseResources();

    return result;
}

RenderResult renderNote(juce::AudioPluginInstance& plugin, double sampleRate, int blockSize, int numSamples, int velocity)
{
    RenderRequest request;
    request.sampleRate = sampleRate;
    request.maxBlockSize = blockSize;
    request.numSamples = numSamples;
    request.midi.push_back({ 0, juce::MidiMessage::noteOn(10, 38, (juce::uint8) velocity) });
    return render(plugin, request);
}

juce::StringArray parameterNames(const juce::AudioPluginInstance& plugin)
{
    juce::StringArray names;

    for (const auto* p : plugin.getParameters())
        names.add(p->getName(1024));

    return names;
}

juce::AudioProcessorParameter* findParameter(juce::AudioPluginInstance& plugin, const juce::String& name)
{
    for (auto* p : plugin.getParameters())
        if (p->getName(1024) == name)
            return p;

    return nullptr;
}

} // namespace snaresim::testhost
