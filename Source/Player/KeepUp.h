#pragma once
// Whether a drum keeps up in real time on this machine, by measurement: a short render of the
// drum through a session as a host plays it (unstruck, then a fortissimo strike), timed block by
// block in the host's block size. KeepUpCheck runs these measurements on a thread of its own and remembers their
// verdicts, so that a caller (the plug-in's parameter reader) asks without ever waiting for one.
// Nothing here runs on the audio thread.

#include "ModelExchange.h"
#include "Parameters.h"

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace snaresim
{

class DrumSession;

struct KeepUpFigures
{
    double load = 0.0;            // seconds of compute per second of audio, over the probe
    double worstBlockShare = 0.0; // the slowest block's compute / its duration
    double audioSeconds = 0.0;    // audio rendered
    int blockSize = 0;
    bool cutShort = false; // stopped at the compute cap: far slower than real time
};

// What "keeps up" means: at most half the real-time budget on average (the host, the editor
// and other plug-ins need the rest), and the slowest block done within 80 % of its duration.
inline constexpr double kKeepUpMaxLoad = 0.5;
inline constexpr double kKeepUpMaxWorstBlock = 0.8;
bool keepsUp(const KeepUpFigures& figures) noexcept;

// The probe: its length in audio (the first 20 % unstruck, then note 38 at velocity 127), at
// least one unstruck and two struck blocks; a render that has used kProbeComputeCapSeconds of
// compute stops there (cutShort; its load is then at least 4 times real time).
inline constexpr double kProbeSeconds = 0.1;
inline constexpr double kProbeComputeCapSeconds = 4.0;

// Times a started session's drum (from silence: it is reset first, and left reset) in blocks of
// blockSize samples through DrumSession::process, as a host's processBlock calls it, with
// denormals flushed as processBlock does. `cancelled` is polled every few hundred samples; when
// it says so the figures so far are returned.
KeepUpFigures measureKeepUp(DrumSession& session, int blockSize, const std::function<bool()>& cancelled = {});

class KeepUpCheck
{
public:
    enum class State
    {
        none,      // nothing asked yet, or no usable rate
        measuring, // asked; the measurement runs
        keepsUp,
        tooSlow,
        failed // the drum could not be built (treated as too slow)
    };

    struct Verdict
    {
        State state = State::none;
        KeepUpFigures figures;
    };

    // How a drum is measured: measureKeepUp, or a stand-in for another machine (tests: an
    // artificial slowdown, a cost model). Called on the check's thread with a render session
    // started on the drum in question.
    using Measurement = std::function<KeepUpFigures(DrumSession&, int blockSize, const std::function<bool()>& cancelled)>;

    KeepUpCheck() = default;
    ~KeepUpCheck();
    KeepUpCheck(const KeepUpCheck&) = delete;
    KeepUpCheck& operator=(const KeepUpCheck&) = delete;

    // Whether a drum built from `params` (with the snares on) keeps up at this rate in blocks of
    // blockSize. Returns at once: a verdict measured before for the same model (GridKey) and
    // block size (the question in measurement is left alone), or `measuring` (the measurement
    // is started on the check's thread; the newest such question replaces one whose measurement
    // has not finished). Thread-safe; not for the audio thread.
    Verdict ask(const ParameterSet& params, double sampleRate, int blockSize);

    // Measures with `m` from the next question on (an empty one: measureKeepUp). Thread-safe.
    void setMeasurement(Measurement m);

    // The verdict for the last question asked (measuring while it runs). Thread-safe.
    Verdict latest() const;

    // Measurements finished so far (for tests).
    int measurementsDone() const noexcept { return done.load(std::memory_order_relaxed); }

    // Stops the thread (a measurement in flight stops within a few hundred samples' compute).
    void stop();

private:
    struct Question
    {
        GridKey key;
        int blockSize = 0;
        bool operator==(const Question&) const = default;
    };
    struct Entry
    {
        Question question;
        Verdict verdict;
    };

    void run();
    const Verdict* findLocked(const Question& q) const;

    mutable std::mutex lock;
    std::condition_variable wake;
    std::thread thread;
    bool exitRequested = false;  // guarded by lock
    bool hasWanted = false;      // guarded by lock
    Question wanted;             // guarded by lock: the last question asked
    ParameterSet wantedParams;   // guarded by lock
    double wantedRate = 0.0;     // guarded by lock
    bool busy = false;           // guarded by lock: a measurement runs
    Question inFlight;           // guarded by lock: its question
    std::vector<Entry> verdicts; // guarded by lock: newest last, at most maxVerdicts
    Measurement measurement;     // guarded by lock: empty for measureKeepUp
    std::atomic<int> done { 0 };
    std::atomic<bool> cancel { false };

    static constexpr std::size_t maxVerdicts = 16;
};

} // namespace snaresim
