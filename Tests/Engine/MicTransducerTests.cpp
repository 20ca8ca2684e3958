// The close microphones' transducer (MicTransducer.h): the SM57's published response at every
// rate the drum runs at, the same response through process() as its formula states, and the
// drum's switch between the transducers live and seamless.
#include "Drum.h"
#include "DrumConfig.h"
#include "MicTransducer.h"
#include "Parameters.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace snaresim;

namespace
{
// Points of the SM57's published typical on-axis response chart (Shure's user guide), dB
// relative to 1 kHz, read to about 1 dB.
struct ChartPoint
{
    double f_Hz, dB;
};
constexpr ChartPoint kChart[] = { { 40, -11 }, { 50, -9 },     { 100, -4 },   { 200, -1 },   { 500, 0 },  { 1000, 0 },
                                  { 2000, 1 }, { 3000, 3 },    { 4000, 4.5 }, { 5000, 5.5 }, { 6000, 6 }, { 7000, 4 },
                                  { 8000, 4 }, { 10000, 2.5 }, { 12000, -1 }, { 15000, -8 } };

double dB(double g) { return 20.0 * std::log10(g); }
} // namespace

TEST_CASE("the dynamic close microphone follows the SM57's published response within 1.5 dB from 40 Hz to 15 kHz at 44.1 to 96 kHz",
          "[mics][transducer]")
{
    for (const double rate : { 44100.0, 48000.0, 96000.0 })
    {
        const MicResponse mic(rate);
        CHECK(dB(mic.gainAt(1000.0)) == Approx(0.0).margin(1e-9));
        for (const auto& p : kChart)
        {
            INFO(rate << " Hz, " << p.f_Hz << " Hz: " << dB(mic.gainAt(p.f_Hz)) << " dB against the chart's " << p.dB);
            CHECK(std::abs(dB(mic.gainAt(p.f_Hz)) - p.dB) < 1.5);
        }
        // rolled off beyond the chart: under -10 dB at 20 Hz and (where the rate carries it) 18 kHz
        CHECK(dB(mic.gainAt(20.0)) < -10.0);
        CHECK(dB(mic.gainAt(18000.0)) < -10.0);
    }
}

TEST_CASE("the dynamic close microphone's samples give the gain its formula states", "[mics][transducer]")
{
    const double rate = 48000.0;
    for (const double f : { 60.0, 1000.0, 5000.0, 14000.0 })
    {
        MicResponse mic(rate);
        const int n = (int) rate; // one second: the transient gone after the first half
        double in = 0.0, out = 0.0;
        for (int i = 0; i < n; ++i)
        {
            const double x = std::sin(2.0 * std::numbers::pi * f * i / rate);
            const double y = mic.process(x);
            if (i >= n / 2)
                in += x * x, out += y * y;
        }
        INFO(f << " Hz");
        CHECK(dB(std::sqrt(out / in)) == Approx(dB(mic.gainAt(f))).margin(0.05));
        mic.clear();
        CHECK(mic.process(0.0) == 0.0);
    }
}

TEST_CASE("the close microphones' transducer switches live without a step, and the pressure microphones sound as without it",
          "[mics][transducer]")
{
    ParameterSet params;
    DrumConfig pressureCfg = makeDrumConfig(params, 48000.0);
    params.set(ParamId::closeMics, 1.0);
    DrumConfig dynamicCfg = makeDrumConfig(params, 48000.0);
    REQUIRE(dynamicCfg.mics.closeMics == MicTransducer::dynamicCardioid);
    REQUIRE(pressureCfg.mics.closeMics == MicTransducer::pressure);
    CHECK(spec(ParamId::closeMics).needs == ChangeNeeds::coefficients);

    Drum a(pressureCfg), b(pressureCfg), c(dynamicCfg);
    a.strikeAtDefaultPoint(3.0);
    b.strikeAtDefaultPoint(3.0);
    c.strikeAtDefaultPoint(3.0);
    const int n = 4800;
    std::vector<double> topA, topB, topC;
    for (int i = 0; i < n; ++i)
    {
        if (i == n / 2)
            b.applyLive(dynamicCfg); // b switches to the dynamic microphones half way
        a.step();
        b.step();
        c.step();
        topA.push_back(a.lastSignals().top_Pa);
        topB.push_back(b.lastSignals().top_Pa);
        topC.push_back(c.lastSignals().top_Pa);
    }
    double peak = 0.0, apart = 0.0;
    for (int i = 0; i < n; ++i)
    {
        REQUIRE(std::isfinite(topC[(size_t) i]));
        peak = std::max(peak, std::abs(topC[(size_t) i]));
        if (i < n / 2)
            CHECK(topB[(size_t) i] == topA[(size_t) i]); // the same until the switch
        else
            CHECK(topB[(size_t) i] == topC[(size_t) i]); // after it, what the dynamic microphones hear from the start
        apart = std::max(apart, std::abs(topA[(size_t) i] - topC[(size_t) i]));
    }
    CHECK(peak > 0.0);
    CHECK(apart > 0.05 * peak); // the transducers differ
}
