#include "PluginProcessor.h"

#include "Drum.h"
#include "DrumConfig.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

namespace
{
const juce::Identifier stateTreeType { "SnareSimState" };

juce::NormalisableRange<float> makeRange (const snaresim::ParameterSpec& spec)
{
    const auto lo = (float) spec.minValue;
    const auto hi = (float) spec.maxValue;

    if (spec.scale == snaresim::ParamScale::logarithmic && spec.minValue > 0.0 && spec.maxValue > spec.minValue)
    {
        const double logRatio = std::log (spec.maxValue / spec.minValue);
        const double minValue = spec.minValue;

        return { lo, hi,
                 [minValue, logRatio] (float start, float end, float proportion)
                 {
                     const auto v = (float) (minValue * std::exp ((double) proportion * logRatio));
                     return juce::jlimit (start, end, v);
                 },
                 [minValue, logRatio] (float, float, float value)
                 {
                     const auto p = std::log ((double) value / minValue) / logRatio;
                     return (float) juce::jlimit (0.0, 1.0, p);
                 },
                 [] (float start, float end, float value) { return juce::jlimit (start, end, value); } };
    }

    return { lo, hi };
}

juce::String unitSuffix (const snaresim::ParameterSpec& spec)
{
    return spec.unit.empty() ? juce::String() : " " + juce::String (std::string (spec.unit));
}
} // namespace

//==============================================================================
SnareSimAudioProcessor::SnareSimAudioProcessor()
    : AudioProcessor (BusesProperties().withOutput ("Output", juce::AudioChannelSet::stereo(), true)),
      apvts (*this, nullptr, stateTreeType, createParameterLayout())
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        auto* raw = apvts.getRawParameterValue (juce::String (std::string (spec.key)));
        jassert (raw != nullptr);
        rawParameters[static_cast<std::size_t> (spec.id)] = raw;
    }
}

SnareSimAudioProcessor::~SnareSimAudioProcessor() = default;

juce::AudioProcessorValueTreeState::ParameterLayout SnareSimAudioProcessor::createParameterLayout()
{
    juce::AudioProcessorValueTreeState::ParameterLayout layout;

    for (const auto& spec : snaresim::parameterSpecs())
    {
        const juce::ParameterID id { juce::String (std::string (spec.key)), 1 };
        const juce::String name (std::string (spec.name));
        const juce::String unit (std::string (spec.unit));

        switch (spec.kind)
        {
            case snaresim::ParamKind::toggle:
                layout.add (std::make_unique<juce::AudioParameterBool> (
                    id, name, spec.defaultValue >= 0.5,
                    juce::AudioParameterBoolAttributes().withLabel (unit)));
                break;

            case snaresim::ParamKind::choice:
            {
                auto choices = juce::StringArray::fromTokens (juce::String (std::string (spec.choices)), "|", "");
                const int numChoices = (int) std::lround (spec.maxValue - spec.minValue) + 1;

                // The engine reads the choice index (0 .. n-1); name any choice the table leaves unnamed.
                while (choices.size() < numChoices)
                    choices.add (juce::String (choices.size()));

                layout.add (std::make_unique<juce::AudioParameterChoice> (
                    id, name, choices, (int) std::lround (spec.defaultValue),
                    juce::AudioParameterChoiceAttributes().withLabel (unit)));
                break;
            }

            case snaresim::ParamKind::integer:
                layout.add (std::make_unique<juce::AudioParameterInt> (
                    id, name, (int) std::lround (spec.minValue), (int) std::lround (spec.maxValue),
                    (int) std::lround (spec.defaultValue),
                    juce::AudioParameterIntAttributes().withLabel (unit)));
                break;

            case snaresim::ParamKind::continuous:
            default:
            {
                const auto suffix = unitSuffix (spec);
                auto attributes = juce::AudioParameterFloatAttributes()
                                      .withLabel (unit)
                                      .withStringFromValueFunction ([suffix] (float value, int maxLength)
                                                                    {
                                                                        auto text = juce::String (value, 4) + suffix;
                                                                        return maxLength > 0 ? text.substring (0, maxLength) : text;
                                                                    });

                layout.add (std::make_unique<juce::AudioParameterFloat> (
                    id, name, makeRange (spec), (float) spec.defaultValue, attributes));
                break;
            }
        }
    }

    return layout;
}

const juce::String SnareSimAudioProcessor::getName() const
{
    return JucePlugin_Name;
}

snaresim::ParameterSet SnareSimAudioProcessor::currentParameters() const
{
    snaresim::ParameterSet params;

    for (const auto& spec : snaresim::parameterSpecs())
        if (const auto* raw = rawParameters[static_cast<std::size_t> (spec.id)])
            params.setClamped (spec.id, (double) raw->load());

    return params;
}

//==============================================================================
void SnareSimAudioProcessor::prepareToPlay (double sampleRate, int maximumExpectedSamplesPerBlock)
{
    // Parameter changes take effect here, in this version: the drum is rebuilt from the current
    // parameter values each time the host prepares the processor.
    std::unique_ptr<snaresim::Drum> newDrum;
    bool fallback = false;

    if (sampleRate > 0.0 && std::isfinite (sampleRate))
    {
        try
        {
            newDrum = std::make_unique<snaresim::Drum> (snaresim::makeDrumConfig (currentParameters(), sampleRate));
        }
        catch (const std::exception& e)
        {
            DBG ("SnareSim: cannot build the drum from the parameters (" << e.what() << "); using the defaults");
            fallback = true;
        }

        if (newDrum == nullptr)
        {
            try
            {
                newDrum = std::make_unique<snaresim::Drum> (snaresim::makeDrumConfig (snaresim::ParameterSet {}, sampleRate));
            }
            catch (const std::exception& e)
            {
                // Nothing can be simulated at this rate: the processor outputs silence.
                juce::ignoreUnused (e);
                DBG ("SnareSim: cannot build the default drum at " << sampleRate << " Hz: " << e.what());
                newDrum.reset();
            }
        }
    }

    std::vector<float> newScratch ((size_t) juce::jmax (maximumExpectedSamplesPerBlock, 32), 0.0f);
    const double newStrikeSpeedMax = newDrum != nullptr ? newDrum->config().strikeSpeedMax_m_per_s : 6.0;

    {
        const juce::ScopedLock sl (getCallbackLock());
        std::swap (drum, newDrum);
        std::swap (scratch, newScratch);
        strikeSpeedMax_m_per_s = newStrikeSpeedMax;
        fellBackToDefaults = fallback;
    }
    // The previous drum and scratch buffer are freed here, outside the lock.
}

void SnareSimAudioProcessor::releaseResources()
{
    if (drum != nullptr)
        drum->reset();
}

bool SnareSimAudioProcessor::isBusesLayoutSupported (const BusesLayout& layouts) const
{
    // No audio input; mono or stereo output.
    if (layouts.getMainInputChannelSet() != juce::AudioChannelSet::disabled())
        return false;

    const auto out = layouts.getMainOutputChannelSet();
    return out == juce::AudioChannelSet::mono() || out == juce::AudioChannelSet::stereo();
}

//==============================================================================
void SnareSimAudioProcessor::handleMidiMessage (const juce::MidiMessage& message) noexcept
{
    if (drum == nullptr)
        return;

    if (message.isNoteOn())
        drum->strikeAtDefaultPoint (snaresim::strikeSpeedFromVelocity (message.getVelocity(), strikeSpeedMax_m_per_s));
    else if (message.isAllSoundOff())
        drum->reset();
}

void SnareSimAudioProcessor::renderRange (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept
{
    const int numChannels = buffer.getNumChannels();
    const int chunkCapacity = (int) scratch.size();

    if (drum == nullptr || chunkCapacity == 0)
    {
        for (int ch = 0; ch < numChannels; ++ch)
            buffer.clear (ch, startSample, numSamples);
        return;
    }

    // Blocks larger than announced in prepareToPlay are rendered in chunks of the scratch size.
    while (numSamples > 0)
    {
        const int n = juce::jmin (numSamples, chunkCapacity);
        float* out = scratch.data();

        drum->process (out, n);

        bool nonFinite = false;
        for (int i = 0; i < n; ++i)
        {
            if (! std::isfinite (out[i]))
            {
                out[i] = 0.0f;
                nonFinite = true;
            }
        }

        if (nonFinite)
        {
            // The simulation blew up: silence the drum rather than pass garbage to the host.
            std::fill (out, out + n, 0.0f);
            drum->reset();
        }

        for (int ch = 0; ch < numChannels; ++ch)
            buffer.copyFrom (ch, startSample, out, n);

        startSample += n;
        numSamples -= n;
    }
}

void SnareSimAudioProcessor::processBlock (juce::AudioBuffer<float>& buffer, juce::MidiBuffer& midiMessages)
{
    juce::ScopedNoDenormals noDenormals;

    const int numSamples = buffer.getNumSamples();
    int position = 0;

    // Split the block at every MIDI event so that each strike starts on its own sample.
    for (const auto metadata : midiMessages)
    {
        const int eventPosition = juce::jlimit (position, numSamples, metadata.samplePosition);

        if (eventPosition > position)
        {
            renderRange (buffer, position, eventPosition - position);
            position = eventPosition;
        }

        handleMidiMessage (metadata.getMessage());
    }

    if (numSamples > position)
        renderRange (buffer, position, numSamples - position);
}

//==============================================================================
juce::AudioProcessorEditor* SnareSimAudioProcessor::createEditor()
{
    return new juce::GenericAudioProcessorEditor (*this);
}

//==============================================================================
void SnareSimAudioProcessor::getStateInformation (juce::MemoryBlock& destData)
{
    auto state = apvts.copyState();

    if (auto xml = state.createXml())
    {
        xml->setAttribute (stateVersionAttribute, stateVersion);
        copyXmlToBinary (*xml, destData);
    }
}

void SnareSimAudioProcessor::setStateInformation (const void* data, int sizeInBytes)
{
    const auto xml = getXmlFromBinary (data, sizeInBytes);

    if (xml == nullptr || ! xml->hasTagName (apvts.state.getType()))
        return;

    // Version 0 (no attribute) and 1 share the same layout: one PARAM child per parameter ID.
    // Parameters missing from an older state keep their current values.
    const int version = xml->getIntAttribute (stateVersionAttribute, 0);
    if (version > stateVersion)
    {
        DBG ("SnareSim: loading a state saved by a newer version (" << version << ")");
    }

    auto tree = juce::ValueTree::fromXml (*xml);
    tree.removeProperty (stateVersionAttribute, nullptr);
    apvts.replaceState (tree);
}

//==============================================================================
// This creates new instances of the plug-in.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter()
{
    return new SnareSimAudioProcessor();
}
