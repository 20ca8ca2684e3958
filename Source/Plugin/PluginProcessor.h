#pragma once
// The SnareSim plug-in processor: JUCE's side of the drum, an adapter onto the engine's one door
// (DrumSession.h). processBlock hands the host's parameters, MIDI and buffer to the session,
// which does the air-model policy, the smoothing, event splitting, model hand-off, guard and
// metering. The parameters (ParameterLayout.h), the saved state (PluginState.h) and the factory
// programs live here.
// In real time processBlock never locks, allocates, frees, logs or blocks; the first block of a
// host's offline render may build the drum that render needs (setNonRealtime).
//
// Threads: processBlock runs on the audio thread; pullSnapshot on the message thread;
// setCurrentProgram and the state calls on the host's message / UI thread (they set parameters
// and may build a new model there, never on the audio thread); the meters and counters may be
// read from any thread.

#include <juce_audio_processors/juce_audio_processors.h>

#include <array>
#include <atomic>
#include <memory>

#include "DrumSession.h"
#include "KeepUp.h"
#include "Parameters.h"

class SnareSimAudioProcessor final : public juce::AudioProcessor,
                                     private juce::AsyncUpdater,
                                     private juce::AudioProcessorParameter::Listener
{
public:
    SnareSimAudioProcessor();
    ~SnareSimAudioProcessor() override;

    //==============================================================================
    void prepareToPlay(double sampleRate, int maximumExpectedSamplesPerBlock) override;
    void releaseResources() override;
    bool isBusesLayoutSupported(const BusesLayout& layouts) const override;

    using AudioProcessor::processBlock;
    void processBlock(juce::AudioBuffer<float>& buffer, juce::MidiBuffer& midiMessages) override;

    //==============================================================================
    juce::AudioProcessorEditor* createEditor() override;
    bool hasEditor() const override { return true; }

    const juce::String getName() const override;
    bool acceptsMidi() const override { return true; }
    bool producesMidi() const override { return false; }
    bool isMidiEffect() const override { return false; }
    double getTailLengthSeconds() const override { return 0.0; }

    // Programs: the factory presets (snaresim::factoryPresets()). setCurrentProgram sets every
    // parameter but keep_up, the machine's (the preset's values, the defaults for the rest) at
    // once on the calling thread;
    // called from inside processBlock, it is deferred to the message thread.
    int getNumPrograms() override;
    int getCurrentProgram() override;
    void setCurrentProgram(int index) override;
    const juce::String getProgramName(int index) override;
    void changeProgramName(int, const juce::String&) override {}

    //==============================================================================
    // The versioned state (PluginState.h).
    void getStateInformation(juce::MemoryBlock& destData) override;
    void setStateInformation(const void* data, int sizeInBytes) override;

    //==============================================================================
    // For the editor.
    juce::AudioProcessorValueTreeState& getValueTreeState() noexcept { return apvts; }

    // Message thread: copies the newest snapshot the audio thread published (about 30 per
    // second of audio) into `out`; false when nothing new was published since the last call.
    bool pullSnapshot(snaresim::DrumSnapshot& out) { return session.drumPlayer().pullSnapshot(out); }

    // Share of the real-time budget the last blocks used (smoothed; 0..1, above 1 when the
    // processor cannot keep up) and the worst recent block.
    float getCpuLoad() const noexcept { return session.drumPlayer().cpuLoad(); }
    float getPeakCpuLoad() const noexcept { return session.drumPlayer().peakCpuLoad(); }
    // Newton solves that missed their cap and fell back (all models since construction).
    long getSolverFallbacks() const noexcept { return session.drumPlayer().solverFallbacks(); }
    // Times the simulation went non-finite and was reset quietly.
    int getNonFiniteResets() const noexcept { return session.drumPlayer().nonFiniteResets(); }
    // Largest number of Newton iterations of any contact solve (all models since construction).
    int getMaxNewtonIterations() const noexcept { return session.drumPlayer().maxNewtonIterations(); }

    //==============================================================================
    // For tests and tools.

    // The parameter values the drum is built from: DrumSession::playedParameters (the air
    // model as it plays, Quality as real time plays it). Thread-safe; never waits for a
    // measurement; not for the audio thread.
    snaresim::ParameterSet currentParameters() const { return session.playedParameters(); }

    // The parameters as the host holds them (clamped into range; the air model as chosen, not
    // as it plays). Any thread but the audio thread.
    snaresim::ParameterSet parameterValues() const { return session.parameters(); }

    // Message thread: sets every parameter of the drum to `values` (as a host's automation
    // would, one gesture each; keep_up, the machine's, stays) and builds the new model now if it
    // needs one. Programs and preset files.
    void applyParameters(const snaresim::ParameterSet& values);

    // True when the model playing now could not be built from the parameters and fell back
    // to the default parameter set.
    bool usedFallbackParameters() const noexcept { return session.drumPlayer().usedFallbackParameters(); }

    // The air box in real time: true while the air model is the air box and the cavity plays
    // instead (not measured yet, or this machine does not keep up with it). The verdict of the
    // measurement for the parameters as they are, and the editor's line about it (empty when
    // there is nothing to say).
    bool airBoxHeldBack() const { return session.airBoxHeldBack(); }
    snaresim::KeepUpCheck::Verdict airBoxVerdict() const { return session.airBoxVerdict(); }
    juce::String airBoxNotice() const { return session.airBoxNotice(); }
    // Measurements of the air box finished so far (for tests).
    int airBoxMeasurements() const noexcept { return session.airBoxCheck().measurementsDone(); }

    // Quality in real time ("Lower Quality when slow", keep_up): the bandwidth playing, the
    // verdict on the chosen one at the prepared rate and block size (none when not measured:
    // offline, switched off, or the air box plays), and the editor's line about a lower one
    // playing (empty when the chosen one plays).
    double playingBandwidth() const noexcept { return session.playingBandwidth(); }
    snaresim::KeepUpCheck::Verdict qualityVerdict() const { return session.qualityVerdict(); }
    juce::String qualityNotice() const { return session.qualityNotice(); }
    // What the editor says about the drum that plays: the air box's line and Quality's.
    juce::String playNotice() const { return session.playNotice(); }
    // Measures Quality's drums with `m` instead of timing them (tests: a slower machine). Every
    // processor made after setDefaultQualityMeasurement starts with its `m` (the test runner's).
    void setQualityMeasurement(snaresim::KeepUpCheck::Measurement m) { session.qualityCheck().setMeasurement(std::move(m)); }
    static void setDefaultQualityMeasurement(snaresim::KeepUpCheck::Measurement m);
    // Measures the air box with `m` instead of timing it (tests: a machine of a known speed).
    void setAirBoxMeasurement(snaresim::KeepUpCheck::Measurement m) { session.airBoxCheck().setMeasurement(std::move(m)); }
    int qualityMeasurements() const noexcept { return session.qualityCheck().measurementsDone(); }

    // The host renders offline (any thread; VST3 hosts call it from the audio thread).
    void setNonRealtime(bool isNonRealtime) noexcept override;

    // Models installed by the audio thread so far (prepareToPlay and background builds).
    int getModelSwapCount() const noexcept { return session.drumPlayer().modelSwapCount(); }

    // The drum playing now (nullptr before prepareToPlay or when the rate cannot be simulated).
    // Only safe to use while processBlock is not running.
    const snaresim::Drum* getDrum() const noexcept { return session.drumPlayer().drum(); }

private:
    void handleAsyncUpdate() override;
    void applyProgram(int index);
    // A host's or the editor's change of a parameter, passed on to the session (any thread).
    void parameterValueChanged(int parameterIndex, float newValue) override;
    void parameterGestureChanged(int, bool) override {}
    void pushParameters() noexcept; // every parameter as the host holds it, to the session

    juce::AudioProcessorValueTreeState apvts;
    std::array<std::atomic<float>*, snaresim::kNumParameters> rawParameters {};
    std::vector<std::pair<juce::RangedAudioParameter*, snaresim::ParamId>> byIndex; // the processor's parameter index -> id

    // The one door into the engine: parameters, air-model policy, player.
    snaresim::DrumSession session;
    std::array<snaresim::PlayerEvent, 1024> events {}; // one block's MIDI, translated (audio thread)

    // --- programs --------------------------------------------------------------------------
    std::atomic<int> currentProgram { 0 };
    std::atomic<int> programToApply { -1 };                           // set inside processBlock, applied on the message thread
    std::atomic<juce::Thread::ThreadID> processingThread { nullptr }; // while in processBlock

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR(SnareSimAudioProcessor)
};
