#include "PluginProcessor.h"
#include "PluginEditor.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "Presets.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <utility>

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
      apvts (*this, nullptr, stateTreeType, createParameterLayout()),
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

const snaresim::Drum* SnareSimAudioProcessor::getDrum() const noexcept
{
    return current != nullptr ? current->drum.get() : nullptr;
}

double SnareSimAudioProcessor::dampingFromDecay (double t60) noexcept
{
    if (! std::isfinite (t60) || t60 <= 0.0)
        return snaresim::spec (snaresim::ParamId::damping).defaultValue;

    return std::clamp (100.0 * std::log (t60 / 4.0) / std::log (0.15 / 4.0), 0.0, 100.0);
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

namespace
{
// A parameter value from the host, made safe for the engine: finite, in range, whole for
// toggles, choices and integers.
double sanitise (const snaresim::ParameterSpec& spec, float raw) noexcept
{
    double v = std::isfinite (raw) ? std::clamp ((double) raw, spec.minValue, spec.maxValue) : spec.defaultValue;
    if (spec.kind != snaresim::ParamKind::continuous)
        v = std::round (v);
    return v;
}
} // namespace

void SnareSimAudioProcessor::readParameterTargets() noexcept
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto i = static_cast<std::size_t> (spec.id);
        const float raw = rawParameters[i]->load (std::memory_order_relaxed);
        const double v = sanitise (spec, raw);

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
    auto state = apvts.copyState();

    if (auto xml = state.createXml())
    {
        xml->setAttribute (stateVersionAttribute, stateVersion);
        copyXmlToBinary (*xml, destData);
    }
}

void SnareSimAudioProcessor::setStateInformation (const void* data, int sizeInBytes)
{
    if (data == nullptr || sizeInBytes <= 0)
        return;

    const auto xml = getXmlFromBinary (data, sizeInBytes);

    if (xml == nullptr || ! xml->hasTagName (stateTreeType.toString()))
        return;

    // Version 0 (no attribute) and 1: the first version's table, where the damping was the
    // batter's T60 (batter_decay), high_damping was batter_high_damping and mic_top_position
    // was listen_position. Unknown IDs are ignored; missing parameters take their defaults.
    const int version = xml->getIntAttribute (stateVersionAttribute, 0);
    std::array<std::optional<double>, snaresim::kNumParameters> values {};

    for (const auto* child : xml->getChildIterator())
    {
        if (! child->hasTagName ("PARAM") || ! child->hasAttribute ("id") || ! child->hasAttribute ("value"))
            continue;

        auto key = child->getStringAttribute ("id").toStdString();
        double value = child->getDoubleAttribute ("value");
        if (! std::isfinite (value))
            continue;

        if (version < 2)
        {
            if (key == "batter_decay")
            {
                key = "damping";
                value = dampingFromDecay (value);
            }
            else if (key == "batter_high_damping")
                key = "high_damping";
            else if (key == "listen_position")
                key = "mic_top_position";
        }

        if (const auto id = snaresim::findParameter (key))
            values[static_cast<std::size_t> (*id)] = value;
    }

    // A complete tree: replaceState leaves parameters missing from it at their current values.
    // Its children in the order the processor's own tree has them (by ID), so that a restored
    // state saves byte for byte as it was loaded.
    std::array<const snaresim::ParameterSpec*, snaresim::kNumParameters> byKey {};
    for (std::size_t i = 0; i < byKey.size(); ++i)
        byKey[i] = &snaresim::parameterSpecs()[i];
    std::sort (byKey.begin(), byKey.end(), [] (const auto* a, const auto* b) { return a->key < b->key; });

    juce::ValueTree tree (stateTreeType);

    for (const auto* specPointer : byKey)
    {
        const auto& spec = *specPointer;
        const auto& stored = values[static_cast<std::size_t> (spec.id)];
        const double value = stored.has_value() ? sanitise (spec, (float) *stored) : spec.defaultValue;

        juce::ValueTree param ("PARAM");
        param.setProperty ("id", juce::String (std::string (spec.key)), nullptr);
        param.setProperty ("value", value, nullptr);
        tree.appendChild (param, nullptr);
    }

    apvts.replaceState (tree);

    // A new grid, if the state needs one, is built now: the next block plays it.
    builder.buildNowIfNeeded();
}

//==============================================================================
// This creates new instances of the plug-in.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter()
{
    return new SnareSimAudioProcessor();
}
