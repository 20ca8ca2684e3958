// The outside air of the reduced model (OutsideAir.h): its energy with the whole drum, its
// passivity, and the lowest modes it gives against the drum in the air box.

#include "LowModes.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace snaresim;

namespace
{
DrumConfig withOutsideAir(DrumConfig c)
{
    c.outside.enabled = c.outside.nearField = true; // as the air box has it: the channels and the near field
    return c;
}
} // namespace

TEST_CASE("outside air: the lossless whole drum with it conserves energy to round-off", "[outside][energy]")
{
    DrumConfig cfg = withOutsideAir(test::wholeDrum()); // 20 wires, cavity, double heads
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    Drum drum(cfg.lossless());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    double drift = 0.0, largestAir = 0.0;
    for (int n = 0; n < 10000; ++n)
    {
        drum.step();
        drift = std::max(drift, std::abs(drum.energy().balance() - b0) / e0);
        largestAir = std::max(largestAir, std::abs(drum.energy().value("outside")));
    }
    INFO("relative variation " << drift << ", the outside air's largest energy " << largestAir / e0 << " of the strike's");
    CHECK(drift < 1e-11);
    CHECK(largestAir > 1e-3 * e0); // the channels really hold energy
    if (cfg.snares.scheme == CollisionScheme::newton)
        CHECK(drum.energy().dissipated_J == 0.0); // the open resistances radiate nothing
}

TEST_CASE("outside air: with its resistances the energy never rises and energy + losses is constant", "[outside][energy]")
{
    // lossless heads and wires: only the radiation (and the near field's dampers) remove energy.
    // A soft stick that strikes once: the test drum's stiff one chatters on the batter's grid
    // (22 contacts in 7 ms), and the share it sends into the radiating (0,1) modes moves with the
    // grid (6.3 % radiated in 0.45 s; 4.0 % with a grid 2 % coarser and the same air), the single
    // contact's by a tenth as much (22 % and 19.5 %).
    DrumConfig cfg = withOutsideAir(test::wholeDrum());
    const DrumConfig lossless = cfg.lossless();
    cfg.batter = lossless.batter;
    cfg.carry = lossless.carry;
    cfg.snares = lossless.snares;
    cfg.snares.scheme = CollisionScheme::newton;
    cfg.mallet.stiffness = 1.0e6;
    cfg.mallet.mass_kg = 0.012;
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    const test::Passivity p = test::passivity(drum, 20000);
    INFO("largest rise " << p.worstRise << ", balance drift " << p.worstBalance << ", radiated " << drum.energy().dissipated_J / e0
                         << " of the strike's energy");
    CHECK(p.worstRise <= 1e-15);
    CHECK(p.worstBalance < 1e-11);
    CHECK(drum.energy().dissipated_J > 0.1 * e0); // the drum radiates a real share in 0.45 s
}

TEST_CASE("outside air: the drum's lowest modes match the air box's within 2 % in frequency and 25 % in decay", "[outside][airbox][slow]")
{
    // The same drum (the pair tables' grids, snares off, lossless heads) in the reduced model
    // and in a 1.4 m air box with absorbing walls, measured alike (LowModes.h). The box's figures
    // are its own here; docs/MODEL.md gives them for 1.8 m too.
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.engaged = false;
    cfg.cavity.gridShellDepth_m = 0.05;
    DrumConfig box = cfg.lossless();
    box.cavity.model = AirModel::airbox;
    box.airBox.walls = AirWalls::absorbing;
    box.airBox.size_m = { 1.4, 1.4, 1.4 };
    box.airBox.threads = 2;
    // The box's anti-phase (0,1) mode radiates fast (about 830 dB/s) and lies more than 30 dB
    // under the strongest peak of the volumes' difference, so it is looked for within 5 % of
    // where the box's own figures put it (docs/MODEL.md, "Outside air": 345.7 Hz,
    // Lab/airbox_figures); not found there, it is 0 Hz and the comparison fails.
    const test::LowModes air = test::lowModes(box, 1 << 14, { 0.0, 345.7 });

    const auto compare = [&](const DrumConfig& model, bool shouldMatch) {
        const test::LowModes m = test::lowModes(model, 1 << 14, { 0.0, air.antiPhase.frequency_Hz });
        const test::Mode pairs[4][2] = {
            { m.inPhase, air.inPhase }, { m.antiPhase, air.antiPhase }, { m.batter11, air.batter11 }, { m.carry11, air.carry11 }
        };
        bool all = true;
        for (const auto& p : pairs)
        {
            INFO("model " << p[0].frequency_Hz << " Hz, " << p[0].decay_dB_per_s << " dB/s; air box " << p[1].frequency_Hz << " Hz, "
                          << p[1].decay_dB_per_s << " dB/s");
            const bool match = p[1].frequency_Hz > 0.0 && std::abs(p[0].frequency_Hz / p[1].frequency_Hz - 1.0) < 0.02 &&
                               std::abs(p[0].decay_dB_per_s / p[1].decay_dB_per_s - 1.0) < 0.25;
            if (shouldMatch)
                CHECK(match);
            all = all && match;
        }
        return all;
    };
    DrumConfig model = withOutsideAir(cfg).lossless();
    model.outside = withOutsideAir(cfg).outside; // lossless heads, the radiation's resistances kept
    CHECK(compare(model, true));
    // The cavity alone (no outside air) is far from it: the comparison can fail.
    CHECK_FALSE(compare(cfg.lossless(), false));
}

TEST_CASE("outside air: a config that enables it builds its channels, and the air box keeps its own", "[outside]")
{
    DrumConfig cfg = withOutsideAir(test::wholeDrum());
    Drum drum(cfg);
    CHECK(drum.outsideAir().active());
    // the heads keep a share of their kinetic energy for the explicit channels (OutsideAir.h)
    CHECK(cfg.kineticReserve(false) > test::wholeDrum().kineticReserve(false));
    DrumConfig box = cfg;
    box.cavity.model = AirModel::airbox;
    box.airBox.size_m = { 0.48, 0.48, 0.4 };
    Drum inBox(box);
    CHECK_FALSE(inBox.outsideAir().active());
    DrumConfig bad = cfg;
    bad.outside.monopole.mass = 0.0;
    CHECK_THROWS_WITH(bad.validate(), Catch::Contains("outside-air channel's mass"));
}

TEST_CASE("outside air: the schema's default plays the channels, the near field on its own switch", "[outside]")
{
    ParameterSet p; // the defaults
    const DrumConfig channels = makeDrumConfig(p, 48000.0);
    CHECK(channels.outside.enabled);
    CHECK_FALSE(channels.outside.nearField);
    Drum drum(channels);
    CHECK(drum.outsideAir().active());
    CHECK_FALSE(drum.nearFieldAir().active());
    p.set(ParamId::nearField, 1.0);
    Drum complete(makeDrumConfig(p, 48000.0));
    CHECK(complete.outsideAir().active());
    CHECK(complete.nearFieldAir().active());
    // the near field comes with the outside air only
    p.set(ParamId::outsideAir, 0.0);
    Drum none(makeDrumConfig(p, 48000.0));
    CHECK_FALSE(none.outsideAir().active());
    CHECK_FALSE(none.nearFieldAir().active());
}
