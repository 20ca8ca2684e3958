#include "PluginProcessor.h"
#include "PluginEditor.h"

#include "ParameterLayout.h"
#include "PluginState.h"
#include "Presets.h"

#include <string>

namespace
{
snaresim::KeepUpCheck::Measurement& defaultQualityMeasurement()
{
    static snaresim::KeepUpCheck::Measurement m;
    return m;
}
} // namespace

//==============================================================================
SnareSimAudioProcessor::SnareSimAudioProcessor()
    : AudioProcessor(BusesProperties().withOutput("Output", juce::AudioChannelSet::stereo(), true)),
      apvts(*this, nullptr, snaresim::plugin::PluginState::treeType, snaresim::plugin::createParameterLayout())
{
    byIndex.resize((std::size_t) getParameters().size(), { nullptr, snaresim::ParamId::batterTension });
    for (const auto& spec : snaresim::parameterSpecs())
    {
        auto* raw = apvts.getRawParameterValue(juce::String(std::string(spec.key)));
        jassert(raw != nullptr);
        rawParameters[static_cast<std::size_t>(spec.id)] = raw;
        if (auto* p = apvts.getParameter(juce::String(std::string(spec.key))))
        {
            byIndex[(std::size_t) p->getParameterIndex()] = { p, spec.id };
            p->addListener(this);
        }
    }
    pushParameters();
    session.qualityCheck().setMeasurement(defaultQualityMeasurement());
    // The factory presets are read from their embedded files on first use (allocating): here,
    // so that a host asking for the programs from its audio thread finds them ready.
    snaresim::factoryPresets();
}

SnareSimAudioProcessor::~SnareSimAudioProcessor()
{
    cancelPendingUpdate();
    for (const auto& [p, id] : byIndex)
        if (p != nullptr)
            p->removeListener(this);
    session.stop();
}

const juce::String SnareSimAudioProcessor::getName() const { return JucePlugin_Name; }

void SnareSimAudioProcessor::parameterValueChanged(int parameterIndex, float)
{
    // The value as the parameter holds it (snapped, sanitised), not as it was sent.
    if (parameterIndex < 0 || (std::size_t) parameterIndex >= byIndex.size() || byIndex[(std::size_t) parameterIndex].first == nullptr)
        return;
    const auto& [p, id] = byIndex[(std::size_t) parameterIndex];
    session.setParameter(id, (double) p->convertFrom0to1(p->getValue()));
}

void SnareSimAudioProcessor::pushParameters() noexcept
{
    for (const auto& spec : snaresim::parameterSpecs())
        session.setParameter(spec.id, (double) rawParameters[static_cast<std::size_t>(spec.id)]->load(std::memory_order_relaxed));
}

void SnareSimAudioProcessor::setDefaultQualityMeasurement(snaresim::KeepUpCheck::Measurement m)
{
    defaultQualityMeasurement() = std::move(m);
}

void SnareSimAudioProcessor::setNonRealtime(bool isNonRealtime) noexcept
{
    AudioProcessor::setNonRealtime(isNonRealtime);
    session.setOffline(isNonRealtime);
}

//==============================================================================
void SnareSimAudioProcessor::prepareToPlay(double sampleRate, int maximumExpectedSamplesPerBlock)
{
    // The player renders in sub-blocks into fixed scratch space: the announced block size
    // needs no allocation and larger blocks just work. The keep-up checks measure in it.
    pushParameters();
    auto preparation = session.prepare(sampleRate, maximumExpectedSamplesPerBlock);

    {
        const juce::ScopedLock sl(getCallbackLock());
        session.start(preparation);
    }
    // The models it replaced are freed with `preparation`, outside the lock. One latency at
    // this rate, whatever Quality or air model plays (DrumSession.h).
    setLatencySamples(session.latencySamples());
}

void SnareSimAudioProcessor::releaseResources()
{
    const juce::ScopedLock sl(getCallbackLock());
    session.releaseResources();
}

bool SnareSimAudioProcessor::isBusesLayoutSupported(const BusesLayout& layouts) const
{
    // No audio input; mono or stereo output.
    if (layouts.getMainInputChannelSet() != juce::AudioChannelSet::disabled())
        return false;

    const auto out = layouts.getMainOutputChannelSet();
    return out == juce::AudioChannelSet::mono() || out == juce::AudioChannelSet::stereo();
}

//==============================================================================
// Audio thread: JUCE's buffer and MIDI translated into the player's calls.

void SnareSimAudioProcessor::processBlock(juce::AudioBuffer<float>& buffer, juce::MidiBuffer& midiMessages)
{
    juce::ScopedNoDenormals noDenormals;
    // Which thread is inside processBlock (no thread_local: in a plug-in loaded with dlopen its
    // first use on a thread may allocate).
    processingThread.store(juce::Thread::getCurrentThreadId(), std::memory_order_relaxed);

    // The host's values (also passed on as they change: parameterValueChanged).
    pushParameters();

    const int numSamples = buffer.getNumSamples();
    if (buffer.getNumChannels() == 0)
    {
        processingThread.store(nullptr, std::memory_order_relaxed);
        return; // nowhere to play to
    }
    float* out = buffer.getWritePointer(0);

    int done = 0;          // samples rendered
    std::size_t count = 0; // events gathered since

    auto renderUpTo = [&](int end) {
        for (std::size_t i = 0; i < count; ++i)
            events[i].sample -= done;
        session.process(out + done, end - done, std::span(events.data(), count));
        done = end;
        count = 0;
    };

    // Note-ons (velocity 0 is a note-off) and all-sound-off (CC 120); read from the raw bytes,
    // so that no SysEx is copied. Note-offs and all-notes-off leave the drum ringing.
    for (const auto metadata : midiMessages)
    {
        const auto* data = metadata.data;
        if (metadata.numBytes < 3)
            continue;

        const int status = data[0] & 0xf0;
        const int at = juce::jlimit(done, numSamples, metadata.samplePosition);

        if (count == events.size())
            renderUpTo(at);

        if (status == 0x90 && data[2] > 0)
            events[count++] = snaresim::PlayerEvent::noteOn(at, data[1] & 0x7f, data[2] & 0x7f);
        else if (status == 0xb0 && data[1] == 120)
            events[count++] = snaresim::PlayerEvent::allSoundOff(at);
    }

    renderUpTo(numSamples);

    for (int ch = 1; ch < buffer.getNumChannels(); ++ch)
        buffer.copyFrom(ch, 0, buffer, 0, 0, numSamples);

    processingThread.store(nullptr, std::memory_order_relaxed);
}

//==============================================================================
juce::AudioProcessorEditor* SnareSimAudioProcessor::createEditor() { return new SnareSimAudioProcessorEditor(*this); }

//==============================================================================
// Programs: the factory presets

int SnareSimAudioProcessor::getNumPrograms() { return (int) snaresim::factoryPresets().size(); }

int SnareSimAudioProcessor::getCurrentProgram() { return currentProgram.load(); }

const juce::String SnareSimAudioProcessor::getProgramName(int index)
{
    const auto presets = snaresim::factoryPresets();
    if (index < 0 || index >= (int) presets.size())
        return {};

    return juce::String(std::string(presets[(size_t) index].name));
}

void SnareSimAudioProcessor::setCurrentProgram(int index)
{
    if (index < 0 || index >= getNumPrograms())
        return;

    currentProgram.store(index);

    // Applied at once, on the calling thread: hosts call this from their own UI or state thread,
    // which is often not JUCE's message thread in a plug-in on Linux, and may save the state
    // right after. Only a call from inside processBlock is deferred to the message thread.
    if (processingThread.load(std::memory_order_relaxed) != juce::Thread::getCurrentThreadId())
    {
        applyProgram(index);
    }
    else
    {
        programToApply.store(index);
        triggerAsyncUpdate();
    }
}

void SnareSimAudioProcessor::handleAsyncUpdate()
{
    const int index = programToApply.exchange(-1);
    if (index >= 0)
        applyProgram(index);
}

void SnareSimAudioProcessor::applyProgram(int index)
{
    const auto presets = snaresim::factoryPresets();
    if (index < 0 || index >= (int) presets.size())
        return;

    // The preset's values over the defaults.
    snaresim::ParameterSet values;
    for (const auto& [id, value] : presets[(size_t) index].values)
        values.setClamped(id, value);
    applyParameters(values);
}

void SnareSimAudioProcessor::applyParameters(const snaresim::ParameterSet& values)
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        // "Lower Quality when slow" is this machine's, not the drum's: it stays as it is.
        if (spec.id == snaresim::ParamId::keepUp)
            continue;
        if (auto* p = apvts.getParameter(juce::String(std::string(spec.key))))
        {
            const float normalised = p->convertTo0to1((float) values.get(spec.id));
            if (p->getValue() != normalised)
            {
                p->beginChangeGesture();
                p->setValueNotifyingHost(normalised);
                p->endChangeGesture();
            }
        }
    }

    // A new grid, if the values need one, is built now: the next block plays it.
    pushParameters();
    session.buildNowIfNeeded();
}

//==============================================================================
// State: the APVTS tree as XML, with a version attribute.

void SnareSimAudioProcessor::getStateInformation(juce::MemoryBlock& destData) { snaresim::plugin::PluginState::write(apvts, destData); }

void SnareSimAudioProcessor::setStateInformation(const void* data, int sizeInBytes)
{
    // A new grid, if the state needs one, is built now: the next block plays it.
    if (snaresim::plugin::PluginState::read(apvts, data, sizeInBytes))
    {
        pushParameters();
        session.buildNowIfNeeded();
    }
}

//==============================================================================
// This creates new instances of the plug-in.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter() { return new SnareSimAudioProcessor(); }
