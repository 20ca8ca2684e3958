// "Lower Quality when slow": in real time, where the drum at the chosen Quality is measured not
// to keep up in the host's blocks, the first lower rung that keeps up plays and the editor says
// so. The machines here are stand-ins (KeepUpCheck::Measurement): a drum's load follows its
// grids' size, so which rung plays is known exactly, whatever this machine's speed.

#include "ProcessorTestHelpers.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <thread>

using namespace snaresim::testing;
using snaresim::ParamId;
using State = snaresim::KeepUpCheck::State;

namespace
{
constexpr double kChosen = 7839.5127; // the default Quality
constexpr int kBlock = 256;

// A machine on which a drum's load is `atChosen` at the default Quality's grids and grows as
// their points do, as the inverse square of the grids' coarseness.
snaresim::KeepUpCheck::Measurement machine(double atChosen)
{
    return [atChosen](snaresim::DrumSession& session, int blockSize, const std::function<bool()>&) {
        const double c = session.drumPlayer().drum()->config().batter.gridCoarseness;
        snaresim::KeepUpFigures f;
        f.load = atChosen * std::pow(snaresim::gridCoarsenessFor(kChosen) / c, 2.0);
        f.worstBlockShare = 1.2 * f.load;
        f.audioSeconds = 0.1;
        f.blockSize = blockSize;
        return f;
    };
}

// Renders silent blocks until `done()`, or 60 s are up; returns done().
template <class Done>
bool renderUntil(SnareSimAudioProcessor& proc, Done&& done)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (! done() && std::chrono::steady_clock::now() < until)
    {
        render(proc, kBlock, kBlock);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return done();
}

// Until the drum playing is built at `bandwidth`.
bool waitForBandwidth(SnareSimAudioProcessor& proc, double bandwidth)
{
    const double coarseness = snaresim::gridCoarsenessFor(bandwidth);
    // (the host's float and the rungs' products round: the same grids to a few millionths)
    return renderUntil(
        proc, [&] { return proc.getDrum() != nullptr && std::abs(proc.getDrum()->config().batter.gridCoarseness - coarseness) <= 1.0e-5; });
}

// Until the rung that plays is no longer being measured (it plays meanwhile).
void waitWhileMeasured(SnareSimAudioProcessor& proc)
{
    renderUntil(proc, [&] { return ! proc.qualityNotice().endsWith("while it is measured"); });
}

// The first rungs below the chosen Quality.
double rung(int n) { return kChosen * std::pow(0.8, n); }
} // namespace

TEST_CASE("in real time a Quality this machine cannot keep up with gives way to the first lower one it can, and the editor says so",
          "[processor][quality]")
{
    // 0.82 of real time at the chosen Quality: 0.54 one rung down (over kKeepUpMaxLoad), 0.35
    // two rungs down, which keeps up.
    SnareSimAudioProcessor proc;
    proc.setQualityMeasurement(machine(0.82));
    set(proc, ParamId::snareCount, 5.0);
    CHECK(parameter(proc, ParamId::keepUp).getValue() == 1.0f); // on by default
    prepare(proc, 48000.0, kBlock);

    REQUIRE(waitForBandwidth(proc, rung(2)));
    waitWhileMeasured(proc); // (the rung plays while it is measured, and after)
    CHECK(proc.playingBandwidth() == Approx(rung(2)).epsilon(1e-6));
    CHECK(proc.currentParameters().get(ParamId::bandwidth) == Approx(rung(2)).epsilon(1e-6));
    CHECK(proc.parameterValues().get(ParamId::bandwidth) == Approx(kChosen).epsilon(1e-6)); // the host's is the chosen one
    CHECK(proc.qualityMeasurements() == 3);

    const auto verdict = proc.qualityVerdict();
    CHECK(verdict.state == State::tooSlow);
    CHECK(verdict.figures.load == Approx(0.82));
    CHECK(proc.qualityNotice() == "Quality: 7.8 kHz needs 0.82x real time here; 5.0 kHz plays (0.35x real time)");
    CHECK(proc.playNotice() == proc.qualityNotice());

    // What plays is the engine's drum at that bandwidth (at rest after the silence it played:
    // the same to the last bit as a fresh drum at the same phase of its steps).
    snaresim::DrumSnapshot atRest;
    proc.getDrum()->fillSnapshot(atRest);
    const auto r = render(proc, kBlock, 2048, { { 0, note(100) } });
    CHECK(r.peak > 1.0e-4f);
    CHECK(r.samples == engineRender(proc.currentParameters(), 48000.0, 2048, { { 0, 38, 100 } }, atRest.samplesRendered % 96));

    // Switched off: the chosen Quality plays, and nothing is said.
    set(proc, ParamId::keepUp, 0.0);
    REQUIRE(waitForBandwidth(proc, kChosen));
    CHECK(proc.qualityNotice() == "");
    CHECK(proc.qualityVerdict().state == State::none);

    // On again: the verdicts are remembered, nothing is measured again.
    set(proc, ParamId::keepUp, 1.0);
    REQUIRE(waitForBandwidth(proc, rung(2)));
    CHECK(proc.qualityMeasurements() == 3);

    // A host's bounce plays the chosen Quality; real time again, the lower one.
    proc.setNonRealtime(true);
    CHECK(proc.currentParameters().get(ParamId::bandwidth) == Approx(kChosen).epsilon(1e-6));
    CHECK(proc.qualityNotice() == "");
    proc.setNonRealtime(false);
    CHECK(proc.currentParameters().get(ParamId::bandwidth) == Approx(rung(2)).epsilon(1e-6));

    // A program keeps the switch as it is (it is this machine's, not the drum's).
    set(proc, ParamId::keepUp, 0.0);
    proc.setCurrentProgram(1);
    CHECK(proc.parameterValues().get(ParamId::keepUp) == 0.0);
}

TEST_CASE("Quality's fallback: a machine that keeps up plays the chosen Quality, one that keeps up with none plays the lowest and says it "
          "may drop out",
          "[processor][quality]")
{
    {
        SnareSimAudioProcessor proc;
        proc.setQualityMeasurement(machine(0.3));
        set(proc, ParamId::snareCount, 5.0);
        prepare(proc, 48000.0, kBlock);
        renderUntil(proc, [&] { return proc.qualityVerdict().state != State::measuring; });
        CHECK(proc.qualityVerdict().state == State::keepsUp);
        CHECK(proc.currentParameters().get(ParamId::bandwidth) == Approx(kChosen).epsilon(1e-6));
        CHECK(proc.getDrum()->config().batter.gridCoarseness == snaresim::gridCoarsenessFor(kChosen));
        CHECK(proc.qualityNotice() == "");
        CHECK(proc.qualityMeasurements() == 1);
    }
    {
        SnareSimAudioProcessor proc;
        proc.setQualityMeasurement(machine(20.0));
        set(proc, ParamId::snareCount, 5.0);
        prepare(proc, 48000.0, kBlock);
        const double least = snaresim::spec(ParamId::bandwidth).minValue;
        REQUIRE(waitForBandwidth(proc, least));
        waitWhileMeasured(proc); // (the lowest rung plays while it is measured, and after)
        CHECK(proc.qualityNotice() ==
              "Quality: 7.8 kHz needs 20x real time here; 3.8 kHz plays and needs 4.90x real time: it may drop out");
        CHECK(proc.qualityMeasurements() == 5);
        const auto r = render(proc, kBlock, 1024, { { 0, note(100) } });
        CHECK(r.allFinite);
        CHECK(r.peak > 1.0e-4f);
    }
}
