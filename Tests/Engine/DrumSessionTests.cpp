// The engine's one door (DrumSession.h): the parameters as set, the air model as each mode plays
// it, a render's build errors and its rebuilds at their sample.

#include "DrumSession.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <stdexcept>

using namespace snaresim;

namespace
{
ParameterSet cheapDrum()
{
    ParameterSet p;
    p.set(ParamId::bandwidth, spec(ParamId::bandwidth).minValue);
    p.set(ParamId::snareCount, 4.0);
    return p;
}

double airModelOf(const ParameterSet& p) { return p.get(ParamId::airModel); }
} // namespace

TEST_CASE("a session holds the parameters clamped into range", "[session]")
{
    DrumSession session(DrumSession::Mode::render);
    CHECK(session.parameters().get(ParamId::batterTension) == spec(ParamId::batterTension).defaultValue);
    session.setParameter(ParamId::batterTension, 1.0e9);
    CHECK(session.parameters().get(ParamId::batterTension) == spec(ParamId::batterTension).maxValue);
    session.setParameter(ParamId::batterTension, std::nan(""));
    CHECK(std::isfinite(session.parameters().get(ParamId::batterTension)));
    session.setParameter(ParamId::snareCount, 7.4);
    CHECK(session.parameters().get(ParamId::snareCount) == 7.0);
}

TEST_CASE("each mode plays the air model its host asks for", "[session]")
{
    ParameterSet p = cheapDrum();
    p.set(ParamId::airModel, (double) AirModel::cavity);
    p.set(ParamId::offlineAirBox, 1.0);

    // The renderer plays the parameters as given, whatever the host's switches say.
    DrumSession render(DrumSession::Mode::render);
    render.setParameters(p);
    CHECK(airModelOf(render.playedParameters()) == (double) AirModel::cavity);
    render.setOffline(true); // a render stays a render
    CHECK(render.mode() == DrumSession::Mode::render);

    // A bounce plays the air box when "Air box when bouncing" is on, the air model when it is off.
    DrumSession host(DrumSession::Mode::live);
    host.setParameters(p);
    host.setOffline(true);
    CHECK(host.mode() == DrumSession::Mode::bounce);
    CHECK(airModelOf(host.playedParameters()) == (double) AirModel::airbox);
    CHECK(host.airBoxNotice() == "Air box: the host renders offline, the air box plays");
    host.setParameter(ParamId::offlineAirBox, 0.0);
    CHECK(airModelOf(host.playedParameters()) == (double) AirModel::cavity);
    CHECK(host.airBoxNotice().empty());
    host.setOffline(false);
    CHECK(host.mode() == DrumSession::Mode::live);
    host.stop();
}

TEST_CASE("a render session reports a drum it cannot build, a live one falls back", "[session]")
{
    DrumSession render(DrumSession::Mode::render);
    render.setParameters(cheapDrum());
    CHECK_THROWS_AS(render.prepareAndStart(0.0, 256), std::invalid_argument);

    DrumSession live(DrumSession::Mode::live);
    live.setParameters(cheapDrum());
    CHECK_NOTHROW(live.prepareAndStart(0.0, 256));
    CHECK(live.drumPlayer().drum() == nullptr); // silence, never a crash
    std::array<float, 64> out {};
    out.fill(1.0f);
    live.process(out.data(), (int) out.size(), {});
    for (const float x : out)
        CHECK(x == 0.0f);
    live.stop();
}

TEST_CASE("in a render a parameter that needs a new drum builds it at its event", "[session]")
{
    DrumSession session(DrumSession::Mode::render);
    session.setParameters(cheapDrum());
    session.prepareAndStart(48000.0, 256);
    auto& player = session.drumPlayer();
    REQUIRE(player.drum() != nullptr);
    CHECK(player.drum()->config().snares.count == 4);
    const int swaps = player.modelSwapCount();

    std::array<float, 256> out {};
    const PlayerEvent events[] = { PlayerEvent::strikeAt(0, 100), PlayerEvent::parameterChange(100, ParamId::snareCount, 6.0) };
    session.process(out.data(), (int) out.size(), events);

    CHECK(session.parameters().get(ParamId::snareCount) == 6.0);
    CHECK(player.modelSwapCount() == swaps + 1);
    REQUIRE(player.drum() != nullptr);
    CHECK(player.drum()->config().snares.count == 6);
    // The strike rang before the event; the new drum is crossfaded in after it.
    double before = 0.0;
    for (int i = 0; i < 100; ++i)
        before = std::max(before, (double) std::abs(out[(std::size_t) i]));
    CHECK(before > 0.0);
    for (const float x : out)
        CHECK(std::isfinite(x));
}
