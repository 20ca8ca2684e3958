#include "DrumPlayer.h"

#include "DrumConfig.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <utility>

namespace snaresim
{

//==============================================================================
// Ramps: linear, as a host's parameter smoother (the same arithmetic step by step).

void DrumPlayer::Ramp::reset(int lengthInSamples, double value) noexcept
{
    length = lengthInSamples;
    current = target = value;
    remaining = 0;
}

void DrumPlayer::Ramp::setTarget(double value) noexcept
{
    if (value == target)
        return;
    if (length <= 0)
    {
        current = target = value;
        remaining = 0;
        return;
    }
    target = value;
    remaining = length;
    step = (target - current) / (double) remaining;
}

double DrumPlayer::Ramp::skip(int numSamples) noexcept
{
    if (numSamples >= remaining)
    {
        current = target;
        remaining = 0;
        return target;
    }
    current += step * (double) numSamples;
    remaining -= numSamples;
    return current;
}

//==============================================================================
DrumPlayer::DrumPlayer(ModelBuilder::ParameterReader readParameters, BuildOptions options) : builder(std::move(readParameters), options)
{
    for (const auto& spec : parameterSpecs())
        smoothed[static_cast<std::size_t>(spec.id)] = spec.kind == ParamKind::continuous && ! spec.rebuildsModel();
}

DrumPlayer::~DrumPlayer()
{
    builder.stop();
    delete fading;
    delete current;
    for (auto*& m : retireBacklog)
        delete std::exchange(m, nullptr);
    // The builder's pending slot and retire queue delete what they still hold.
}

DrumPlayer::Preparation::~Preparation() = default;

DrumPlayer::Preparation DrumPlayer::prepare(double sampleRate, const ParameterSet& params, OnBuildFailure onFailure)
{
    const bool usableRate = sampleRate > 0.0 && std::isfinite(sampleRate);
    const double newRate = usableRate ? sampleRate : 0.0;

    builder.start();

    // No background build runs while the preparation holds the builder's lock.
    Preparation p(builder.getLock());
    p.player = this;
    p.params = params;
    p.key = GridKey::of(params, newRate);

    std::unique_ptr<DrumModel> pending(builder.pending.take());
    p.keepCurrent = current != nullptr && current->requested == p.key;

    if (! p.keepCurrent)
    {
        if (pending != nullptr && pending->requested == p.key)
            p.fresh = std::move(pending);
        else
        {
            try
            {
                p.fresh = buildModel(params, newRate, builder.options(), onFailure);
            }
            catch (const std::invalid_argument&)
            {
                throw; // OnBuildFailure::raise: the caller reports it
            }
            catch (const std::exception&)
            {
                // Out of memory: keep playing what there is.
            }
        }
    }
    if (pending != nullptr)
        p.old.push_back(std::move(pending));
    return p;
}

void DrumPlayer::start(Preparation& p) noexcept
{
    if (p.fresh != nullptr)
    {
        p.old.emplace_back(current);
        current = p.fresh.release();
        modelSwaps.fetch_add(1, std::memory_order_relaxed);
    }

    p.old.emplace_back(std::exchange(fading, nullptr));
    for (auto*& m : retireBacklog)
        p.old.emplace_back(std::exchange(m, nullptr));

    for (const auto& m : p.old)
        if (m != nullptr && m->drum != nullptr)
        {
            retiredFallbacks += m->drum->solverStats().fallbacks;
            retiredMaxIterations = std::max(retiredMaxIterations, m->drum->solverStats().maxIterations);
        }

    rate = current != nullptr ? current->sampleRate() : 0.0;
    fellBackNow.store(current != nullptr && current->fellBack, std::memory_order_relaxed);
    publishLatency();
    fadeLength = std::max(1, (int) std::lround(crossfadeSeconds * rate));
    fadePosition = 0;
    quietSamples = 1 << 30; // the drum starts quiet (new or reset below)
    snapshotInterval = std::max(1, (int) std::lround(rate / 30.0));
    samplesSinceSnapshot = 0;
    samplesSinceFiniteCheck = 0;

    // Start from the parameters as they are now, without ramps.
    liveParameters = p.params;
    const int rampLength = (int) std::floor(smoothingSeconds * std::max(rate, 1.0));
    for (const auto& spec : parameterSpecs())
        ramps[static_cast<std::size_t>(spec.id)].reset(rampLength, p.params.get(spec.id));
    lastSnaresParameter = p.params.get(ParamId::snaresEngaged);
    snaresEngaged = lastSnaresParameter >= 0.5;
    liveDirty = true;

    // Playback starts from a quiet drum (a kept one may still ring from before).
    if (p.keepCurrent && current != nullptr)
        current->silence();

    builder.setTargetLocked(rate, current != nullptr ? current->requested : p.key);
}

void DrumPlayer::releaseResources() noexcept
{
    for (auto* m : { current, fading })
        if (m != nullptr)
            m->silence();
}

//==============================================================================
// Audio thread: models

void DrumPlayer::retire(DrumModel* model) noexcept
{
    if (model == nullptr)
        return;

    if (model->drum != nullptr)
    {
        const auto& stats = model->drum->solverStats();
        retiredFallbacks += stats.fallbacks;
        retiredMaxIterations = std::max(retiredMaxIterations, stats.maxIterations);
    }

    if (builder.retired.tryPush(model))
        return;

    for (auto& slot : retireBacklog)
        if (slot == nullptr)
        {
            slot = model;
            return;
        }

    // Cannot happen (one model arrives per background build, and the builder empties the
    // queue between builds); should it, leaking a model beats freeing on the audio thread.
}

void DrumPlayer::flushRetireBacklog() noexcept
{
    for (auto& slot : retireBacklog)
        if (slot != nullptr && builder.retired.tryPush(slot))
            slot = nullptr;
}

void DrumPlayer::installPendingModel() noexcept
{
    if (fading != nullptr || builder.pending.isEmpty())
        return; // one crossfade at a time: a newer model waits in the slot

    DrumModel* next = builder.pending.take();
    if (next == nullptr)
        return;

    if (next->sampleRate() != rate)
    {
        retire(next); // built for a rate this player no longer runs at
        return;
    }

    if (current != nullptr && current->drum != nullptr && quietSamples < fadeLength)
    {
        fading = current; // both run while the new one fades in
        fadePosition = 0;
    }
    else
    {
        retire(current); // silent (or no drum): nothing to fade
    }

    current = next;
    modelSwaps.fetch_add(1, std::memory_order_relaxed);
    fellBackNow.store(next->fellBack, std::memory_order_relaxed);
    publishLatency();
    liveDirty = true; // the new drum takes the live values (and the snares state) at once
}

void DrumPlayer::publishLatency() noexcept
{
    latencyNow.store(current != nullptr ? current->latencySamples() : 0, std::memory_order_relaxed);
}

//==============================================================================
// Audio thread: parameters

void DrumPlayer::setTarget(ParamId id, double raw) noexcept
{
    const auto& s = spec(id);
    const auto i = static_cast<std::size_t>(id);
    const double v = sanitise(s, raw);

    if (smoothed[i])
    {
        ramps[i].setTarget(v);
    }
    else if (s.rebuildsModel())
    {
        // The model's own value is used until the background thread delivers a new model.
    }
    else if (id == ParamId::snaresEngaged)
    {
        // A change of the parameter wins over the last snares off / on note.
        if (v != lastSnaresParameter)
        {
            lastSnaresParameter = v;
            snaresEngaged = v >= 0.5;
            liveDirty = true;
        }
    }
    else if (liveParameters.get(id) != v)
    {
        liveParameters.setClamped(id, v);
        liveDirty = true;
    }
}

void DrumPlayer::advanceParameters(int numSamples) noexcept
{
    for (const auto& s : parameterSpecs())
    {
        const auto i = static_cast<std::size_t>(s.id);
        if (smoothed[i] && ramps[i].moving())
        {
            liveParameters.setClamped(s.id, ramps[i].skip(numSamples));
            liveDirty = true;
        }
    }

    if (! liveDirty || current == nullptr || current->drum == nullptr)
        return;

    auto params = liveParameters;
    for (const auto& s : parameterSpecs())
        if (s.rebuildsModel())
            params.setClamped(s.id, current->built.get(s.id));
    params.setClamped(ParamId::snaresEngaged, snaresEngaged ? 1.0 : 0.0);

    auto& d = *current->drum;
    const auto cfg = mapParameters(params, d.sampleRate(), builder.options());
    d.applyLive(cfg);

    liveDirty = false;
}

//==============================================================================
// Audio thread: events and rendering

void DrumPlayer::applyEvent(const PlayerEvent& event) noexcept
{
    switch (event.type)
    {
        case PlayerEvent::Type::noteOn:
            // The articulation map and the velocity curve live in the drum. A note never
            // resets it; during a crossfade both models play it.
            for (auto* m : { current, fading })
                if (m != nullptr && m->drum != nullptr)
                    m->drum->playNote(event.note, event.velocity);

            // "Snares off / on" notes hold until the snares_engaged parameter next changes.
            if (current != nullptr && current->drum != nullptr)
                snaresEngaged = current->drum->snaresEngaged();

            quietSamples = 0;
            break;

        case PlayerEvent::Type::strike:
            for (auto* m : { current, fading })
                if (m != nullptr && m->drum != nullptr)
                    m->drum->strikeAtDefaultPoint(strikeSpeedFromVelocity(event.velocity, m->drum->config().strikeSpeedMax_m_per_s));
            quietSamples = 0;
            break;

        case PlayerEvent::Type::allSoundOff:
            for (auto* m : { current, fading })
                if (m != nullptr)
                    m->silence();
            break;

        case PlayerEvent::Type::parameter:
            if (static_cast<std::size_t>(event.parameter) < kNumParameters)
                setTarget(event.parameter, event.value);
            break;
    }
}

bool DrumPlayer::renderModel(DrumModel& model, float* out, int numSamples, StepObserver* observer) noexcept
{
    if (model.drum == nullptr)
    {
        std::fill(out, out + numSamples, 0.0f);
        return true;
    }

    auto& d = *model.drum;
    if (observer == nullptr)
        d.process(out, numSamples);
    else
        for (int i = 0; i < numSamples; ++i)
        {
            out[i] = (float) d.step();
            observer->afterStep(d);
        }

    bool finite = true;
    for (int i = 0; i < numSamples; ++i)
        finite = finite && std::isfinite(out[i]);

    if (! finite)
    {
        // The simulation blew up: reset it quietly and output silence for this chunk.
        d.reset();
        std::fill(out, out + numSamples, 0.0f);
        resetsNow.fetch_add(1, std::memory_order_relaxed);
    }
    model.pad.process(out, numSamples);
    return finite;
}

void DrumPlayer::renderSubBlock(float* out, int numSamples, StepObserver* observer) noexcept
{
    advanceParameters(numSamples);

    if (current != nullptr)
        renderModel(*current, out, numSamples, observer);
    else
        std::fill(out, out + numSamples, 0.0f);

    if (fading != nullptr)
    {
        float* old = fadeScratch.data();
        renderModel(*fading, old, numSamples, nullptr);

        const float step = 1.0f / (float) fadeLength;
        for (int i = 0; i < numSamples; ++i)
        {
            const float g = std::min(1.0f, (float) (fadePosition + i + 1) * step);
            out[i] = g * out[i] + (1.0f - g) * old[i];
        }

        fadePosition += numSamples;
        if (fadePosition >= fadeLength)
        {
            retire(std::exchange(fading, nullptr));
            liveDirty = true;
        }
    }

    // A state that went non-finite without reaching the output yet (checked now and then:
    // the scan costs about a sample's worth of work).
    samplesSinceFiniteCheck += numSamples;
    if (samplesSinceFiniteCheck >= 1024)
    {
        samplesSinceFiniteCheck = 0;
        if (current != nullptr && current->drum != nullptr && ! current->drum->isFinite())
        {
            current->silence();
            resetsNow.fetch_add(1, std::memory_order_relaxed);
            std::fill(out, out + numSamples, 0.0f);
        }
    }

    // Never pass non-finite or subnormal values on (NaN fails the comparison too).
    float peak = 0.0f;
    for (int i = 0; i < numSamples; ++i)
    {
        if (! (std::abs(out[i]) >= 1.0e-30f) || ! std::isfinite(out[i]))
            out[i] = 0.0f;
        peak = std::max(peak, std::abs(out[i]));
    }

    // Below -180 dB for a whole crossfade: a new model can then replace this one at once.
    quietSamples = peak < 1.0e-9f ? std::min(quietSamples + numSamples, 1 << 30) : 0;

    samplesSinceSnapshot += numSamples;
    if (samplesSinceSnapshot >= snapshotInterval)
    {
        samplesSinceSnapshot = 0;
        if (current != nullptr && current->drum != nullptr)
        {
            current->drum->fillSnapshot(snapshots.back());
            snapshots.publish();
        }
    }
}

void DrumPlayer::renderRange(float* out, int numSamples, StepObserver* observer) noexcept
{
    // Sub-blocks of at most subBlockSize samples: parameters move at least this often.
    while (numSamples > 0)
    {
        const int n = std::min(numSamples, subBlockSize);
        renderSubBlock(out, n, observer);
        out += n;
        numSamples -= n;
    }
}

void DrumPlayer::process(float* out, int n, std::span<const PlayerEvent> events, StepObserver* observer) noexcept
{
    const auto started = std::chrono::steady_clock::now();

    flushRetireBacklog();
    installPendingModel();

    int position = 0;
    n = std::max(0, n);

    // Split the block at every event so that each takes effect on its own sample.
    for (const auto& event : events)
    {
        const int at = std::clamp(event.sample, position, n);
        if (at > position)
        {
            renderRange(out + position, at - position, observer);
            position = at;
        }
        applyEvent(event);
    }

    if (n > position)
        renderRange(out + position, n - position, observer);

    publishStats();
    updateCpuLoad(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), n);
}

//==============================================================================
// Counters

void DrumPlayer::publishStats() noexcept
{
    long fallbacks = retiredFallbacks;
    int iterations = retiredMaxIterations;

    for (auto* m : { current, fading })
        if (m != nullptr && m->drum != nullptr)
        {
            const auto& stats = m->drum->solverStats();
            fallbacks += stats.fallbacks;
            iterations = std::max(iterations, stats.maxIterations);
        }

    fallbacksNow.store(fallbacks, std::memory_order_relaxed);
    iterationsNow.store(iterations, std::memory_order_relaxed);
}

void DrumPlayer::updateCpuLoad(double elapsed, int numSamples) noexcept
{
    if (numSamples <= 0 || rate <= 0.0)
        return;

    const double budget = (double) numSamples / rate;
    const double load = elapsed / budget;

    // Smoothed over about a quarter of a second of audio; the peak decays over about 2 s.
    smoothedLoad += (1.0 - std::exp(-budget / 0.25)) * (load - smoothedLoad);
    peakLoad = std::max(load, peakLoad * std::exp(-budget / 2.0));

    cpuLoadNow.store((float) smoothedLoad, std::memory_order_relaxed);
    peakCpuLoadNow.store((float) peakLoad, std::memory_order_relaxed);
}

bool DrumPlayer::pullSnapshot(DrumSnapshot& out)
{
    if (! snapshots.take())
        return false;

    out = snapshots.front();
    return true;
}

} // namespace snaresim
