#include "PluginProcessor.h"
#include "PluginEditor.h"

#include "ParameterLayout.h"
#include "PluginState.h"
#include "Presets.h"

#include "DrumConfig.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace
{
// Each rung of Quality's fallback is 0.8 of the bandwidth above it: about 0.64 of its cost (the
// heads' grid points grow as the bandwidth's square).
constexpr double kQualityRung = 0.8;

snaresim::KeepUpCheck::Measurement& defaultQualityMeasurement()
{
    static snaresim::KeepUpCheck::Measurement m;
    return m;
}

juce::String kHz(double f) { return juce::String(f / 1000.0, 1) + " kHz"; }

juce::String timesRealTime(double load)
{
    return (load < 10.0 ? juce::String(load, 2) : juce::String(juce::roundToInt(load))) + "x real time";
}
} // namespace

//==============================================================================
SnareSimAudioProcessor::SnareSimAudioProcessor()
    : AudioProcessor(BusesProperties().withOutput("Output", juce::AudioChannelSet::stereo(), true)),
      apvts(*this, nullptr, snaresim::plugin::PluginState::treeType, snaresim::plugin::createParameterLayout()),
      player([this] { return currentParameters(); })
{
    for (const auto& spec : snaresim::parameterSpecs())
    {
        auto* raw = apvts.getRawParameterValue(juce::String(std::string(spec.key)));
        jassert(raw != nullptr);
        rawParameters[static_cast<std::size_t>(spec.id)] = raw;
    }
    qualityCheck.setMeasurement(defaultQualityMeasurement());
    // The factory presets are read from their embedded files on first use (allocating): here,
    // so that a host asking for the programs from its audio thread finds them ready.
    snaresim::factoryPresets();
}

SnareSimAudioProcessor::~SnareSimAudioProcessor()
{
    cancelPendingUpdate();
    player.stopBuilding(); // the builder reads currentParameters, which asks keepUp and qualityCheck
    keepUp.stop();
    qualityCheck.stop();
}

const juce::String SnareSimAudioProcessor::getName() const { return JucePlugin_Name; }

snaresim::ParameterSet SnareSimAudioProcessor::hostParameters() const
{
    snaresim::ParameterSet params;

    for (const auto& spec : snaresim::parameterSpecs())
        if (const auto* raw = rawParameters[static_cast<std::size_t>(spec.id)])
            params.setClamped(spec.id, (double) raw->load());

    return params;
}

snaresim::KeepUpCheck::Verdict SnareSimAudioProcessor::askKeepUp(const snaresim::ParameterSet& params) const
{
    try
    {
        return keepUp.ask(params, preparedRate.load(), preparedBlockSize.load());
    }
    catch (const std::exception&)
    {
        return {}; // nothing known: the cavity plays
    }
}

void SnareSimAudioProcessor::setDefaultQualityMeasurement(snaresim::KeepUpCheck::Measurement m)
{
    defaultQualityMeasurement() = std::move(m);
}

snaresim::KeepUpCheck::Verdict SnareSimAudioProcessor::askQuality(const snaresim::ParameterSet& params) const
{
    try
    {
        return qualityCheck.ask(params, preparedRate.load(), preparedBlockSize.load());
    }
    catch (const std::exception&)
    {
        return {}; // nothing known: the chosen Quality plays
    }
}

bool SnareSimAudioProcessor::lowersQuality(const snaresim::ParameterSet& params) const
{
    return ! offline.load() && params.get(snaresim::ParamId::keepUp) >= 0.5 &&
           std::lround(params.get(snaresim::ParamId::airModel)) != (long) snaresim::AirModel::airbox;
}

snaresim::ParameterSet SnareSimAudioProcessor::keptUp(snaresim::ParameterSet params) const
{
    // Down the rungs while each is measured too slow; the first one not known to be too slow
    // plays (measured or being measured), or the lowest.
    using State = snaresim::KeepUpCheck::State;
    const double least = snaresim::spec(snaresim::ParamId::bandwidth).minValue;
    for (double f = params.get(snaresim::ParamId::bandwidth);; f = std::max(least, f * kQualityRung))
    {
        params.setClamped(snaresim::ParamId::bandwidth, f);
        const auto state = askQuality(params).state;
        if ((state != State::tooSlow && state != State::failed) || f <= least)
            return params;
    }
}

snaresim::ParameterSet SnareSimAudioProcessor::currentParameters() const
{
    auto params = withAirPolicy(hostParameters());
    if (lowersQuality(params))
        params = keptUp(params);
    playedBandwidth.store(params.get(snaresim::ParamId::bandwidth));
    return params;
}

snaresim::KeepUpCheck::Verdict SnareSimAudioProcessor::qualityVerdict() const
{
    const auto params = withAirPolicy(hostParameters());
    if (! lowersQuality(params))
        return {};
    return askQuality(params);
}

juce::String SnareSimAudioProcessor::qualityNotice() const
{
    using State = snaresim::KeepUpCheck::State;
    const auto params = withAirPolicy(hostParameters());
    if (! lowersQuality(params))
        return {};
    const auto chosen = askQuality(params);
    if (chosen.state != State::tooSlow && chosen.state != State::failed)
        return {};

    const double asked = params.get(snaresim::ParamId::bandwidth);
    const auto playing = keptUp(params);
    const double f = playing.get(snaresim::ParamId::bandwidth);
    const auto verdict = askQuality(playing);
    const juce::String why =
        chosen.state == State::failed ? "cannot be built here" : "needs " + timesRealTime(chosen.figures.load) + " here";
    juce::String line = "Quality: " + kHz(asked) + " " + why + "; " + kHz(f);
    switch (verdict.state)
    {
        case State::keepsUp: return line + " plays (" + timesRealTime(verdict.figures.load) + ")";
        case State::tooSlow: return line + " plays and needs " + timesRealTime(verdict.figures.load) + ": it may drop out";
        case State::failed: return line + " plays";
        case State::measuring:
        case State::none: break;
    }
    return line + " plays while it is measured";
}

juce::String SnareSimAudioProcessor::playNotice() const
{
    const auto air = airBoxNotice(), quality = qualityNotice();
    return air.isEmpty() ? quality : quality.isEmpty() ? air : air + "\n" + quality;
}

snaresim::ParameterSet SnareSimAudioProcessor::withAirPolicy(snaresim::ParameterSet params) const
{
    using snaresim::AirModel;
    using snaresim::ParamId;

    if (offline.load())
    {
        if (params.get(ParamId::offlineAirBox) >= 0.5)
            params.setClamped(ParamId::airModel, (double) AirModel::airbox);
    }
    else if (std::lround(params.get(ParamId::airModel)) == (long) AirModel::airbox)
    {
        const bool live = askKeepUp(params).state == snaresim::KeepUpCheck::State::keepsUp;
        airBoxLive.store(live);
        if (! live)
            params.setClamped(ParamId::airModel, (double) AirModel::cavity);
    }
    else
    {
        airBoxLive.store(false);
    }

    return params;
}

bool SnareSimAudioProcessor::playsAirBox() const noexcept
{
    const auto* drum = player.drum();
    return drum != nullptr && drum->config().cavity.model == snaresim::AirModel::airbox;
}

bool SnareSimAudioProcessor::airBoxHeldBack() const
{
    const auto params = hostParameters();
    return ! offline.load() && std::lround(params.get(snaresim::ParamId::airModel)) == (long) snaresim::AirModel::airbox &&
           askKeepUp(params).state != snaresim::KeepUpCheck::State::keepsUp;
}

snaresim::KeepUpCheck::Verdict SnareSimAudioProcessor::airBoxVerdict() const
{
    const auto params = hostParameters();
    if (std::lround(params.get(snaresim::ParamId::airModel)) != (long) snaresim::AirModel::airbox)
        return {};
    return askKeepUp(params);
}

juce::String SnareSimAudioProcessor::airBoxNotice() const
{
    using State = snaresim::KeepUpCheck::State;

    if (offline.load())
        return std::lround(currentParameters().get(snaresim::ParamId::airModel)) == (long) snaresim::AirModel::airbox
                   ? "Air box: the host renders offline, the air box plays"
                   : "";

    const auto params = hostParameters();
    if (std::lround(params.get(snaresim::ParamId::airModel)) != (long) snaresim::AirModel::airbox)
        return {};

    const auto verdict = askKeepUp(params);
    const double load = verdict.figures.load;
    const auto times = (load < 10.0 ? juce::String(load, 1) : juce::String(juce::roundToInt(load))) + "x real time";
    switch (verdict.state)
    {
        case State::keepsUp: return "Air box: needs " + times + " here; it plays live";
        case State::tooSlow: return "Air box: needs " + times + " here; the cavity plays live, bounces use the air box";
        case State::failed: return "Air box: cannot be built here; the cavity plays";
        case State::measuring: return "Air box: measuring whether it keeps up here; the cavity plays meanwhile";
        case State::none: break;
    }
    return "Air box: measured once the audio starts; the cavity plays meanwhile";
}

void SnareSimAudioProcessor::setNonRealtime(bool isNonRealtime) noexcept
{
    AudioProcessor::setNonRealtime(isNonRealtime);
    offline.store(isNonRealtime);
}

//==============================================================================
void SnareSimAudioProcessor::prepareToPlay(double sampleRate, int maximumExpectedSamplesPerBlock)
{
    // What the air box is measured at (currentParameters).
    preparedRate.store(sampleRate);
    preparedBlockSize.store(maximumExpectedSamplesPerBlock > 0 ? maximumExpectedSamplesPerBlock : 512);

    // The player renders in sub-blocks into fixed scratch space: the announced block size
    // needs no allocation and larger blocks just work.
    auto preparation = player.prepare(sampleRate, currentParameters());

    const juce::ScopedLock sl(getCallbackLock());
    player.start(preparation);
    // The models it replaced are freed with `preparation`, outside the lock.
}

void SnareSimAudioProcessor::releaseResources()
{
    const juce::ScopedLock sl(getCallbackLock());
    player.releaseResources();
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

    // A host that starts an offline render while playing (LV2 hosts say so only here, in the
    // audio callback) gets the drum that render needs before its first sample: built now, on
    // this thread, which is then not a real-time one. Real-time blocks never get here.
    const bool offlineNow = offline.load(std::memory_order_relaxed);
    if (offlineNow != offlineInBlocks)
    {
        offlineInBlocks = offlineNow;
        if (offlineNow)
        {
            try
            {
                player.buildNowIfNeeded();
            }
            catch (const std::exception&)
            {
                // The background builder tries again.
            }
        }
    }

    for (const auto& spec : snaresim::parameterSpecs())
        player.setTarget(spec.id, (double) rawParameters[static_cast<std::size_t>(spec.id)]->load(std::memory_order_relaxed));

    const int numSamples = buffer.getNumSamples();
    if (buffer.getNumChannels() == 0)
    {
        processingThread.store(nullptr, std::memory_order_relaxed);
        return; // nowhere to play to
    }
    float* out = buffer.getWritePointer(0);

    // Real time never plays a drum that cannot keep up: an air-box drum left from an offline
    // render (the host says it is back in real time only now) is silent until the drum real
    // time plays is built (in the background; taken here as soon as it is there).
    if (! offlineNow && ! airBoxLive.load(std::memory_order_relaxed) && playsAirBox())
    {
        player.process(out, 0, {});
        if (playsAirBox())
        {
            buffer.clear();
            processingThread.store(nullptr, std::memory_order_relaxed);
            return;
        }
    }

    int done = 0;          // samples rendered
    std::size_t count = 0; // events gathered since

    auto renderUpTo = [&](int end) {
        for (std::size_t i = 0; i < count; ++i)
            events[i].sample -= done;
        player.process(out + done, end - done, std::span(events.data(), count));
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
    player.buildNowIfNeeded();
}

//==============================================================================
// State: the APVTS tree as XML, with a version attribute.

void SnareSimAudioProcessor::getStateInformation(juce::MemoryBlock& destData) { snaresim::plugin::PluginState::write(apvts, destData); }

void SnareSimAudioProcessor::setStateInformation(const void* data, int sizeInBytes)
{
    // A new grid, if the state needs one, is built now: the next block plays it.
    if (snaresim::plugin::PluginState::read(apvts, data, sizeInBytes))
        player.buildNowIfNeeded();
}

//==============================================================================
// This creates new instances of the plug-in.
juce::AudioProcessor* JUCE_CALLTYPE createPluginFilter() { return new SnareSimAudioProcessor(); }
