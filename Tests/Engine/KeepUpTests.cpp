// Whether a drum keeps up in real time: the probe's figures, and the check that measures off the
// caller's thread and remembers its verdicts.

#include "Drum.h"
#include "DrumConfig.h"
#include "DrumSession.h"
#include "KeepUp.h"

#include <catch2/catch.hpp>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <thread>

using namespace snaresim;

namespace
{
ParameterSet fastDrum()
{
    ParameterSet p;
    p.set(ParamId::bandwidth, qualityBandwidth_Hz(3.0));
    p.set(ParamId::snareCount, 5.0);
    return p;
}

KeepUpCheck::Verdict waitForVerdict(KeepUpCheck& check, const ParameterSet& p, double rate, int block)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    for (;;)
    {
        const auto v = check.ask(p, rate, block);
        if (v.state != KeepUpCheck::State::measuring || std::chrono::steady_clock::now() > until)
            return v;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}
} // namespace

TEST_CASE("the keep-up probe times an unstruck and a struck drum in the host's blocks", "[keepup]")
{
    DrumSession session(DrumSession::Mode::render);
    session.setParameters(fastDrum());
    session.prepareAndStart(48000.0, 256);
    const auto f = measureKeepUp(session, 256);
    CHECK(f.blockSize == 256);
    CHECK_FALSE(f.cutShort);
    // 0.1 s of audio in whole blocks: 19 of 256 samples.
    CHECK(f.audioSeconds == Approx(19 * 256 / 48000.0));
    CHECK(f.load > 0.0);
    CHECK(std::isfinite(f.load));
    CHECK(f.worstBlockShare >= f.load);
    // The drum is left as it was found: reset, silent.
    std::array<float, 64> out {};
    out.fill(1.0f);
    session.process(out.data(), (int) out.size(), {});
    for (const float x : out)
        REQUIRE(x == 0.0f);

    // Large blocks: at least one unstruck and two struck ones.
    const auto big = measureKeepUp(session, 8192);
    CHECK(big.audioSeconds == Approx(3 * 8192 / 48000.0));

    // Cancelled at once: nothing rendered, and no verdict of keeping up.
    const auto none = measureKeepUp(session, 256, [] { return true; });
    CHECK(none.audioSeconds == 0.0);
    CHECK_FALSE(keepsUp(none));

    // The verdict's thresholds.
    KeepUpFigures g;
    g.audioSeconds = 0.1;
    g.load = kKeepUpMaxLoad;
    g.worstBlockShare = kKeepUpMaxWorstBlock;
    CHECK(keepsUp(g));
    g.load = kKeepUpMaxLoad * 1.01;
    CHECK_FALSE(keepsUp(g));
    g.load = 0.1;
    g.worstBlockShare = 1.0;
    CHECK_FALSE(keepsUp(g));
    g.worstBlockShare = 0.1;
    g.cutShort = true;
    CHECK_FALSE(keepsUp(g));
}

TEST_CASE("the keep-up check measures in the background and remembers what it measured", "[keepup]")
{
    // A stand-in machine that measures until the test lets it finish (or the question is
    // replaced) and finds a drum asked in blocks of 512 at 0.2 of real time, any other at 3 times
    // real time: what the check does, with no clock in the test.
    KeepUpCheck check;
    std::atomic<bool> finish { false };
    check.setMeasurement([&finish](DrumSession&, int blockSize, const std::function<bool()>& cancelled) {
        while (! finish && ! (cancelled && cancelled()))
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        KeepUpFigures f;
        f.load = blockSize == 512 ? 0.2 : 3.0;
        f.worstBlockShare = blockSize == 512 ? 0.3 : 4.0;
        f.audioSeconds = 0.1;
        f.blockSize = blockSize;
        return f;
    });
    auto airbox = fastDrum();
    airbox.set(ParamId::airModel, (double) AirModel::airbox);

    CHECK(check.ask(airbox, 0.0, 256).state == KeepUpCheck::State::none); // no rate: nothing asked
    CHECK(check.latest().state == KeepUpCheck::State::none);

    // Asked, it answers at once that it is measuring, while the measurement runs elsewhere.
    CHECK(check.ask(airbox, 48000.0, 256).state == KeepUpCheck::State::measuring);
    CHECK(check.latest().state == KeepUpCheck::State::measuring);
    CHECK(check.measurementsDone() == 0);
    finish = true;
    const auto v = waitForVerdict(check, airbox, 48000.0, 256);
    REQUIRE(v.state == KeepUpCheck::State::tooSlow);
    CHECK(v.figures.load == 3.0);
    CHECK(check.measurementsDone() == 1);
    CHECK(check.latest().state == KeepUpCheck::State::tooSlow);

    // Live parameters do not make another model: the same verdict, not measured again.
    auto louder = airbox;
    louder.set(ParamId::outputGain, 6.0);
    louder.set(ParamId::batterTension, 4000.0);
    CHECK(check.ask(louder, 48000.0, 256).state == KeepUpCheck::State::tooSlow);
    CHECK(check.measurementsDone() == 1);

    // A question replaced before its answer is not answered; the newest is.
    finish = false;
    auto other = airbox;
    other.set(ParamId::airLoss, 5.0e-6);
    CHECK(check.ask(other, 44100.0, 128).state == KeepUpCheck::State::measuring);
    const auto fast = fastDrum();
    CHECK(check.ask(fast, 48000.0, 512).state == KeepUpCheck::State::measuring);
    finish = true;
    const auto w = waitForVerdict(check, fast, 48000.0, 512);
    CHECK(w.state == KeepUpCheck::State::keepsUp);
    CHECK(check.measurementsDone() == 2);
    CHECK(check.latest().state == KeepUpCheck::State::keepsUp);

    // Stopped: known verdicts stay, nothing new is measured; the replaced question has none.
    check.stop();
    CHECK(check.ask(airbox, 48000.0, 256).state == KeepUpCheck::State::tooSlow);
    CHECK(check.ask(other, 44100.0, 128).state == KeepUpCheck::State::none);
    CHECK(check.ask(airbox, 96000.0, 256).state == KeepUpCheck::State::none);
}

TEST_CASE("the keep-up check measures with a stand-in machine, and a question it knows leaves the one in measurement alone", "[keepup]")
{
    KeepUpCheck check;
    std::atomic<int> calls { 0 };
    // A machine that takes 0.3 s to measure and finds the drum at 0.2 of real time.
    check.setMeasurement([&calls](DrumSession&, int blockSize, const std::function<bool()>& cancelled) {
        ++calls;
        KeepUpFigures f;
        for (int i = 0; i < 300 && ! (cancelled && cancelled()); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        f.load = 0.2;
        f.worstBlockShare = 0.3;
        f.audioSeconds = 0.1;
        f.blockSize = blockSize;
        return f;
    });
    const auto first = fastDrum();
    const auto v = waitForVerdict(check, first, 48000.0, 256);
    REQUIRE(v.state == KeepUpCheck::State::keepsUp);
    CHECK(v.figures.load == 0.2);
    CHECK(check.measurementsDone() == 1);

    // While another drum is measured, asking about the known one (as the plug-in does each time
    // it reads its parameters) answers at once and does not cancel the measurement.
    auto second = first;
    second.set(ParamId::snareCount, 6.0);
    CHECK(check.ask(second, 48000.0, 256).state == KeepUpCheck::State::measuring);
    for (int i = 0; i < 40; ++i)
    {
        CHECK(check.ask(first, 48000.0, 256).state == KeepUpCheck::State::keepsUp);
        std::this_thread::sleep_for(std::chrono::milliseconds(15));
    }
    CHECK(waitForVerdict(check, second, 48000.0, 256).state == KeepUpCheck::State::keepsUp);
    CHECK(check.measurementsDone() == 2);
    CHECK(calls == 2); // measured once each: never cancelled and started again
}
