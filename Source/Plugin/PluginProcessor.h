#pragma once
// The SnareSim plug-in processor: a MIDI-driven synth around snaresim::Drum.
//
// Parameters are built from snaresim::parameterSpecs() (Source/Engine/Parameters.h); the
// table's key is the parameter ID. In this version a parameter change takes effect at the next
// prepareToPlay(), where the drum is rebuilt from the current values.

#include <juce_audio_processors/juce_audio_processors.h>

#include <array>
#include <atomic>
#include <memory>
#include <vector>

#include "Parameters.h"

namespace snaresim
{
class Drum;
}

class SnareSimAudioProcessor final : public juce::AudioProcessor
{
public:
    // Written into saved states; states without it are read as version 0.
    static constexpr int stateVersion = 1;
    static constexpr const char* stateVersionAttribute = "stateVersion";

    SnareSimAudioProcessor();
    ~SnareSimAudioProcessor() override;

    //==============================================================================
    void prepareToPlay (double sampleRate, int maximumExpectedSamplesPerBlock) override;
    void releaseResources() override;
    bool isBusesLayoutSupported (const BusesLayout& layouts) const override;

    using AudioProcessor::processBlock;
    void processBlock (juce::AudioBuffer<float>& buffer, juce::MidiBuffer& midiMessages) override;

    //==============================================================================
    juce::AudioProcessorEditor* createEditor() override;
    bool hasEditor() const override { return true; }

    const juce::String getName() const override;
    bool acceptsMidi() const override { return true; }
    bool producesMidi() const override { return false; }
    bool isMidiEffect() const override { return false; }
    double getTailLengthSeconds() const override { return 0.0; }

    int getNumPrograms() override { return 1; }
    int getCurrentProgram() override { return 0; }
    void setCurrentProgram (int) override {}
    const juce::String getProgramName (int) override { return {}; }
    void changeProgramName (int, const juce::String&) override {}

    //==============================================================================
    void getStateInformation (juce::MemoryBlock& destData) override;
    void setStateInformation (const void* data, int sizeInBytes) override;

    //==============================================================================
    juce::AudioProcessorValueTreeState& getValueTreeState() noexcept { return apvts; }

    // The current parameter values as the engine sees them (clamped into range).
    snaresim::ParameterSet currentParameters() const;

    // True when the last prepareToPlay() could not build the drum from the parameters and
    // fell back to the default parameter set.
    bool usedFallbackParameters() const noexcept { return fellBackToDefaults; }

    // The drum currently used for rendering (nullptr before prepareToPlay).
    const snaresim::Drum* getDrum() const noexcept { return drum.get(); }

    static juce::AudioProcessorValueTreeState::ParameterLayout createParameterLayout();

private:
    void handleMidiMessage (const juce::MidiMessage& message) noexcept;
    void renderRange (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept;

    juce::AudioProcessorValueTreeState apvts;
    std::array<std::atomic<float>*, snaresim::kNumParameters> rawParameters {};

    std::unique_ptr<snaresim::Drum> drum;  // swapped under the callback lock in prepareToPlay
    double strikeSpeedMax_m_per_s = 6.0;   // of the drum's config, for the velocity curve
    std::vector<float> scratch;            // mono render buffer, sized in prepareToPlay
    bool fellBackToDefaults = false;

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR (SnareSimAudioProcessor)
};
