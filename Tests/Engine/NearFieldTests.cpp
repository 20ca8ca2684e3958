// The near field's mass on the heads' higher modes (NearFieldAir.h): its shapes beside the
// outside air's channels, the lossless whole drum's energy with it, and its dampers' passivity.
// Against the air box: DrumAirTests.cpp ("the air box's air loads the batter's higher modes").

#include "BatterModes.h"
#include "Bessel.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace snaresim;

namespace
{
DrumConfig withNearField(DrumConfig c)
{
    c.outside.enabled = c.outside.nearField = true; // the near field comes with the outside air
    return c;
}
} // namespace

TEST_CASE("near field: the shapes, every (m, n) up to the cutoff but the channels' (0,1) and (1,1)", "[nearfield]")
{
    const DrumConfig cfg = withNearField(DrumConfig {});
    const auto shapes = NearFieldAir::shapes(cfg.nearFieldSpec());
    const double top = cfg.outside.nearFieldUpTo_per_m * cfg.batter.radius_m;
    int onBatter = 0;
    for (size_t i = 0; i < shapes.size(); ++i)
    {
        const NearFieldShape& s = shapes[i];
        CHECK(s.zero == Approx(besselZero(s.m, s.n)).epsilon(1e-12));
        CHECK(s.zero <= top);
        CHECK_FALSE((s.m < 2 && s.n == 1));
        if (i > 0 && shapes[i - 1].head == s.head)
            CHECK(s.zero >= shapes[i - 1].zero);
        onBatter += s.head == 0 ? 1 : 0;
    }
    // j <= 60 R = 10.67: (0,2) (0,3), (1,2) (1,3), (2,1) (2,2), (3,1) (3,2), (4,1), (5,1), (6,1),
    // each m > 0 twice (cos, sin)
    CHECK(onBatter == 2 + 2 * 2 + 2 * 2 + 2 * 2 + 2 + 2 + 2);
    CHECK(shapes.front().m == 2);
    CHECK(shapes.front().zero == Approx(5.13562).epsilon(1e-5));
    CHECK(NearFieldAir::shapes(DrumConfig {}.nearFieldSpec()).empty()); // off with the outside air
    CHECK(NearFieldAir::kineticReserve(cfg.nearFieldSpec(), true) == cfg.outside.nearFieldReserve);
    CHECK(NearFieldAir::kineticReserve(DrumConfig {}.nearFieldSpec(), true) == 0.0);
}

TEST_CASE("near field: each channel puts rho_a (1 + coth kH) / k on its mode, its corner above the mode", "[nearfield]")
{
    for (const double rate : { 44100.0, 48000.0, 96000.0 })
    {
        DrumConfig cfg = withNearField(DrumConfig {});
        cfg.sampleRate_Hz = rate;
        const Drum drum(cfg);
        const NearFieldAir& air = drum.nearFieldAir();
        REQUIRE(air.size() == 40);
        for (int i = 0; i < air.size(); ++i)
        {
            const NearFieldShape& s = air.shape(i);
            const MembraneSpec& head = s.head == 0 ? cfg.batter : cfg.carry;
            const double k = s.zero / head.radius_m, rhoA = cfg.cavity.airDensity_kg_per_m3;
            const double mu = rhoA * (1.0 + 1.0 / std::tanh(k * cfg.cavity.shellDepth_m)) / k;
            CHECK(air.arealMass(i) == Approx(mu).epsilon(1e-12));
            const double loaded =
                k * std::sqrt(head.tension_N_per_m / head.density_kg_per_m2) / std::sqrt(1.0 + mu / head.density_kg_per_m2);
            CHECK(air.modeFrequency_Hz(i) == Approx(loaded / (2.0 * M_PI)).epsilon(1e-12));
            // a mass at its mode: the compliance's corner well above it (docs/MODEL.md: 1.7-6.5 times)
            INFO("(" << s.m << "," << s.n << ") on head " << s.head << " at " << rate << " Hz");
            CHECK(air.corner_Hz(i) > 1.5 * air.modeFrequency_Hz(i));
        }
    }
}

TEST_CASE("near field: the (0,n) and (1,n) shapes leave the channels' coordinates and the lowest modes alone", "[nearfield]")
{
    // On a fine grid: each shape's sum, first moment and overlap with (0,1) / (1,1), against its
    // norm (the continuum's are zero; the grid's rim leaves parts in 1e3).
    const double R = 0.1778, h = R / 200.0;
    const DrumConfig cfg = withNearField(DrumConfig {});
    for (const NearFieldShape& s : NearFieldAir::shapes(cfg.nearFieldSpec()))
    {
        if (s.head != 0 || s.m > 1)
            continue;
        const NearFieldShape lowest { 0, s.m, 1, s.sine, besselZero(s.m, 1) };
        double norm = 0.0, sum = 0.0, moment = 0.0, overlap = 0.0, lowNorm = 0.0;
        for (double y = -R; y <= R; y += h)
            for (double x = -R; x <= R; x += h)
            {
                const double v = NearFieldAir::shapeValue(s, R, x, y);
                const double r = std::hypot(x, y),
                             low = r < R ? std::cyl_bessel_j((double) s.m, lowest.zero * r / R) * (s.m == 0 ? 1.0 : (s.sine ? y : x) / r)
                                         : 0.0;
                norm += v * v;
                sum += v;
                moment += v * (s.sine ? y : x) / R;
                overlap += v * low;
                lowNorm += low * low;
            }
        const double n = std::sqrt(norm);
        const double count = M_PI * (R / h) * (R / h);
        INFO("(" << s.m << "," << s.n << (s.sine ? " sin" : " cos") << ")");
        if (s.m == 0)
            CHECK(std::abs(sum) / (n * std::sqrt(count)) < 2e-3);
        else
            CHECK(std::abs(moment) / (n * std::sqrt(count / 4.0)) < 2e-3);
        CHECK(std::abs(overlap) / (n * std::sqrt(lowNorm)) < 2e-3);
        // and it is still most of its mode: the parts taken away are small
        const double full = std::cyl_bessel_j((double) s.m + 1.0, s.zero);
        CHECK(norm * h * h > 0.5 * M_PI * R * R * full * full * (s.m == 0 ? 2.0 : 1.0) / 2.0);
    }
}

TEST_CASE("near field: the lossless whole drum with it conserves energy to round-off", "[nearfield][energy]")
{
    DrumConfig cfg = withNearField(test::wholeDrum()); // 20 wires, cavity, double heads
    cfg.snares.scheme = GENERATE(CollisionScheme::newton, CollisionScheme::quadratised);
    cfg.cavity.modesUpTo_Hz = GENERATE(0.0, 1000.0); // with the cavity's modes the cells' pressures add
    Drum drum(cfg.lossless());
    REQUIRE(drum.nearFieldAir().size() == 2 * 20);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    double largest = 0.0;
    const double drift = test::balanceDrift(drum, 10000, [&] { largest = std::max(largest, std::abs(drum.energy().value("near_field"))); });
    INFO("relative variation " << drift << ", the near field's largest energy " << largest / e0 << " of the strike's");
    CHECK(drift < 1e-11);
    CHECK(largest > 1e-4 * e0); // the channels really hold energy
    if (cfg.snares.scheme == CollisionScheme::newton)
        CHECK(drum.energy().dissipated_J == 0.0); // open resistances, no damper
}

TEST_CASE("near field: with single-precision heads the lossless drum holds its energy to float round-off", "[nearfield][energy][precision]")
{
    // the product's heads; bound as for the heads alone (HeadPrecisionTests.cpp): 2^-24 sqrt(n)
    const double drift = test::singlePrecisionDrift(withNearField(test::wholeDrum()), 20000), bound = test::floatDriftBound(20000);
    INFO("relative energy variation " << drift << " (bound " << bound << ")");
    CHECK(drift < bound);
}

TEST_CASE("near field: its dampers only take energy, and energy + losses is constant", "[nearfield][energy]")
{
    // lossless heads and wires, the outside air's resistances open: only the dampers remove energy
    DrumConfig cfg = withNearField(test::wholeDrum()).lossless();
    cfg.outside.nearFieldDamping = 1.0;
    cfg.snares.scheme = CollisionScheme::newton;
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.1);
    const double e0 = drum.energy().total();
    const test::Passivity p = test::passivity(drum, 20000);
    INFO("largest rise " << p.worstRise << ", balance drift " << p.worstBalance << ", the dampers took " << drum.energy().dissipated_J / e0
                         << " of the strike's energy");
    CHECK(p.worstRise <= 1e-15);
    CHECK(p.worstBalance < 1e-11);
    CHECK(drum.energy().dissipated_J > 0.0);
}

TEST_CASE("near field: its dampers barely touch the heads' modes below the channels' corners", "[nearfield]")
{
    // The batter's loaded modes with lossless heads, the outside air's resistances open: what the
    // dampers add to their decay. The compliance hardly moves at a mode below its channel's
    // corner; measured 0.8-3.4 dB/s, where the heads' own damping is 15 dB/s at its least
    // (damping 0 %, T60 4 s) and 175 dB/s by default.
    const std::vector<test::BatterMode> modes {
        { 2, 5.13562, "(2,1)" }, { 3, 6.38016, "(3,1)" }, { 4, 7.58834, "(4,1)" }, { 2, 8.41724, "(2,2)" }
    };
    DrumConfig cfg = withNearField(test::wholeDrum()).lossless();
    cfg.snares.engaged = false;
    DrumConfig damped = cfg;
    damped.outside.nearFieldDamping = 1.0;
    const int steps = 1 << 15;
    const auto free = test::batterModeCoordinates(cfg, modes, steps), held = test::batterModeCoordinates(damped, modes, steps);
    const double fs = cfg.sampleRate_Hz, R = cfg.batter.radius_m;
    for (size_t q = 0; q < modes.size(); ++q)
    {
        const double loaded = 0.92 * modes[q].j * std::sqrt(cfg.batter.tension_N_per_m / cfg.batter.density_kg_per_m2) / (2.0 * M_PI * R);
        const double f = test::peakNear(held[q], fs, loaded);
        const double added = test::bandDecay_dB_per_s(held[q], fs, f) - test::bandDecay_dB_per_s(free[q], fs, f);
        INFO(modes[q].name << " at " << f << " Hz: the dampers add " << added << " dB/s");
        CHECK(added > 0.0);
        CHECK(added < 5.0);
    }
}

TEST_CASE("near field: a config that cannot work is refused with a readable message", "[nearfield]")
{
    DrumConfig cfg = withNearField(test::wholeDrum());
    CHECK_NOTHROW(cfg.validate());
    DrumConfig bad = cfg;
    bad.outside.nearFieldReserve = 0.0;
    CHECK_THROWS_WITH(bad.validate(), Catch::Contains("near field's reserve"));
    bad = cfg;
    bad.outside.nearFieldDamping = 2.0;
    CHECK_THROWS_WITH(bad.validate(), Catch::Contains("near field's damping"));
    bad = cfg;
    bad.outside.nearFieldUpTo_per_m = -1.0;
    CHECK_THROWS_WITH(bad.validate(), Catch::Contains("near field's largest wavenumber"));
    bad = cfg;
    bad.outside.nearFieldCellSize_m = std::nan("");
    CHECK_THROWS_WITH(bad.validate(), Catch::Contains("near field's cells"));
}
