#include "DrumSession.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

namespace snaresim
{
namespace
{
// Each rung of Quality's fallback is 0.8 of the bandwidth above it: about 0.64 of its cost (the
// heads' grid points grow as the bandwidth's square).
constexpr double kQualityRung = 0.8;

bool isAirBox(const ParameterSet& params) { return std::lround(params.get(ParamId::airModel)) == (long) AirModel::airbox; }

std::string kHz(double f)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.1f kHz", f / 1000.0);
    return text;
}

std::string timesRealTime(double load, int decimals)
{
    char text[48];
    if (load < 10.0)
        std::snprintf(text, sizeof text, "%.*fx real time", decimals, load);
    else
        std::snprintf(text, sizeof text, "%ldx real time", std::lround(load));
    return text;
}

// Live and bouncing, every drum lags by the longest at the rate; a render takes each drum's own.
BuildOptions withLatency(BuildOptions options, DrumSession::Mode mode)
{
    options.constantLatency = mode != DrumSession::Mode::render;
    return options;
}
} // namespace

DrumSession::DrumSession(Mode mode, BuildOptions options)
    : currentMode(mode), modeInBlocks(mode), player([this] { return playedParameters(); }, withLatency(options, mode))
{
    setParameters(ParameterSet {});
}

DrumSession::~DrumSession() { stop(); }

void DrumSession::stop()
{
    player.stopBuilding(); // the builder reads playedParameters, which asks the checks
    airBoxKeepUp.stop();
    qualityKeepUp.stop();
}

//==============================================================================
// Parameters

void DrumSession::setParameter(ParamId id, double value) noexcept
{
    const auto& s = spec(id);
    values[static_cast<std::size_t>(id)].store(std::clamp(sanitise(s, value), s.minValue, s.maxValue), std::memory_order_relaxed);
}

void DrumSession::setParameters(const ParameterSet& params) noexcept
{
    for (const auto& s : parameterSpecs())
        setParameter(s.id, params.get(s.id));
}

ParameterSet DrumSession::parameters() const noexcept
{
    ParameterSet params;
    for (const auto& s : parameterSpecs())
        params.setClamped(s.id, values[static_cast<std::size_t>(s.id)].load(std::memory_order_relaxed));
    return params;
}

void DrumSession::setOffline(bool offline) noexcept
{
    auto expected = offline ? Mode::live : Mode::bounce;
    currentMode.compare_exchange_strong(expected, offline ? Mode::bounce : Mode::live);
}

KeepUpCheck::Verdict DrumSession::ask(KeepUpCheck& check, const ParameterSet& params) const
{
    try
    {
        return check.ask(params, preparedRate.load(), preparedBlockSize.load());
    }
    catch (const std::exception&)
    {
        return {}; // nothing known: the cavity plays, the chosen Quality plays
    }
}

ParameterSet DrumSession::withAirPolicy(ParameterSet params) const
{
    switch (mode())
    {
        case Mode::render: break;
        case Mode::bounce:
            if (params.get(ParamId::offlineAirBox) >= 0.5)
                params.setClamped(ParamId::airModel, (double) AirModel::airbox);
            break;
        case Mode::live:
            if (isAirBox(params))
            {
                const bool live = ask(airBoxKeepUp, params).state == KeepUpCheck::State::keepsUp;
                airBoxLive.store(live);
                if (! live)
                    params.setClamped(ParamId::airModel, (double) AirModel::cavity);
            }
            else
            {
                airBoxLive.store(false);
            }
            break;
    }
    return params;
}

bool DrumSession::lowersQuality(const ParameterSet& params) const
{
    return mode() == Mode::live && params.get(ParamId::keepUp) >= 0.5 && ! isAirBox(params);
}

ParameterSet DrumSession::keptUp(ParameterSet params) const
{
    // Down the rungs while each is measured too slow; the first one not known to be too slow
    // plays (measured or being measured), or the lowest.
    using State = KeepUpCheck::State;
    const double least = spec(ParamId::bandwidth).minValue;
    for (double f = params.get(ParamId::bandwidth);; f = std::max(least, f * kQualityRung))
    {
        params.setClamped(ParamId::bandwidth, f);
        const auto state = ask(qualityKeepUp, params).state;
        if ((state != State::tooSlow && state != State::failed) || f <= least)
            return params;
    }
}

ParameterSet DrumSession::playedParameters() const
{
    auto params = withAirPolicy(parameters());
    if (lowersQuality(params))
        params = keptUp(params);
    playedBandwidth.store(params.get(ParamId::bandwidth));
    return params;
}

//==============================================================================
// Preparing

DrumPlayer::Preparation DrumSession::prepare(double sampleRate, int blockSize)
{
    preparedRate.store(sampleRate);
    preparedBlockSize.store(blockSize > 0 ? blockSize : 512);
    const auto onFailure = mode() == Mode::render ? OnBuildFailure::raise : OnBuildFailure::fallBack;
    return player.prepare(sampleRate, playedParameters(), onFailure);
}

void DrumSession::prepareAndStart(double sampleRate, int blockSize)
{
    {
        auto preparation = prepare(sampleRate, blockSize); // holds the builder until it is gone
        start(preparation);
    }
    if (mode() == Mode::render)
        player.stopBuilding(); // a render builds on its own thread, at its events (setAndBuild)
}

//==============================================================================
// Audio thread

bool DrumSession::playsAirBox() const noexcept
{
    const auto* drum = player.drum();
    return drum != nullptr && drum->config().cavity.model == AirModel::airbox;
}

void DrumSession::setAndBuild(const PlayerEvent& event)
{
    setParameter(event.parameter, event.value);
    player.setTarget(event.parameter, event.value);
    // A render waits for the new drum; live and bounces build it in the background.
    if (mode() == Mode::render && spec(event.parameter).rebuildsModel())
        player.buildNowIfNeeded();
}

void DrumSession::process(float* out, int n, std::span<const PlayerEvent> events, StepObserver* observer) noexcept
{
    // A host that starts a bounce while playing (LV2 hosts say so only here, in the audio
    // callback) gets the drum that bounce needs before its first sample: built now, on this
    // thread, which is then not a real-time one. Real-time blocks never get here.
    const Mode modeNow = mode();
    if (modeNow != modeInBlocks)
    {
        modeInBlocks = modeNow;
        if (modeNow == Mode::bounce)
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

    for (const auto& s : parameterSpecs())
        player.setTarget(s.id, values[static_cast<std::size_t>(s.id)].load(std::memory_order_relaxed));

    // Live never plays a drum that cannot keep up: an air-box drum left from a bounce (the host
    // says it is back in real time only now) is silent until the drum real time plays is built
    // (in the background; taken here as soon as it is there).
    if (modeNow == Mode::live && ! airBoxLive.load(std::memory_order_relaxed) && playsAirBox())
    {
        player.process(out, 0, {});
        if (playsAirBox())
        {
            std::fill(out, out + std::max(n, 0), 0.0f);
            return;
        }
    }

    // The block split at its parameter events; the events between go to the player with it.
    int done = 0;
    std::size_t count = 0;
    auto renderUpTo = [&](int end) {
        player.process(out + done, end - done, std::span(segment.data(), count), observer);
        done = end;
        count = 0;
    };
    for (const auto& event : events)
    {
        const int at = std::clamp(event.sample, done, std::max(n, done));
        if (event.type == PlayerEvent::Type::parameter && static_cast<std::size_t>(event.parameter) < kNumParameters)
        {
            renderUpTo(at);
            try
            {
                setAndBuild(event);
            }
            catch (const std::exception&)
            {
                // Out of memory: the drum plays on as it is.
            }
            continue;
        }
        if (count == segment.size())
            renderUpTo(at);
        segment[count] = event;
        segment[count++].sample = at - done;
    }
    renderUpTo(std::max(n, done));
}

//==============================================================================
// What plays, and why

bool DrumSession::airBoxHeldBack() const
{
    const auto params = parameters();
    return mode() == Mode::live && isAirBox(params) && ask(airBoxKeepUp, params).state != KeepUpCheck::State::keepsUp;
}

KeepUpCheck::Verdict DrumSession::airBoxVerdict() const
{
    const auto params = parameters();
    if (! isAirBox(params))
        return {};
    return ask(airBoxKeepUp, params);
}

KeepUpCheck::Verdict DrumSession::qualityVerdict() const
{
    const auto params = withAirPolicy(parameters());
    if (! lowersQuality(params))
        return {};
    return ask(qualityKeepUp, params);
}

std::string DrumSession::airBoxNotice() const
{
    using State = KeepUpCheck::State;

    if (mode() != Mode::live)
        return isAirBox(playedParameters()) ? "Air box: the host renders offline, the air box plays" : "";

    const auto params = parameters();
    if (! isAirBox(params))
        return {};

    const auto verdict = ask(airBoxKeepUp, params);
    const auto times = timesRealTime(verdict.figures.load, 1);
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

std::string DrumSession::qualityNotice() const
{
    using State = KeepUpCheck::State;
    const auto params = withAirPolicy(parameters());
    if (! lowersQuality(params))
        return {};
    const auto chosen = ask(qualityKeepUp, params);
    if (chosen.state != State::tooSlow && chosen.state != State::failed)
        return {};

    const double asked = params.get(ParamId::bandwidth);
    const auto playing = keptUp(params);
    const double f = playing.get(ParamId::bandwidth);
    const auto verdict = ask(qualityKeepUp, playing);
    const std::string why =
        chosen.state == State::failed ? "cannot be built here" : "needs " + timesRealTime(chosen.figures.load, 2) + " here";
    const std::string line = "Quality: " + kHz(asked) + " " + why + "; " + kHz(f);
    switch (verdict.state)
    {
        case State::keepsUp: return line + " plays (" + timesRealTime(verdict.figures.load, 2) + ")";
        case State::tooSlow: return line + " plays and needs " + timesRealTime(verdict.figures.load, 2) + ": it may drop out";
        case State::failed: return line + " plays";
        case State::measuring:
        case State::none: break;
    }
    return line + " plays while it is measured";
}

std::string DrumSession::playNotice() const
{
    const auto air = airBoxNotice(), quality = qualityNotice();
    return air.empty() ? quality : quality.empty() ? air : air + "\n" + quality;
}

} // namespace snaresim
