#pragma once
// The one door into the engine. Every client plays the drum through a DrumSession: the plug-in
// and its standalone, the renderer, its --match and --bench, and the keep-up probe's questions.
//
// A session holds
//  - the parameters as the host (or the renderer's command line) sets them;
//  - how the drum is played: live (real time), a bounce (a host's offline render) or a render
//    (the renderer: the parameters as given);
//  - the air-model policy: a bounce plays the air box when "Air box when bouncing" is on; live,
//    the air box plays only once it is measured to keep up here at the prepared rate and block
//    size (KeepUp.h), the cavity meanwhile or otherwise; live with "Lower Quality when slow" on,
//    a bandwidth measured too slow gives way to the first lower rung that is not;
//  - the player (DrumPlayer.h): smoothing, events, rebuilds built off the audio thread (at once,
//    on the calling thread, in a render), the hand-off, the guard and the counters;
//  - the latency: live and bouncing, every drum lags its strikes by the longest lag at the rate
//    (BuildOptions::constantLatency: 96 samples at 48 kHz), whatever Quality or air model
//    plays; a render takes each drum's own lag (the renderer takes it off).
// Drums are built in one place, buildDrum (ModelExchange.h), with the session's BuildOptions.
//
// Threads: process() and setParameter() may run on the audio thread and never lock, allocate,
// free, log or block (but in a render, where a rebuilding parameter's event builds the new
// drum at once, and in a bounce's first block, which builds the drum the bounce plays: that
// thread is then not a real-time one). prepare() / start() as DrumPlayer's; the rest on any
// other thread.

#include "BuildOptions.h"
#include "DrumPlayer.h"
#include "KeepUp.h"
#include "Parameters.h"

#include <array>
#include <atomic>
#include <span>
#include <string>

namespace snaresim
{

class DrumSession
{
public:
    enum class Mode
    {
        live,   // a host in real time: the air-model policy and Quality's keep-up apply
        bounce, // a host's offline render: the air box when "Air box when bouncing" is on
        render  // the renderer: the parameters as given, the chosen Quality, a drum that cannot be built is an error
    };

    explicit DrumSession(Mode mode = Mode::live, BuildOptions options = {});
    ~DrumSession();
    DrumSession(const DrumSession&) = delete;
    DrumSession& operator=(const DrumSession&) = delete;

    // --- parameters (any thread; lock- and allocation-free) ---------------------------------
    void setParameter(ParamId id, double value) noexcept; // clamped into range
    void setParameters(const ParameterSet& values) noexcept;
    // The values as set (the air model as chosen, not as it plays).
    ParameterSet parameters() const noexcept;
    // The values the drum is built from: parameters() with the air-model policy and, live,
    // Quality's keep-up. Never waits for a measurement; not for the audio thread.
    ParameterSet playedParameters() const;

    // --- how the drum plays -----------------------------------------------------------------
    // live <-> bounce as the host says (any thread); a render stays a render.
    void setOffline(bool offline) noexcept;
    Mode mode() const noexcept { return currentMode.load(); }

    // --- preparing (not the audio thread) ---------------------------------------------------
    // As DrumPlayer's; the block size is what the keep-up checks measure in.
    DrumPlayer::Preparation prepare(double sampleRate, int blockSize);
    void start(DrumPlayer::Preparation& preparation) noexcept { player.start(preparation); }
    // Both at once (hosts whose audio cannot run meanwhile). In a render, throws
    // std::invalid_argument when the drum cannot be built (no fallback).
    void prepareAndStart(double sampleRate, int blockSize);
    void releaseResources() noexcept { player.releaseResources(); }
    // The output's lag behind a strike in samples of the prepared rate (after start()).
    int latencySamples() const noexcept { return player.latencySamples(); }
    // After a state or program load: the drum the parameters need now is built at once.
    void buildNowIfNeeded() { player.buildNowIfNeeded(); }
    // Stops the background threads (the builder and the keep-up checks).
    void stop();

    // --- audio thread -----------------------------------------------------------------------
    // n samples (mono) into out: every parameter to the player, then the block split at its
    // events (a parameter event sets that parameter from its sample on, as setParameter). Live,
    // a drum in the air box that does not keep up is never played: silence until the drum
    // real time plays is built.
    void process(float* out, int n, std::span<const PlayerEvent> events, StepObserver* observer = nullptr) noexcept;

    // --- what plays, and why (any thread but the audio thread) ------------------------------
    // Live, the air box chosen and held back (not measured yet, or too slow here).
    bool airBoxHeldBack() const;
    // The measurement's verdict for the air box chosen (none for another air model).
    KeepUpCheck::Verdict airBoxVerdict() const;
    // Quality's: the chosen bandwidth's verdict live with "Lower Quality when slow" on (none otherwise).
    KeepUpCheck::Verdict qualityVerdict() const;
    double playingBandwidth() const noexcept { return playedBandwidth.load(); }
    // One line each for the editor (empty when there is nothing to say), and both.
    std::string airBoxNotice() const;
    std::string qualityNotice() const;
    std::string playNotice() const;

    // The checks themselves (tests measure with a stand-in for another machine).
    // Thread-safe: reachable from a const session.
    KeepUpCheck& airBoxCheck() const noexcept { return airBoxKeepUp; }
    KeepUpCheck& qualityCheck() const noexcept { return qualityKeepUp; }

    // The player: counters, snapshots, the drum playing (DrumPlayer.h).
    DrumPlayer& drumPlayer() noexcept { return player; }
    const DrumPlayer& drumPlayer() const noexcept { return player; }

private:
    ParameterSet withAirPolicy(ParameterSet params) const;
    bool lowersQuality(const ParameterSet& params) const;
    ParameterSet keptUp(ParameterSet params) const;
    KeepUpCheck::Verdict ask(KeepUpCheck& check, const ParameterSet& params) const;
    bool playsAirBox() const noexcept;
    void setAndBuild(const PlayerEvent& event);

    std::atomic<Mode> currentMode;
    std::array<std::atomic<double>, kNumParameters> values {};
    std::atomic<double> preparedRate { 0.0 };
    std::atomic<int> preparedBlockSize { 0 };
    mutable KeepUpCheck airBoxKeepUp, qualityKeepUp;
    mutable std::atomic<bool> airBoxLive { false };      // live plays the air box (it keeps up here)
    mutable std::atomic<double> playedBandwidth { 0.0 }; // what playedParameters last chose
    Mode modeInBlocks = Mode::live;                      // the mode process() last saw (audio thread)
    std::array<PlayerEvent, 256> segment {};             // a block's events between parameter events

    DrumPlayer player; // last: its builder reads the members above
};

} // namespace snaresim
