// The drum at the host's rate: it is simulated at a fraction of the host's rate (the default's
// grids at 32 or 33.075 kHz) and its signals interpolated (HostRateInterpolator.h). The interpolation's error
// against an ideal band-limited signal, the host rate's drum against the simulated one, and its
// strikes against the same drum's at the simulated rate on the strike features.

#include "Drum.h"
#include "DrumConfig.h"
#include "HostRateInterpolator.h"
#include "Parameters.h"
#include "StrikeFeatures.h"
#include "StrikeFingerprint.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

using namespace snaresim;
using render::measureStrike;
using render::StrikeRules;

namespace
{
ParameterSet withBandwidth(double hz)
{
    ParameterSet p;
    p.setClamped(ParamId::bandwidth, hz);
    return p;
}
} // namespace

TEST_CASE("host rate: the simulated rate halves the host's to 44.1 or 48 kHz and simulates the default's grids at 32 or 33.075 kHz",
          "[rate]")
{
    struct Row
    {
        double host, simulated;
        int up, down;
    };
    // the default's grids (7.84 kHz)
    const std::vector<Row> reduced { { 22050.0, 22050.0, 1, 1 },  { 32000.0, 32000.0, 1, 1 },   { 44100.0, 33075.0, 4, 3 },
                                     { 48000.0, 32000.0, 3, 2 },  { 64000.0, 64000.0, 1, 1 },   { 88200.0, 33075.0, 8, 3 },
                                     { 96000.0, 32000.0, 3, 1 },  { 176400.0, 33075.0, 16, 3 }, { 192000.0, 32000.0, 6, 1 },
                                     { 384000.0, 32000.0, 12, 1 } };
    for (const auto& row : reduced)
    {
        INFO(row.host << " Hz");
        const DrumConfig cfg = makeDrumConfig(ParameterSet {}, row.host);
        const SimulatedRate s = simulatedRateFor(row.host, cfg.batter.gridCoarseness);
        CHECK(s.rate_Hz == row.simulated);
        CHECK(s.up == row.up);
        CHECK(s.down == row.down);
        CHECK(cfg.sampleRate_Hz == row.simulated);
        CHECK(cfg.outputRate() == row.host);
        CHECK(cfg.outputUp() == row.up);
        CHECK(cfg.outputDown() == row.down);
    }
    // finer grids (12 kHz) at the host's rate halved
    const std::vector<Row> halved { { 44100.0, 44100.0, 1, 1 },
                                    { 48000.0, 48000.0, 1, 1 },
                                    { 88200.0, 44100.0, 2, 1 },
                                    { 96000.0, 48000.0, 2, 1 },
                                    { 192000.0, 48000.0, 4, 1 } };
    for (const auto& row : halved)
    {
        INFO(row.host << " Hz, 12 kHz bandwidth");
        const DrumConfig cfg = makeDrumConfig(withBandwidth(12000.0), row.host);
        CHECK(cfg.batter.gridCoarseness < kReducedRateCoarseness);
        CHECK(cfg.sampleRate_Hz == row.simulated);
        CHECK(cfg.outputUp() == row.up);
        CHECK(cfg.outputDown() == row.down);
    }
    // the air box (offline) is simulated at the host's rate
    ParameterSet box;
    box.setClamped(ParamId::airModel, (double) AirModel::airbox);
    CHECK(mapParameters(box, 96000.0).sampleRate_Hz == 96000.0);
    CHECK(mapParameters(box, 48000.0).sampleRate_Hz == 48000.0);
    // a config whose output rate is no such multiple is refused
    DrumConfig odd;
    odd.outputRate_Hz = 5.0 * odd.sampleRate_Hz;
    CHECK_THROWS_WITH(odd.validate(), Catch::Contains("output rate"));
}

namespace
{
// A signal at the simulated rate fs through the interpolator, one value per host sample
// (host sample n: phase n M mod L; a simulated sample due before the phases below M).
template <class Signal>
std::vector<double> resampled(HostRateInterpolator& up, long hostSamples, Signal x)
{
    std::vector<double> out((size_t) hostSamples);
    long next = 0;
    int phase = 0;
    for (long n = 0; n < hostSamples; ++n)
    {
        if (phase < up.down())
            up.push({ x(next++), 0.0, 0.0, 0.0 });
        out[(size_t) n] = up.value(0, phase);
        phase = (phase + up.down()) % up.factor();
    }
    return out;
}
} // namespace

TEST_CASE("host rate: the interpolation passes the band to 0.4 of the simulated rate within -90 dB, images included", "[rate]")
{
    for (const auto& [L, M] : std::vector<std::pair<int, int>> { { 2, 1 }, { 4, 1 }, { 3, 1 }, { 3, 2 }, { 4, 3 }, { 8, 3 } })
    {
        HostRateInterpolator up(L, M);
        const double fs = 32000.0, host = fs * L / M;
        REQUIRE(up.delay() * 2 + 1 == up.length());
        for (const double share : { 0.0, 0.003, 0.03, 0.15, 0.3, 0.4 })
        {
            const double hz = share * fs;
            up.clear();
            const long samples = 4000L * L / M;
            const auto y = resampled(up, samples, [&](long n) { return std::cos(2.0 * std::numbers::pi * hz * (double) n / fs); });
            double error = 0.0, signal = 0.0;
            for (long n = (long) up.length() / M + 1; n < samples; ++n) // after the filter's start
            {
                // host sample n stands at (n M - delay) / L simulated samples
                const double ideal = std::cos(2.0 * std::numbers::pi * hz * ((double) (n * M) - up.delay()) / (L * fs));
                error += (y[(size_t) n] - ideal) * (y[(size_t) n] - ideal);
                signal += ideal * ideal;
            }
            const double dB = 10.0 * std::log10(error / signal);
            INFO("L " << L << ", M " << M << " (" << host << " Hz), " << hz << " Hz: error " << dB << " dB");
            CHECK(dB < -90.0);
        }
    }
}

TEST_CASE("host rate: a drum lags its strikes by its interpolation's delay and the longest lag at a rate is the default grids'", "[rate]")
{
    // The interpolation's delay: delay() samples at L times the simulated rate, host rate times
    // M, so delay() / M host samples (the test above holds the signal to it within -90 dB).
    for (const double rate : { 22050.0, 32000.0, 44100.0, 48000.0, 64000.0, 88200.0, 96000.0, 192000.0 })
    {
        INFO(rate << " Hz");
        const Drum reduced(makeDrumConfig(ParameterSet {}, rate));
        const Drum finer(makeDrumConfig(withBandwidth(12000.0), rate));
        for (const Drum* d : { &reduced, &finer })
        {
            const HostRateInterpolator up(d->config().outputUp(), d->config().outputDown());
            CHECK(d->latencySamples() == (double) up.delay() / up.down());
        }
        CHECK(longestLatencySamples(rate) == std::max(reduced.latencySamples(), finer.latencySamples()));
        // about 2 ms where the default's grids are interpolated, none where no drum is
        if (reduced.config().outputUp() > 1)
        {
            CHECK(reduced.latencySamples() / rate > 0.0019);
            CHECK(reduced.latencySamples() / rate < 0.00205);
        }
        else
            CHECK(longestLatencySamples(rate) == 0.0);
    }
    CHECK(longestLatencySamples(48000.0) == 96.0);
    CHECK(longestLatencySamples(44100.0) == Approx(257.0 / 3.0));
}

namespace
{
std::vector<double> strikeAt(const DrumConfig& cfg, int velocity, double seconds)
{
    Drum drum(cfg);
    std::vector<double> out((size_t) std::lround(seconds * cfg.outputRate()));
    drum.playNote(38, velocity);
    for (double& y : out)
        y = drum.step();
    return out;
}
std::vector<double> strikeAt(double rate, int velocity, double seconds)
{
    return strikeAt(makeDrumConfig(ParameterSet {}, rate), velocity, seconds);
}
} // namespace

TEST_CASE("host rate: the drum at the host's rate is the drum simulated at its simulated rate, interpolated", "[rate]")
{
    for (const double rate : { 48000.0, 44100.0, 96000.0 })
    {
        const DrumConfig cfg = makeDrumConfig(ParameterSet {}, rate);
        INFO(rate << " Hz, simulated at " << cfg.sampleRate_Hz << " Hz");
        const auto simulated = strikeAt(cfg.sampleRate_Hz, 110, 0.1);
        Drum host(cfg);
        REQUIRE(host.sampleRate() == rate);
        REQUIRE(host.simulationRate() == cfg.sampleRate_Hz);
        CHECK(host.batter().grid().numInterior() == Drum(makeDrumConfig(ParameterSet {}, cfg.sampleRate_Hz)).batter().grid().numInterior());
        HostRateInterpolator up(cfg.outputUp(), cfg.outputDown());
        host.playNote(38, 110);
        const long samples = (long) simulated.size() * cfg.outputUp() / cfg.outputDown();
        const auto want = resampled(up, samples, [&](long n) { return simulated[(size_t) n]; });
        long differing = 0;
        for (long n = 0; n < samples; ++n)
        {
            const double got = host.step();
            differing += std::memcmp(&want[(size_t) n], &got, sizeof got) == 0 ? 0 : 1;
        }
        CHECK(differing == 0);
    }
}

namespace
{
// A strike at the simulated rate as the host's rate plays its band: through the interpolation's
// filter (twice the rate), every other sample kept.
std::vector<double> inHostBand(const std::vector<double>& simulated)
{
    HostRateInterpolator up(2, 2);
    return resampled(up, (long) simulated.size(), [&](long n) { return simulated[(size_t) n]; });
}
} // namespace

TEST_CASE(
    "host rate: strikes at 44.1 to 192 kHz have the features of the strike at the simulated rate, within their just-noticeable differences",
    "[rate][slow]")
{
    // The centroid and the falls within 5 % (ISO 3382-1 Annex A for decay times), each band
    // share within one point: as the vector targets and the single-precision heads are held.
    // The reference is the simulated rate's strike in the band the host's rate plays (to 0.45 of
    // the simulated rate: HostRateInterpolator.h).
    for (const int velocity : { 60, 127 })
        for (const double rate : { 44100.0, 48000.0, 88200.0, 96000.0, 176400.0, 192000.0 })
        {
            const double simulated = makeDrumConfig(ParameterSet {}, rate).sampleRate_Hz; // 32 or 33.075 kHz
            const auto base = measureStrike(inHostBand(strikeAt(simulated, velocity, 1.0)), simulated, StrikeRules::render);
            const auto f = measureStrike(strikeAt(rate, velocity, 1.0), rate, StrikeRules::render);
            INFO("velocity " << velocity << ", " << rate << " Hz: centroid " << f.tailCentroid_Hz.value_or(0.0) << " Hz (" << simulated
                             << " Hz: " << base.tailCentroid_Hz.value_or(0.0) << "), fall 20 dB " << f.fall20_ms.value_or(0.0) << " ms ("
                             << base.fall20_ms.value_or(0.0) << "), fall 40 dB " << f.fall40_ms.value_or(0.0) << " ms ("
                             << base.fall40_ms.value_or(0.0) << "), share above 10 kHz " << f.bandShares[4] << " (" << base.bandShares[4]
                             << ")");
            REQUIRE(f.tailCentroid_Hz);
            REQUIRE(f.fall20_ms);
            REQUIRE(f.fall40_ms);
            CHECK(std::abs(*f.tailCentroid_Hz / *base.tailCentroid_Hz - 1.0) < 0.05);
            CHECK(std::abs(*f.fall20_ms / *base.fall20_ms - 1.0) < 0.05);
            CHECK(std::abs(*f.fall40_ms / *base.fall40_ms - 1.0) < 0.05);
            for (size_t b = 0; b < f.bandShares.size(); ++b)
                CHECK(std::abs(f.bandShares[b] - base.bandShares[b]) < 0.01);
        }
}

TEST_CASE("host rate: the default's grids simulated at 32 kHz lie nearer the finest grids' drum than simulated at 48 kHz", "[rate][slow]")
{
    // Whole-strike distances (StrikeFingerprint.h) of 1 s strikes at 48 kHz, summed over
    // velocities 60, 100 and 127, to the drum of the finest grids (21.1 kHz, simulated at 48 kHz).
    // The default's grids carry 7.84 kHz; what a 48 kHz step adds above 16 kHz is the coarse
    // grids' and the contacts' clicks, which the finest grids do not make.
    const DrumConfig reduced = makeDrumConfig(ParameterSet {}, 48000.0);
    REQUIRE(reduced.sampleRate_Hz == 32000.0);
    DrumConfig full = reduced; // the same grids, at a 48 kHz step
    full.sampleRate_Hz = 48000.0;
    full.outputRate_Hz = 0.0;
    full.validate();
    const DrumConfig finest = makeDrumConfig(withBandwidth(21100.0), 48000.0);
    REQUIRE(finest.sampleRate_Hz == 48000.0);
    double atReduced = 0.0, atFull = 0.0;
    for (const int velocity : { 60, 100, 127 })
    {
        const auto print = [&](const DrumConfig& cfg) {
            const auto x = strikeAt(cfg, velocity, 1.0);
            return render::strikeFingerprint(x, 48000.0, render::StrikeRules::render);
        };
        const auto truth = print(finest);
        const double a = render::strikeDistance_dB(print(reduced), truth), b = render::strikeDistance_dB(print(full), truth);
        INFO("velocity " << velocity << ": simulated at 32 kHz " << a << " dB, at 48 kHz " << b << " dB");
        CHECK(a > 0.0);
        atReduced += a;
        atFull += b;
    }
    INFO("summed: simulated at 32 kHz " << atReduced << " dB, at 48 kHz " << atFull << " dB");
    CHECK(atReduced < atFull);
}

TEST_CASE("host rate: below 48 kHz the heads and the wires keep their 48 kHz grids where those are stable", "[rate]")
{
    // Grids of 12 kHz, simulated at 44.1 and 48 kHz: the same nodes; the spacing within 0.5 %
    // (the share of kinetic energy the explicit couplings keep, DrumConfig::kineticReserve,
    // depends on the step).
    const Drum reference(makeDrumConfig(withBandwidth(12000.0), 48000.0));
    for (const double rate : { 44100.0, 88200.0 })
    {
        INFO(rate << " Hz");
        const Drum drum(makeDrumConfig(withBandwidth(12000.0), rate));
        REQUIRE(drum.simulationRate() == 44100.0);
        CHECK(drum.batter().grid().numInterior() == reference.batter().grid().numInterior());
        CHECK(drum.carry().grid().numInterior() == reference.carry().grid().numInterior());
        CHECK(drum.batter().grid().spacing() == Approx(reference.batter().grid().spacing()).epsilon(0.005));
        CHECK(drum.carry().grid().spacing() == Approx(reference.carry().grid().spacing()).epsilon(0.005));
        CHECK(drum.snareWires().spacing() == reference.snareWires().spacing());
        CHECK(drum.snareContact().numPoints() == reference.snareContact().numPoints());
    }
    // The default's grids, simulated at 32 and 33.075 kHz (48, 44.1 and 88.2 kHz): the grids of
    // the 48 kHz step, node for node (designed there with that step's reserve:
    // DrumConfig::designReserve).
    DrumConfig full = makeDrumConfig(ParameterSet {}, 48000.0);
    full.sampleRate_Hz = 48000.0;
    full.outputRate_Hz = 0.0;
    const Drum atFull(full);
    for (const double rate : { 48000.0, 44100.0, 88200.0 })
    {
        INFO(rate << " Hz, the default's grids");
        const Drum drum(makeDrumConfig(ParameterSet {}, rate));
        REQUIRE(drum.simulationRate() < 34000.0);
        CHECK(drum.batter().grid().numInterior() == atFull.batter().grid().numInterior());
        CHECK(drum.carry().grid().numInterior() == atFull.carry().grid().numInterior());
        CHECK(drum.batter().grid().spacing() == atFull.batter().grid().spacing());
        CHECK(drum.carry().grid().spacing() == atFull.carry().grid().spacing());
        CHECK(drum.snareWires().spacing() == atFull.snareWires().spacing());
        CHECK(drum.snareContact().numPoints() == atFull.snareContact().numPoints());
    }
    // Where the 48 kHz grid would be unstable (22.05 kHz at Quality 2) it is the stability bound
    // of the rate's own step (eq. 39-40), coarser than at 48 kHz.
    const DrumConfig low = makeDrumConfig(ParameterSet {}, 22050.0);
    const Drum coarse(low);
    const double k = 1.0 / 22050.0;
    CHECK(coarse.batter().grid().spacing() > atFull.batter().grid().spacing());
    MembraneSpec bound = low.batter;
    bound.gridCoarseness = 1.0;
    bound.gridTimeStep_s = 0.0;
    CHECK(Membrane::gridSpacing(low.batter, k, low.kineticReserve(true)) == Membrane::gridSpacing(bound, k, low.kineticReserve(true)));
    // Above 48 kHz (64 kHz: simulated at its own rate) the grid is Quality's multiple of the
    // rate's own bound, as it always was.
    const DrumConfig fast = makeDrumConfig(ParameterSet {}, 64000.0);
    MembraneSpec own = fast.batter;
    own.gridTimeStep_s = 0.0;
    CHECK(Membrane::gridSpacing(fast.batter, 1.0 / 64000.0, fast.kineticReserve(true)) ==
          Membrane::gridSpacing(own, 1.0 / 64000.0, fast.kineticReserve(true)));
}
