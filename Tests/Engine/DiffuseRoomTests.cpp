// The room's diffuse field (DiffuseRoom.h): Sabine's level, the decay it is set to at low and
// high frequencies, three fields that do not correlate, and no room at all when it is off.

#include "DiffuseRoom.h"
#include "Drum.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>
#include <vector>

using namespace snaresim;

namespace
{
// The room's response to a unit impulse of the source, `seconds` long, at each microphone.
std::array<std::vector<double>, DiffuseRoom::kOutputs> impulseResponses(const RoomSpec& spec, double rate, double seconds)
{
    DiffuseRoom room(spec, rate);
    std::array<std::vector<double>, DiffuseRoom::kOutputs> h;
    const int n = (int) (seconds * rate);
    for (int t = 0; t < n; ++t)
    {
        const auto out = room.listen(t == 0 ? 1.0 : 0.0);
        for (int m = 0; m < DiffuseRoom::kOutputs; ++m)
            h[(size_t) m].push_back(out[(size_t) m]);
    }
    return h;
}

double energy(const std::vector<double>& x) { return std::inner_product(x.begin(), x.end(), x.begin(), 0.0); }

// T60 from Schroeder's backward integral of x^2, between -15 and -45 dB (past the first, sparse
// passes).
double reverberationTime(const std::vector<double>& x, double rate)
{
    std::vector<double> tail(x.size() + 1, 0.0);
    for (size_t i = x.size(); i-- > 0;)
        tail[i] = tail[i + 1] + x[i] * x[i];
    auto when = [&](double dB) {
        size_t i = 0;
        while (i < x.size() && 10.0 * std::log10(tail[i] / tail[0]) > dB)
            ++i;
        return (double) i / rate;
    };
    return 60.0 / 30.0 * (when(-45.0) - when(-15.0));
}

// Cascaded one-pole low-passes at fc, or (high) first differences: the slow or the fast part.
std::vector<double> lowPart(std::vector<double> x, double fc, double rate)
{
    const double a = std::exp(-2.0 * M_PI * fc / rate);
    for (int pass = 0; pass < 4; ++pass)
    {
        double s = 0.0;
        for (double& v : x)
            v = s = (1.0 - a) * v + a * s;
    }
    return x;
}
std::vector<double> highPart(std::vector<double> x)
{
    for (int pass = 0; pass < 4; ++pass)
        for (size_t i = x.size(); i-- > 1;)
            x[i] = x[i] - x[i - 1];
    return x;
}
} // namespace

TEST_CASE("the room's diffuse field holds Sabine's energy, 1 / r_c^2 of the source's at 1 m, within 2 dB", "[room]")
{
    for (const double rate : { 48000.0, 32000.0 })
        for (const RoomSpec spec : { RoomSpec { 0.3, 60.0 }, RoomSpec { 1.0, 60.0 }, RoomSpec { 0.5, 500.0 } })
        {
            INFO("T60 " << spec.reverberationTime_s << " s, V " << spec.volume_m3 << " m^3, " << rate << " Hz");
            const double rc = 0.057 * std::sqrt(spec.volume_m3 / spec.reverberationTime_s);
            CHECK(DiffuseRoom(spec, rate).criticalDistance() == Approx(rc));
            const auto h = impulseResponses(spec, rate, 6.0 * spec.reverberationTime_s);
            for (const auto& x : h)
                CHECK(std::abs(10.0 * std::log10(energy(x) * rc * rc)) < 2.0);
        }
}

TEST_CASE("the room's field decays in 1.3 T60 at low frequencies and 0.8 T60 at the highest, within 15 %", "[room]")
{
    const double rate = 48000.0;
    for (const double t60 : { 0.3, 0.8 })
    {
        INFO("T60 " << t60 << " s");
        const auto h = impulseResponses({ t60, 60.0 }, rate, 5.0 * t60);
        for (const auto& x : h)
        {
            CHECK(reverberationTime(lowPart(x, 100.0, rate), rate) == Approx(1.3 * t60).epsilon(0.15));
            CHECK(reverberationTime(highPart(x), rate) == Approx(0.8 * t60).epsilon(0.15));
        }
    }
}

TEST_CASE("the three microphones hear diffuse fields that do not correlate", "[room]")
{
    const auto h = impulseResponses({ 0.5, 60.0 }, 48000.0, 2.0);
    for (int a = 0; a < DiffuseRoom::kOutputs; ++a)
        for (int b = a + 1; b < DiffuseRoom::kOutputs; ++b)
        {
            const double c = std::inner_product(h[(size_t) a].begin(), h[(size_t) a].end(), h[(size_t) b].begin(), 0.0);
            CHECK(std::abs(c) / std::sqrt(energy(h[(size_t) a]) * energy(h[(size_t) b])) < 0.2);
        }
}

TEST_CASE("without a room nothing is added, and the drum plays as in the free field", "[room]")
{
    DiffuseRoom off({ 0.0, 60.0 }, 48000.0);
    CHECK_FALSE(off.active());
    for (int t = 0; t < 100; ++t)
        for (double v : off.listen(t == 0 ? 1.0 : 0.3))
            CHECK(v == 0.0);

    DrumConfig cfg = test::wholeDrum();
    auto render = [](const DrumConfig& c) {
        Drum drum(c);
        drum.strike(5.0, 0.3, 0.0);
        std::vector<double> out(4800);
        for (double& v : out)
            v = drum.step();
        return out;
    };
    const auto free = render(cfg);
    cfg.room = { 0.0, 500.0 }; // a volume without a time is no room
    CHECK(render(cfg) == free);
    cfg.room = { 0.4, 60.0 };
    const auto inRoom = render(cfg);
    CHECK(inRoom != free);
    for (double v : inRoom)
        REQUIRE(std::isfinite(v));
}
