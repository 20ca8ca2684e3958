#include "KeepUp.h"

#include "DrumSession.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <span>

#if defined(__SSE__) || defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#define SNARESIM_HAVE_MXCSR 1
#endif

namespace snaresim
{

namespace
{
// Denormals flushed to zero while in scope, as the plug-in's processBlock runs (JUCE's
// ScopedNoDenormals; the engine has no JUCE).
class FlushDenormals
{
public:
#if SNARESIM_HAVE_MXCSR
    FlushDenormals() noexcept : saved(_mm_getcsr()) { _mm_setcsr(saved | 0x8040u); } // FTZ | DAZ
    ~FlushDenormals() { _mm_setcsr(saved); }

private:
    unsigned int saved;
#elif defined(__aarch64__) && defined(__GNUC__)
    FlushDenormals() noexcept : saved(__builtin_aarch64_get_fpcr()) { __builtin_aarch64_set_fpcr(saved | (1u << 24)); } // FZ
    ~FlushDenormals() { __builtin_aarch64_set_fpcr(saved); }

private:
    unsigned int saved;
#endif
};
} // namespace

bool keepsUp(const KeepUpFigures& f) noexcept
{
    return ! f.cutShort && f.audioSeconds > 0.0 && f.load <= kKeepUpMaxLoad && f.worstBlockShare <= kKeepUpMaxWorstBlock;
}

KeepUpFigures measureKeepUp(DrumSession& session, int blockSize, const std::function<bool()>& cancelled)
{
    using Clock = std::chrono::steady_clock;
    const FlushDenormals flush;

    KeepUpFigures f;
    blockSize = std::max(1, blockSize);
    f.blockSize = blockSize;
    const double rate = session.drumPlayer().sampleRate();
    if (session.drumPlayer().drum() == nullptr || ! (rate > 0.0))
        return f;

    const int probeSamples = (int) std::ceil(kProbeSeconds * rate);
    const int unstruckBlocks = std::max(1, (int) std::lround(0.2 * probeSamples / blockSize));
    const int blocks = std::max(unstruckBlocks + 2, (probeSamples + blockSize - 1) / blockSize);
    const auto cap = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kProbeComputeCapSeconds));
    constexpr int chunk = 256; // cancellation and the cap are looked at this often
    std::array<float, chunk> scratch {};

    session.releaseResources(); // from silence
    Clock::duration total {}, worst {};
    long rendered = 0;
    bool stopped = false;

    for (int b = 0; b < blocks && ! stopped; ++b)
    {
        Clock::duration block {};
        int done = 0;
        while (done < blockSize)
        {
            if ((cancelled && cancelled()) || total + block > cap)
            {
                stopped = true;
                f.cutShort = total + block > cap;
                break;
            }
            const int n = std::min(chunk, blockSize - done);
            const bool strike = b == unstruckBlocks && done == 0;
            const PlayerEvent note = PlayerEvent::noteOn(0, 38, 127);
            const auto start = Clock::now();
            session.process(scratch.data(), n, strike ? std::span(&note, 1) : std::span<const PlayerEvent> {});
            block += Clock::now() - start;
            done += n;
        }
        total += block;
        rendered += done;
        // A block cut short counts as a whole one only for its own share.
        if (done > 0)
            worst = std::max(worst, done == blockSize ? block : block * blockSize / done);
    }
    session.releaseResources();

    const double seconds = std::chrono::duration<double>(total).count();
    f.audioSeconds = (double) rendered / rate;
    f.load = f.audioSeconds > 0.0 ? seconds / f.audioSeconds : 0.0;
    f.worstBlockShare = std::chrono::duration<double>(worst).count() / ((double) blockSize / rate);
    return f;
}

//==============================================================================
KeepUpCheck::~KeepUpCheck() { stop(); }

void KeepUpCheck::stop()
{
    {
        const std::lock_guard<std::mutex> g(lock);
        exitRequested = true;
        cancel.store(true);
    }
    wake.notify_all();
    if (thread.joinable())
        thread.join();
}

const KeepUpCheck::Verdict* KeepUpCheck::findLocked(const Question& q) const
{
    for (const auto& e : verdicts)
        if (e.question == q)
            return &e.verdict;
    return nullptr;
}

KeepUpCheck::Verdict KeepUpCheck::ask(const ParameterSet& params, double sampleRate, int blockSize)
{
    if (! (sampleRate > 0.0) || ! std::isfinite(sampleRate) || blockSize <= 0)
        return {};

    const Question q { GridKey::of(params, sampleRate), blockSize };
    const std::lock_guard<std::mutex> g(lock);

    if (const auto* known = findLocked(q))
        return *known;

    const bool changed = ! hasWanted || ! (wanted == q);
    wanted = q;
    hasWanted = true;
    wantedParams = params;
    wantedRate = sampleRate;

    // A measurement of another question is no longer wanted.
    if (changed && busy && ! (inFlight == q))
        cancel.store(true);

    if (exitRequested)
        return {};

    if (changed)
    {
        if (! thread.joinable())
        {
            try
            {
                thread = std::thread([this] { run(); });
            }
            catch (const std::exception&)
            {
                return {}; // no thread to measure on: nothing is known
            }
        }
        wake.notify_all();
    }

    Verdict v;
    v.state = State::measuring;
    return v;
}

void KeepUpCheck::setMeasurement(Measurement m)
{
    const std::lock_guard<std::mutex> g(lock);
    measurement = std::move(m);
}

KeepUpCheck::Verdict KeepUpCheck::latest() const
{
    const std::lock_guard<std::mutex> g(lock);
    if (! hasWanted)
        return {};
    if (const auto* known = findLocked(wanted))
        return *known;
    Verdict v;
    v.state = exitRequested ? State::none : State::measuring;
    return v;
}

void KeepUpCheck::run()
{
    std::unique_lock<std::mutex> g(lock);

    for (;;)
    {
        wake.wait(g, [this] { return exitRequested || (hasWanted && findLocked(wanted) == nullptr); });
        if (exitRequested)
            return;

        const Question q = wanted;
        // The snares on: the costlier case, and a live change (notes 33 / 34 throw them off and
        // on without a new model), so the verdict must hold for it.
        ParameterSet params = wantedParams;
        params.setClamped(ParamId::snaresEngaged, 1.0);
        const double rate = wantedRate;
        inFlight = q;
        busy = true;
        cancel.store(false);
        const Measurement measure = measurement ? measurement : Measurement(&measureKeepUp);
        g.unlock();

        Verdict v;
        bool finished = true;
        try
        {
            // The drum as a host plays it: a session of its own (built with buildDrum), its parameters as asked.
            DrumSession probe(DrumSession::Mode::render);
            probe.setParameters(params);
            probe.prepareAndStart(rate, q.blockSize);
            if (cancel.load())
                finished = false;
            else
            {
                v.figures = measure(probe, q.blockSize, [this] { return cancel.load(std::memory_order_relaxed); });
                finished = ! cancel.load() || v.figures.cutShort;
                v.state = keepsUp(v.figures) ? State::keepsUp : State::tooSlow;
            }
        }
        catch (const std::exception&)
        {
            // Cannot be built here (out of memory, or a configuration the engine refuses).
            v.state = State::failed;
        }

        g.lock();
        busy = false;
        if (finished && findLocked(q) == nullptr)
        {
            if (verdicts.size() >= maxVerdicts)
                verdicts.erase(verdicts.begin());
            verdicts.push_back({ q, v });
            done.fetch_add(1, std::memory_order_relaxed);
        }
    }
}

} // namespace snaresim
