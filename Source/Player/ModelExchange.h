#pragma once
// Building drum models off the audio thread and handing them over without locks.
//
// A DrumModel is a snaresim::Drum with the parameter values it was built from. The audio
// thread owns the model it plays (and the one it fades out). New models come from the
// ModelBuilder thread through a single-slot exchange (one std::atomic pointer); models the
// audio thread is done with go back to the builder thread through a small lock-free retire
// queue and are deleted there. The audio thread never allocates, frees, locks or waits.

#include "BuildOptions.h"
#include "Drum.h"
#include "LatencyPad.h"
#include "Parameters.h"

#include <array>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

namespace snaresim
{

// What a model's grid depends on: the sample rate and the parameters that rebuild the model.
struct GridKey
{
    double sampleRate = 0.0;
    std::array<double, kNumParameters> values {}; // parameters that rebuild the model; 0 for the others

    static GridKey of(const ParameterSet& params, double sampleRate) noexcept;
    bool operator==(const GridKey&) const = default;
};

struct DrumModel
{
    std::unique_ptr<Drum> drum; // nullptr: nothing can be simulated at this rate (silence)
    ParameterSet built;         // the values the drum was built from
    GridKey requested;          // what was asked for (differs from `built` after a fallback)
    bool fellBack = false;      // the requested values failed; built from the defaults
    LatencyPad pad;             // after the drum's output (BuildOptions::constantLatency)

    double sampleRate() const noexcept { return requested.sampleRate; }
    // the drum's and the pad's lag behind a strike, in host samples (0 without a drum)
    int latencySamples() const noexcept { return drum != nullptr ? (int) std::lround(drum->latencySamples()) + pad.length() : 0; }
    // the drum silenced and its pad emptied (real-time safe)
    void silence() noexcept
    {
        if (drum != nullptr)
            drum->reset();
        pad.clear();
    }
};

// The whole samples that bring a drum's lag to the longest at its host rate
// (longestLatencySamples, Drum::latencySamples): its pad under BuildOptions::constantLatency.
inline int latencyPadFor(const Drum& drum) noexcept
{
    return (int) std::lround(longestLatencySamples(drum.sampleRate())) - (int) std::lround(drum.latencySamples());
}

// The one place a Drum is built for a client: the parameters mapped at this rate
// (makeDrumConfig), the options applied, the drum made. Throws std::invalid_argument when the
// drum cannot be simulated so. Not for the audio thread.
std::unique_ptr<Drum> buildDrum(const ParameterSet& params, double sampleRate, const BuildOptions& options = {});

// What a model does when its parameters cannot be built.
enum class OnBuildFailure
{
    fallBack, // the default parameter set at that rate, else an empty (silent) model
    raise     // std::invalid_argument, as buildDrum (offline clients, who report it)
};

// Builds a model from `params` with buildDrum, with BuildOptions::constantLatency its pad to
// the longest lag at the rate. Falling back, it never throws anything but std::bad_alloc. Not
// for the audio thread.
std::unique_ptr<DrumModel> buildModel(const ParameterSet& params, double sampleRate, const BuildOptions& options = {},
                                      OnBuildFailure onFailure = OnBuildFailure::fallBack);

// One slot, one pointer: whoever exchanges a pointer out owns it.
template <typename T>
class AtomicSlot
{
public:
    AtomicSlot() = default;
    AtomicSlot(const AtomicSlot&) = delete;
    AtomicSlot& operator=(const AtomicSlot&) = delete;
    ~AtomicSlot() { delete take(); }

    // Puts `next` in the slot and returns what was there (the caller owns it), or nullptr.
    T* exchange(T* next) noexcept { return slot.exchange(next, std::memory_order_acq_rel); }
    T* take() noexcept { return exchange(nullptr); }
    bool isEmpty() const noexcept { return slot.load(std::memory_order_acquire) == nullptr; }

private:
    std::atomic<T*> slot { nullptr };
};

// A fixed number of slots the audio thread drops objects into (tryPush) and another thread
// empties (deleteAll). Lock-free and allocation-free on both sides.
template <typename T, std::size_t Capacity>
class RetireQueue
{
public:
    RetireQueue() = default;
    RetireQueue(const RetireQueue&) = delete;
    RetireQueue& operator=(const RetireQueue&) = delete;
    ~RetireQueue() { deleteAll(); }

    // False when every slot is taken: keep the object and try again later.
    bool tryPush(T* object) noexcept
    {
        for (auto& s : slots)
        {
            T* expected = nullptr;
            if (s.compare_exchange_strong(expected, object, std::memory_order_acq_rel))
                return true;
        }
        return false;
    }

    void deleteAll()
    {
        for (auto& s : slots)
            delete s.exchange(nullptr, std::memory_order_acq_rel);
    }

private:
    std::array<std::atomic<T*>, Capacity> slots {};
};

// The background thread: builds a model whenever the parameters that rebuild the model differ from the
// last model it built or was told about (polling their atomics, so nobody has to wake it from
// the audio thread), publishes it in `pending`, and deletes retired models.
class ModelBuilder final
{
public:
    using ParameterReader = std::function<ParameterSet()>; // thread-safe (reads atomics)

    explicit ModelBuilder(ParameterReader readParameters, BuildOptions options = {});
    ~ModelBuilder();

    void start();
    void stop();

    // Held while a model is built and published; prepareToPlay holds it to install a model
    // itself and to set the target without racing the builder.
    std::mutex& getLock() noexcept { return lock; }

    // With getLock() held: models are built at this rate, and `current` is what is installed
    // (so no model is built for it). A sample rate <= 0 stops building.
    void setTargetLocked(double sampleRate, const GridKey& current);

    // Builds the model the parameters need now, on the calling thread, if it differs from the
    // last one (message thread, after a state or program load: the next block then plays it).
    // Never the audio thread.
    void buildNowIfNeeded();

    const BuildOptions& options() const noexcept { return buildOptions; }

    AtomicSlot<DrumModel> pending;     // builder -> audio thread
    RetireQueue<DrumModel, 8> retired; // audio thread -> builder (deleted there)

    static constexpr int pollIntervalMs = 15;

private:
    void run();
    void buildIfNeededLocked();

    ParameterReader readParameters;
    const BuildOptions buildOptions;
    std::mutex lock;
    std::thread thread;
    std::mutex wakeLock;
    std::condition_variable wake;
    bool exitRequested = false; // guarded by wakeLock
    double targetRate = 0.0;    // guarded by lock
    GridKey lastKey;            // guarded by lock: the newest model built or installed
};

} // namespace snaresim
