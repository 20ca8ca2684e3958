#pragma once
// The SnareSim plug-in processor: a MIDI-driven synth around snaresim::Drum.
//
// Parameters are built from snaresim::parameterSpecs() (Source/Engine/Parameters.h); the
// table's key is the parameter ID. Every parameter is live:
//  - continuous ones are smoothed (about 30 ms) and applied to the running drum every
//    sub-block of at most 32 samples (Drum::applyLive);
//  - toggles and choices apply at once;
//  - the needsNewGrid ones (and a new sample rate) need a new model, built on a background
//    thread (ModelExchange.h), handed over lock-free and crossfaded in over about 20 ms.
// processBlock never locks, allocates, frees, logs or blocks.
//
// Threads: processBlock runs on the audio thread; pullSnapshot on the message thread;
// setCurrentProgram and the state calls on the host's message / UI thread (they set parameters
// and may build a new model there, never on the audio thread); the meters and counters may be
// read from any thread.

#include <juce_audio_processors/juce_audio_processors.h>

#include <array>
#include <atomic>
#include <memory>

#include "DrumSnapshot.h"
#include "ModelExchange.h"
#include "Parameters.h"
#include "TripleBuffer.h"

namespace snaresim
{
class Drum;
}

class SnareSimAudioProcessor final : public juce::AudioProcessor,
                                     private juce::AsyncUpdater
{
public:
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

    // Programs: the factory presets (snaresim::factoryPresets()). setCurrentProgram sets every
    // parameter (the preset's values, the defaults for the rest) at once on the calling thread;
    // called from inside processBlock, it is deferred to the message thread.
    int getNumPrograms() override;
    int getCurrentProgram() override;
    void setCurrentProgram (int index) override;
    const juce::String getProgramName (int index) override;
    void changeProgramName (int, const juce::String&) override {}

    //==============================================================================
    // The versioned state (PluginState.h).
    void getStateInformation (juce::MemoryBlock& destData) override;
    void setStateInformation (const void* data, int sizeInBytes) override;

    //==============================================================================
    // For the editor.
    juce::AudioProcessorValueTreeState& getValueTreeState() noexcept { return apvts; }

    // Message thread: copies the newest snapshot the audio thread published (about 30 per
    // second of audio) into `out`; false when nothing new was published since the last call.
    bool pullSnapshot (snaresim::DrumSnapshot& out);

    // Share of the real-time budget the last blocks used (smoothed; 0..1, above 1 when the
    // processor cannot keep up) and the worst recent block.
    float getCpuLoad() const noexcept { return cpuLoad.load (std::memory_order_relaxed); }
    float getPeakCpuLoad() const noexcept { return peakCpuLoad.load (std::memory_order_relaxed); }
    // Newton solves that missed their cap and fell back (all models since construction).
    long getSolverFallbacks() const noexcept { return solverFallbacks.load (std::memory_order_relaxed); }
    // Times the simulation went non-finite and was reset quietly.
    int getNonFiniteResets() const noexcept { return nonFiniteResets.load (std::memory_order_relaxed); }
    // Largest number of Newton iterations of any contact solve (all models since construction).
    int getMaxNewtonIterations() const noexcept { return maxNewtonIterations.load (std::memory_order_relaxed); }

    //==============================================================================
    // For tests and tools.

    // The current parameter values as the engine sees them (clamped into range). Thread-safe.
    snaresim::ParameterSet currentParameters() const;

    // True when the model playing now could not be built from the parameters and fell back
    // to the default parameter set.
    bool usedFallbackParameters() const noexcept { return fellBackToDefaults.load(); }

    // Models installed by the audio thread so far (prepareToPlay and background builds).
    int getModelSwapCount() const noexcept { return modelSwaps.load(); }

    // The drum playing now (nullptr before prepareToPlay or when the rate cannot be simulated).
    // Only safe to use while processBlock is not running.
    const snaresim::Drum* getDrum() const noexcept;


private:
    using DrumModel = snaresim::plugin::DrumModel;

    static constexpr int subBlockSize = 32;         // parameters are applied at least this often
    static constexpr double smoothingSeconds = 0.03;
    static constexpr double crossfadeSeconds = 0.02;

    void handleAsyncUpdate() override;
    void applyProgram (int index);

    // Audio thread.
    void installPendingModel() noexcept;
    void retire (DrumModel* model) noexcept;
    void flushRetireBacklog() noexcept;
    void readParameterTargets() noexcept;
    void advanceParameters (int numSamples) noexcept;
    void handleMidiMessage (const juce::MidiMessage& message) noexcept;
    void renderRange (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept;
    void renderSubBlock (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept;
    bool renderModel (DrumModel& model, float* out, int numSamples) noexcept;
    void publishStats() noexcept;
    void updateCpuLoad (juce::int64 startTicks, int numSamples) noexcept;

    juce::AudioProcessorValueTreeState apvts;
    std::array<std::atomic<float>*, snaresim::kNumParameters> rawParameters {};

    // --- models ---------------------------------------------------------------------------
    snaresim::plugin::ModelBuilder builder;
    DrumModel* current = nullptr;       // audio thread (prepareToPlay under the callback lock)
    DrumModel* fading = nullptr;        // the previous model, fading out
    std::array<DrumModel*, 16> retireBacklog {};   // retired models the queue had no room for
    int fadePosition = 0, fadeLength = 1;
    int quietSamples = 0;               // samples the output has been silent (no fade needed then)
    double sampleRate = 0.0;            // the rate prepared for (audio thread's copy)
    std::atomic<bool> fellBackToDefaults { false };
    std::atomic<int> modelSwaps { 0 };

    // --- parameters (audio thread) ---------------------------------------------------------
    snaresim::ParameterSet liveParameters;      // what the drum plays with now (smoothed)
    std::array<juce::SmoothedValue<double>, snaresim::kNumParameters> smoothers;
    std::array<bool, snaresim::kNumParameters> smoothed {};   // continuous and live
    bool liveDirty = true;              // liveParameters changed since the last applyLive
    float lastSnaresParameter = -1.0f;  // snares_engaged as last read (-1: not read yet)
    bool snaresEngaged = true;          // the parameter, or the last snares off / on note

    // --- rendering (audio thread) ----------------------------------------------------------
    std::array<float, subBlockSize> renderScratch {}, fadeScratch {};
    int samplesSinceSnapshot = 0, snapshotInterval = 1600;
    int samplesSinceFiniteCheck = 0;
    long retiredFallbacks = 0;
    int retiredMaxIterations = 0;

    // --- published to other threads --------------------------------------------------------
    snaresim::plugin::TripleBuffer<snaresim::DrumSnapshot> snapshots;
    std::atomic<float> cpuLoad { 0.0f }, peakCpuLoad { 0.0f };
    std::atomic<long> solverFallbacks { 0 };
    std::atomic<int> nonFiniteResets { 0 };
    std::atomic<int> maxNewtonIterations { 0 };
    double smoothedLoad = 0.0, peakLoad = 0.0;  // audio thread

    // --- programs --------------------------------------------------------------------------
    std::atomic<int> currentProgram { 0 };
    std::atomic<int> programToApply { -1 };     // set inside processBlock, applied on the message thread
    std::atomic<juce::Thread::ThreadID> processingThread { nullptr };   // while in processBlock

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR (SnareSimAudioProcessor)
};
