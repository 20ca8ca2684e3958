#include "PluginProcessor.h"
#include "PluginEditor.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "ParameterLayout.h"
#include "PluginState.h"
#include "Presets.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>


//==============================================================================
SnareSimAudioProcessor::SnareSimAudioProcessor()
    : AudioProcessor (BusesProperties().withOutput ("Output", juce::AudioChannelSet::stereo(), true)),
      apvts (*this, nullptr, snaresim::plugin::PluginState::treeType, snaresim::plugin::createParameterLayout()),
      builder ([this] { return currentParameters(); })
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto i = static_cast<std::size_t> (spec.id);
        auto* raw = apvts.getRawParameterValue (juce::String (std::string (spec.key)));
        jassert (raw != nullptr);
        rawParameters[i] = raw;
        smoothed[i] = spec.kind == snaresim::ParamKind::continuous && ! spec.needsNewGrid;
    }
}

SnareSimAudioProcessor::~SnareSimAudioProcessor()
{
    cancelPendingUpdate();
    builder.stop();

    delete fading;
    delete current;
    for (auto*& m : retireBacklog)
        delete std::exchange (m, nullptr);
    // The builder's pending slot and retire queue delete what they still hold.
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

const snaresim::Drum* SnareSimAudioProcessor::getDrum() const noexcept
{
    return current != nullptr ? current->drum.get() : nullptr;
}

//==============================================================================
void SnareSimAudioProcessor::prepareToPlay (double newSampleRate, int /*maximumExpectedSamplesPerBlock*/)
{
    // The processor renders in sub-blocks of at most subBlockSize samples into fixed scratch
    // arrays, so the announced block size needs no allocation and larger blocks just work.
    const bool usableRate = newSampleRate > 0.0 && std::isfinite (newSampleRate);
    const double rate = usableRate ? newSampleRate : 0.0;

    builder.start();

    const auto params = currentParameters();
    const auto key = snaresim::plugin::GridKey::of (params, rate);

    std::unique_ptr<DrumModel> oldCurrent, oldFading, fresh;
    std::array<DrumModel*, 16> oldBacklog {};

    {
        // No background build runs while this holds the builder's lock.
        const juce::ScopedLock builderLock (builder.getLock());
        std::unique_ptr<DrumModel> pending (builder.pending.take());

        const bool keepCurrent = current != nullptr && current->requested == key;

        if (! keepCurrent)
        {
            if (pending != nullptr && pending->requested == key)
                fresh = std::move (pending);
            else
            {
                try
                {
                    fresh = snaresim::plugin::buildModel (params, rate);
                }
                catch (const std::exception&)
                {
                    // Out of memory: keep playing what there is.
                }
            }
        }

        {
            const juce::ScopedLock sl (getCallbackLock());

            if (fresh != nullptr)
            {
                oldCurrent.reset (current);
                current = fresh.release();
                modelSwaps.fetch_add (1);
            }

            oldFading.reset (fading);
            fading = nullptr;
            std::swap (oldBacklog, retireBacklog);

            for (auto* m : { oldCurrent.get(), oldFading.get() })
                if (m != nullptr && m->drum != nullptr)
                {
                    retiredFallbacks += m->drum->solverStats().fallbacks;
                    retiredMaxIterations = juce::jmax (retiredMaxIterations, m->drum->solverStats().maxIterations);
                }

            sampleRate = current != nullptr ? current->sampleRate() : 0.0;
            fellBackToDefaults.store (current != nullptr && current->fellBack);
            fadeLength = juce::jmax (1, (int) std::lround (crossfadeSeconds * sampleRate));
            fadePosition = 0;
            quietSamples = 1 << 30;     // the drum starts quiet (new or reset below)
            snapshotInterval = juce::jmax (1, (int) std::lround (sampleRate / 30.0));
            samplesSinceSnapshot = 0;
            samplesSinceFiniteCheck = 0;

            // Start from the parameters as they are now, without ramps.
            liveParameters = params;
            for (const auto& spec : snaresim::parameterSpecs())
            {
                const auto i = static_cast<std::size_t> (spec.id);
                smoothers[i].reset (juce::jmax (sampleRate, 1.0), smoothingSeconds);
                smoothers[i].setCurrentAndTargetValue (params.get (spec.id));
            }
            lastSnaresParameter = (float) params.get (snaresim::ParamId::snaresEngaged);
            snaresEngaged = lastSnaresParameter >= 0.5f;
            liveDirty = true;

            // Playback starts from a quiet drum (a kept one may still ring from before).
            if (keepCurrent && current->drum != nullptr)
                current->drum->reset();
        }

        builder.setTargetLocked (sampleRate, current != nullptr ? current->requested : key);
    }

    for (auto* m : oldBacklog)
        delete m;
    // oldCurrent and oldFading are deleted here, outside both locks.
}

void SnareSimAudioProcessor::releaseResources()
{
    const juce::ScopedLock sl (getCallbackLock());

    for (auto* m : { current, fading })
        if (m != nullptr && m->drum != nullptr)
            m->drum->reset();
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
// Audio thread: models

void SnareSimAudioProcessor::retire (DrumModel* model) noexcept
{
    if (model == nullptr)
        return;

    if (model->drum != nullptr)
    {
        const auto& stats = model->drum->solverStats();
        retiredFallbacks += stats.fallbacks;
        retiredMaxIterations = juce::jmax (retiredMaxIterations, stats.maxIterations);
    }

    if (builder.retired.tryPush (model))
        return;

    for (auto& slot : retireBacklog)
        if (slot == nullptr)
        {
            slot = model;
            return;
        }

    // Cannot happen (one model arrives per background build, and the builder empties the
    // queue between builds); should it, leaking a model beats freeing on the audio thread.
    jassertfalse;
}

void SnareSimAudioProcessor::flushRetireBacklog() noexcept
{
    for (auto& slot : retireBacklog)
        if (slot != nullptr && builder.retired.tryPush (slot))
            slot = nullptr;
}

void SnareSimAudioProcessor::installPendingModel() noexcept
{
    if (fading != nullptr || builder.pending.isEmpty())
        return;     // one crossfade at a time: a newer model waits in the slot

    DrumModel* next = builder.pending.take();
    if (next == nullptr)
        return;

    if (next->sampleRate() != sampleRate)
    {
        retire (next);  // built for a rate this processor no longer runs at
        return;
    }

    if (current != nullptr && current->drum != nullptr && quietSamples < fadeLength)
    {
        fading = current;       // both run while the new one fades in
        fadePosition = 0;
    }
    else
    {
        retire (current);       // silent (or no drum): nothing to fade
    }

    current = next;
    modelSwaps.fetch_add (1, std::memory_order_relaxed);
    fellBackToDefaults.store (next->fellBack, std::memory_order_relaxed);
    liveDirty = true;   // the new drum takes the live values (and the snares state) at once
}

//==============================================================================
// Audio thread: parameters


void SnareSimAudioProcessor::readParameterTargets() noexcept
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto i = static_cast<std::size_t> (spec.id);
        const float raw = rawParameters[i]->load (std::memory_order_relaxed);
        const double v = snaresim::plugin::sanitise (spec, (double) raw);

        if (smoothed[i])
        {
            if (v != smoothers[i].getTargetValue())
                smoothers[i].setTargetValue (v);
        }
        else if (spec.needsNewGrid)
        {
            // The model's own value is used until the background thread delivers a new model.
        }
        else if (spec.id == snaresim::ParamId::snaresEngaged)
        {
            // A change of the parameter wins over the last snares off / on note.
            if ((float) v != lastSnaresParameter)
            {
                lastSnaresParameter = (float) v;
                snaresEngaged = v >= 0.5;
                liveDirty = true;
            }
        }
        else if (liveParameters.get (spec.id) != v)
        {
            liveParameters.setClamped (spec.id, v);
            liveDirty = true;
        }
    }
}

void SnareSimAudioProcessor::advanceParameters (int numSamples) noexcept
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto i = static_cast<std::size_t> (spec.id);
        if (smoothed[i] && smoothers[i].isSmoothing())
        {
            liveParameters.setClamped (spec.id, smoothers[i].skip (numSamples));
            liveDirty = true;
        }
    }

    if (! liveDirty || current == nullptr || current->drum == nullptr)
        return;

    auto params = liveParameters;
    for (const auto& spec : snaresim::parameterSpecs())
        if (spec.needsNewGrid)
            params.setClamped (spec.id, current->built.get (spec.id));
    params.setClamped (snaresim::ParamId::snaresEngaged, snaresEngaged ? 1.0 : 0.0);

    auto& drum = *current->drum;
    const auto cfg = snaresim::mapParameters (params, drum.sampleRate());
    if (drum.canApplyLive (cfg))
        drum.applyLive (cfg);

    liveDirty = false;
}

//==============================================================================
// Audio thread: MIDI and rendering

void SnareSimAudioProcessor::handleMidiMessage (const juce::MidiMessage& message) noexcept
{
    if (message.isNoteOn())
    {
        // The articulation map and the velocity curve live in the engine. A note never resets
        // the drum; during a crossfade both models play it.
        for (auto* m : { current, fading })
            if (m != nullptr && m->drum != nullptr)
                m->drum->playNote (message.getNoteNumber(), message.getVelocity());

        // "Snares off / on" notes hold until the snares_engaged parameter next changes.
        if (current != nullptr && current->drum != nullptr)
            snaresEngaged = current->drum->snaresEngaged();

        quietSamples = 0;
    }
    else if (message.isAllSoundOff())
    {
        for (auto* m : { current, fading })
            if (m != nullptr && m->drum != nullptr)
                m->drum->reset();
    }
    // Note-offs, all-notes-off (the drum rings on, as a real one does) and reset-all-controllers
    // do nothing.
}

bool SnareSimAudioProcessor::renderModel (DrumModel& model, float* out, int numSamples) noexcept
{
    if (model.drum == nullptr)
    {
        std::fill (out, out + numSamples, 0.0f);
        return true;
    }

    model.drum->process (out, numSamples);

    bool finite = true;
    for (int i = 0; i < numSamples; ++i)
        finite = finite && std::isfinite (out[i]);

    if (finite)
        return true;

    // The simulation blew up: reset it quietly and output silence for this chunk.
    model.drum->reset();
    std::fill (out, out + numSamples, 0.0f);
    nonFiniteResets.fetch_add (1, std::memory_order_relaxed);
    return false;
}

void SnareSimAudioProcessor::renderSubBlock (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept
{
    jassert (numSamples <= subBlockSize);
    advanceParameters (numSamples);

    float* out = renderScratch.data();

    if (current != nullptr)
        renderModel (*current, out, numSamples);
    else
        std::fill (out, out + numSamples, 0.0f);

    if (fading != nullptr)
    {
        float* old = fadeScratch.data();
        renderModel (*fading, old, numSamples);

        const float step = 1.0f / (float) fadeLength;
        for (int i = 0; i < numSamples; ++i)
        {
            const float g = juce::jmin (1.0f, (float) (fadePosition + i + 1) * step);
            out[i] = g * out[i] + (1.0f - g) * old[i];
        }

        fadePosition += numSamples;
        if (fadePosition >= fadeLength)
        {
            retire (std::exchange (fading, nullptr));
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
            current->drum->reset();
            nonFiniteResets.fetch_add (1, std::memory_order_relaxed);
            std::fill (out, out + numSamples, 0.0f);
        }
    }

    // Never pass non-finite or subnormal values on (NaN fails the comparison too).
    float peak = 0.0f;
    for (int i = 0; i < numSamples; ++i)
    {
        if (! (std::abs (out[i]) >= 1.0e-30f) || ! std::isfinite (out[i]))
            out[i] = 0.0f;
        peak = juce::jmax (peak, std::abs (out[i]));
    }

    // Below -180 dB for a whole crossfade: a new model can then replace this one at once.
    quietSamples = peak < 1.0e-9f ? juce::jmin (quietSamples + numSamples, 1 << 30) : 0;

    for (int ch = 0; ch < buffer.getNumChannels(); ++ch)
        juce::FloatVectorOperations::copy (buffer.getWritePointer (ch, startSample), out, numSamples);

    samplesSinceSnapshot += numSamples;
    if (samplesSinceSnapshot >= snapshotInterval)
    {
        samplesSinceSnapshot = 0;
        if (current != nullptr && current->drum != nullptr)
        {
            current->drum->fillSnapshot (snapshots.back());
            snapshots.publish();
        }
    }
}

void SnareSimAudioProcessor::renderRange (juce::AudioBuffer<float>& buffer, int startSample, int numSamples) noexcept
{
    // Sub-blocks of at most subBlockSize samples: parameters move at least this often, and
    // any block size works with the fixed scratch arrays.
    while (numSamples > 0)
    {
        const int n = juce::jmin (numSamples, subBlockSize);
        renderSubBlock (buffer, startSample, n);
        startSample += n;
        numSamples -= n;
    }
}

void SnareSimAudioProcessor::publishStats() noexcept
{
    long fallbacks = retiredFallbacks;
    int iterations = retiredMaxIterations;

    for (auto* m : { current, fading })
        if (m != nullptr && m->drum != nullptr)
        {
            const auto& stats = m->drum->solverStats();
            fallbacks += stats.fallbacks;
            iterations = juce::jmax (iterations, stats.maxIterations);
        }

    solverFallbacks.store (fallbacks, std::memory_order_relaxed);
    maxNewtonIterations.store (iterations, std::memory_order_relaxed);
}

void SnareSimAudioProcessor::updateCpuLoad (juce::int64 startTicks, int numSamples) noexcept
{
    if (numSamples <= 0 || sampleRate <= 0.0)
        return;

    const double elapsed = juce::Time::highResolutionTicksToSeconds (juce::Time::getHighResolutionTicks() - startTicks);
    const double budget = (double) numSamples / sampleRate;
    const double load = elapsed / budget;

    // Smoothed over about a quarter of a second of audio; the peak decays over about 2 s.
    smoothedLoad += (1.0 - std::exp (-budget / 0.25)) * (load - smoothedLoad);
    peakLoad = juce::jmax (load, peakLoad * std::exp (-budget / 2.0));

    cpuLoad.store ((float) smoothedLoad, std::memory_order_relaxed);
    peakCpuLoad.store ((float) peakLoad, std::memory_order_relaxed);
}

void SnareSimAudioProcessor::processBlock (juce::AudioBuffer<float>& buffer, juce::MidiBuffer& midiMessages)
{
    juce::ScopedNoDenormals noDenormals;
    // Which thread is inside processBlock (no thread_local: in a plug-in loaded with dlopen its
    // first use on a thread may allocate).
    processingThread.store (juce::Thread::getCurrentThreadId(), std::memory_order_relaxed);
    const auto startTicks = juce::Time::getHighResolutionTicks();

    flushRetireBacklog();
    installPendingModel();
    readParameterTargets();

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

    publishStats();
    updateCpuLoad (startTicks, numSamples);
    processingThread.store (nullptr, std::memory_order_relaxed);
}

//==============================================================================
bool SnareSimAudioProcessor::pullSnapshot (snaresim::DrumSnapshot& out)
{
    if (! snapshots.take())
        return false;

    out = snapshots.front();
    return true;
}

//==============================================================================
juce::AudioProcessorEditor* SnareSimAudioProcessor::createEditor()
{
    return new SnareSimAudioProcessorEditor (*this);
}

//==============================================================================
// Programs: the factory presets

int SnareSimAudioProcessor::getNumPrograms()
{
    return (int) snaresim::factoryPresets().size();
}

int SnareSimAudioProcessor::getCurrentProgram()
{
    return currentProgram.load();
}

const juce::String SnareSimAudioProcessor::getProgramName (int index)
{
    const auto presets = snaresim::factoryPresets();
    if (index < 0 || index >= (int) presets.size())
        return {};

    return juce::String (std::string (presets[(size_t) index].name));
}

void SnareSimAudioProcessor::setCurrentProgram (int index)
{
    if (index < 0 || index >= getNumPrograms())
        return;

    currentProgram.store (index);

    // Applied at once, on the calling thread: hosts call this from their own UI or state thread,
    // which is often not JUCE's message thread in a plug-in on Linux, and may save the state
    // right after. Only a call from inside processBlock is deferred to the message thread.
    if (processingThread.load (std::memory_order_relaxed) != juce::Thread::getCurrentThreadId())
    {
        applyProgram (index);
    }
    else
    {
        programToApply.store (index);
        triggerAsyncUpdate();
    }
}

void SnareSimAudioProcessor::handleAsyncUpdate()
{
    const int index = programToApply.exchange (-1);
    if (index >= 0)
        applyProgram (index);
}

void SnareSimAudioProcessor::applyProgram (int index)
{
    const auto presets = snaresim::factoryPresets();
    if (index < 0 || index >= (int) presets.size())
        return;

    // The preset's values over the defaults.
    snaresim::ParameterSet values;
    for (const auto& [id, value] : presets[(size_t) index].values)
        values.setClamped (id, value);

    for (const auto& spec : snaresim::parameterSpecs())
    {
        if (auto* p = apvts.getParameter (juce::String (std::string (spec.key))))
        {
            const float normalised = p->convertTo0to1 ((float) values.get (spec.id));
            if (p->getValue() != normalised)
            {
                p->beginChangeGesture();
                p->setValueNotifyingHost (normalised);
                p->endChangeGesture();
            }
        }
    }

    // A new grid, if the program needs one, is built now: the next block plays it.
    builder.buildNowIfNeeded();
}

//==============================================================================
// State: the APVTS tree as XML, with a version attribute.

void SnareSimAudioProcessor::getStateInformation (juce::MemoryBlock& destData)
{
    snaresim::plugin::PluginState::write (apvts, destData);
}

void SnareSimAudioProcessor::setStateInformation (const void* data, int sizeInBytes)
{
    // A new grid, if the state needs one, is built now: the next block plays it.
    if (snaresim::plugin::PluginState::read (apvts, data, sizeInBytes))
        builder.buildNowIfNeeded();
}

//==============================================================================
// This creates new instances of the plug-in.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter()
{
    return new SnareSimAudioProcessor();
}
