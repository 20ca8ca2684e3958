#pragma once
// The real-time player: everything between a session (DrumSession.h, the one door every client
// plays through) and the Drum.
//
//  - parameters: continuous ones are smoothed (about 30 ms) and applied to the running drum
//    every sub-block of at most 32 samples (Drum::applyLive); toggles and choices apply at
//    once; those whose change needs a new grid or model (and a new sample rate) need a new model, built on a
//    background thread (ModelExchange.h), handed over lock-free and crossfaded in (20 ms);
//  - events: a block is split at every event (notes through the articulation map, all sound
//    off, parameter changes), so each takes effect on its own sample;
//  - the guard: a drum that goes non-finite is reset and silenced; no NaN, Inf or subnormal
//    value ever leaves process();
//  - the counters the editor shows: CPU load, Newton iterations, fallbacks, resets.
//
// Threads: process(), setTarget() and the event calls run on the audio thread and never
// lock, allocate, free, log or block. prepare() / start() / stopBuilding() run on another thread
// while the host keeps the audio thread out of process() during start(). The counters may be
// read from any thread; pullSnapshot() from one reader thread.

#include "Drum.h"
#include "DrumSnapshot.h"
#include "ModelExchange.h"
#include "Parameters.h"
#include "TripleBuffer.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace snaresim
{

struct PlayerEvent
{
    enum class Type : std::uint8_t
    {
        noteOn,      // note and velocity (1..127) through the articulation map
        strike,      // velocity (1..127): the main strike at the strike-position control
        allSoundOff, // silence the drum at once
        parameter    // a new target value for one parameter from this sample on
    };

    int sample = 0; // offset in the block; events must be in order
    Type type = Type::noteOn;
    int note = 0;
    int velocity = 0;
    ParamId parameter = ParamId::batterTension;
    double value = 0.0;

    static PlayerEvent noteOn(int sample, int note, int velocity) { return { sample, Type::noteOn, note, velocity }; }
    static PlayerEvent strikeAt(int sample, int velocity) { return { sample, Type::strike, 0, velocity }; }
    static PlayerEvent allSoundOff(int sample) { return { sample, Type::allSoundOff }; }
    static PlayerEvent parameterChange(int sample, ParamId id, double v)
    {
        PlayerEvent e { sample, Type::parameter };
        e.parameter = id;
        e.value = v;
        return e;
    }
};

// For offline hosts (the renderer): called after every step with the drum that made it.
class StepObserver
{
public:
    virtual ~StepObserver() = default;
    virtual void afterStep(const Drum& drum) = 0;
};

class DrumPlayer
{
public:
    static constexpr int subBlockSize = 32; // parameters are applied at least this often
    static constexpr double smoothingSeconds = 0.03;
    static constexpr double crossfadeSeconds = 0.02;

    // readParameters: what the background builder builds new models from (thread-safe);
    // options: what every model is built with besides them (BuildOptions.h).
    explicit DrumPlayer(ModelBuilder::ParameterReader readParameters, BuildOptions options = {});
    ~DrumPlayer();
    DrumPlayer(const DrumPlayer&) = delete;
    DrumPlayer& operator=(const DrumPlayer&) = delete;

    // --- preparing (not the audio thread) ---------------------------------------------------
    // prepare() builds the model for this rate and these parameters (keeping the current one
    // when it fits) while holding the builder; start() installs it and starts from the
    // parameters without ramps, and must run while process() cannot (the host's callback
    // lock); the preparation, destroyed afterwards, frees the old models outside that lock.
    class Preparation
    {
    public:
        Preparation(Preparation&&) = default;
        ~Preparation();

    private:
        friend class DrumPlayer;
        explicit Preparation(std::mutex& builderLock) : hold(builderLock) {}
        std::unique_lock<std::mutex> hold;
        std::unique_ptr<DrumModel> fresh;
        std::vector<std::unique_ptr<DrumModel>> old;
        ParameterSet params;
        GridKey key;
        bool keepCurrent = false;
        DrumPlayer* player = nullptr;
    };

    // With OnBuildFailure::raise, prepare() throws std::invalid_argument when `params` cannot
    // be built at this rate (offline clients, who report it) instead of falling back.
    Preparation prepare(double sampleRate, const ParameterSet& params, OnBuildFailure onFailure = OnBuildFailure::fallBack);
    void start(Preparation& preparation) noexcept;

    // Silences the drums (host's callback lock held).
    void releaseResources() noexcept;

    // After a state or a program load (not the audio thread): the model the parameters need
    // now is built at once, so the next block plays it.
    void buildNowIfNeeded() { builder.buildNowIfNeeded(); }

    // The background builder runs from prepare() until stopBuilding() or destruction.
    void stopBuilding() { builder.stop(); }

    // --- audio thread -----------------------------------------------------------------------
    // The host's value of a parameter for the coming block (sanitised here).
    void setTarget(ParamId id, double value) noexcept;

    // Renders n samples (mono) into out, with the events at their samples. With an observer,
    // the drum is stepped one sample at a time and handed to it after every step.
    void process(float* out, int n, std::span<const PlayerEvent> events, StepObserver* observer = nullptr) noexcept;

    // --- any thread -------------------------------------------------------------------------
    float cpuLoad() const noexcept { return cpuLoadNow.load(std::memory_order_relaxed); }
    float peakCpuLoad() const noexcept { return peakCpuLoadNow.load(std::memory_order_relaxed); }
    long solverFallbacks() const noexcept { return fallbacksNow.load(std::memory_order_relaxed); }
    int nonFiniteResets() const noexcept { return resetsNow.load(std::memory_order_relaxed); }
    int maxNewtonIterations() const noexcept { return iterationsNow.load(std::memory_order_relaxed); }
    bool usedFallbackParameters() const noexcept { return fellBackNow.load(std::memory_order_relaxed); }
    int modelSwapCount() const noexcept { return modelSwaps.load(std::memory_order_relaxed); }
    // The output's lag behind a strike in whole host samples: the drum playing now's
    // (Drum::latencySamples, rounded) and its pad's (DrumModel::latencySamples; 0 without a
    // drum). With BuildOptions::constantLatency the same for every drum at the rate.
    int latencySamples() const noexcept { return latencyNow.load(std::memory_order_relaxed); }

    // One reader thread: the newest snapshot published (about 30 per second of audio) into
    // `out`; false when nothing new was published since the last call.
    bool pullSnapshot(DrumSnapshot& out);

    // The drum playing now (nullptr before start() or when the rate cannot be simulated).
    // Only while process() is not running.
    const Drum* drum() const noexcept { return current != nullptr ? current->drum.get() : nullptr; }
    Drum* drum() noexcept { return current != nullptr ? current->drum.get() : nullptr; }
    double sampleRate() const noexcept { return rate; }

private:
    void installPendingModel() noexcept;
    void retire(DrumModel* model) noexcept;
    void flushRetireBacklog() noexcept;
    void applyEvent(const PlayerEvent& event) noexcept;
    void advanceParameters(int numSamples) noexcept;
    bool renderModel(DrumModel& model, float* out, int numSamples, StepObserver* observer) noexcept;
    void renderRange(float* out, int numSamples, StepObserver* observer) noexcept;
    void renderSubBlock(float* out, int numSamples, StepObserver* observer) noexcept;
    void publishStats() noexcept;
    void publishLatency() noexcept;
    void updateCpuLoad(double elapsedSeconds, int numSamples) noexcept;

    // A value that moves to its target linearly over a fixed number of samples.
    struct Ramp
    {
        double current = 0.0, target = 0.0, step = 0.0;
        int remaining = 0, length = 1;

        void reset(int lengthInSamples, double value) noexcept;
        void setTarget(double value) noexcept;
        bool moving() const noexcept { return remaining > 0; }
        double skip(int numSamples) noexcept;
    };

    ModelBuilder builder;
    DrumModel* current = nullptr;                // the model playing (audio thread; start() under the host's lock)
    DrumModel* fading = nullptr;                 // the previous model, fading out
    std::array<DrumModel*, 16> retireBacklog {}; // retired models the queue had no room for
    int fadePosition = 0, fadeLength = 1;
    int quietSamples = 0; // samples the output has been silent (no fade needed then)
    double rate = 0.0;    // the rate started with

    // parameters (audio thread)
    ParameterSet liveParameters; // what the drum plays with now (smoothed)
    std::array<Ramp, kNumParameters> ramps {};
    std::array<bool, kNumParameters> smoothed {}; // continuous and live
    bool liveDirty = true;                        // liveParameters changed since the last applyLive
    double lastSnaresParameter = -1.0;            // snares_engaged as last set (-1: not yet)
    bool snaresEngaged = true;                    // the parameter, or the last snares off / on note

    // rendering (audio thread)
    std::array<float, subBlockSize> fadeScratch {};
    int samplesSinceSnapshot = 0, snapshotInterval = 1600;
    int samplesSinceFiniteCheck = 0;
    long retiredFallbacks = 0;
    int retiredMaxIterations = 0;
    double smoothedLoad = 0.0, peakLoad = 0.0;

    // published to other threads
    TripleBuffer<DrumSnapshot> snapshots;
    std::atomic<float> cpuLoadNow { 0.0f }, peakCpuLoadNow { 0.0f };
    std::atomic<long> fallbacksNow { 0 };
    std::atomic<int> resetsNow { 0 };
    std::atomic<int> iterationsNow { 0 };
    std::atomic<bool> fellBackNow { false };
    std::atomic<int> modelSwaps { 0 };
    std::atomic<int> latencyNow { 0 };
};

} // namespace snaresim
