// The mallet strikes and rebounds (eq. 9-11, 26-27, 44-45).

#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

using namespace snaresim;

TEST_CASE("the mallet rebounds after a physically sensible contact", "[mallet]")
{
    const DrumConfig cfg = test::losslessHead();
    Drum drum(cfg);
    const double v0 = 5.0, strikeRadius = 0.3;
    drum.strike(v0, strikeRadius, 0.0);
    const double k = 1.0 / cfg.sampleRate_Hz;

    int contactSteps = 0;
    double peakCompression = 0.0, vOut = 0.0;
    for (int n = 0; n < 4000 && drum.mallet(0).inPlay(); ++n)
    {
        drum.step();
        const Mallet& m = drum.mallet(0);
        if (m.etaNow > 0.0)
            ++contactSteps;
        peakCompression = std::max(peakCompression, m.etaNow);
        if (m.inPlay())
            vOut = (m.zNow - m.zPrev) / k;
    }
    const double contactTime = contactSteps * k;
    INFO("contact " << contactTime * 1e3 << " ms, peak compression " << peakCompression * 1e3 << " mm, rebound " << vOut << " m/s");

    // Expected ranges, from two limits:
    // - rigid barrier (kappa = 1e8, alpha = 1.5, M = 0.028 kg, 5 m/s): peak compression
    //   ((alpha+1) M v^2 / (2 kappa))^(1/(alpha+1)) = 0.60 mm, contact 2.94 x that / v = 0.35 ms.
    //   A yielding head takes part of the energy: less compression, longer contact.
    // - the mallet riding the head's (0,1) mode: modal mass m01 = rho pi R^2 J1(j01)^2 (9.5 g),
    //   stiffness K01 = (2 pi f01)^2 m01 (14.9 kN/m); struck where the mode shape is
    //   phi = J0(j01 r/R), half a period is pi sqrt((M phi^2 + m01) / K01) (4.5 ms). Higher
    //   modes add compliance; the contact must be within a factor 2 of that.
    const double M = cfg.mallet.mass_kg, kappa = cfg.mallet.stiffness, alpha = cfg.mallet.exponent;
    const double rigidCompression = std::pow((alpha + 1.0) * M * v0 * v0 / (2.0 * kappa), 1.0 / (alpha + 1.0));
    CHECK(rigidCompression == Approx(0.60e-3).epsilon(0.02));
    const double j01 = 2.404825557695773, R = cfg.batter.radius_m, rho = cfg.batter.density_kg_per_m2;
    const double f01 = j01 * std::sqrt(cfg.batter.tension_N_per_m / rho) / (2.0 * std::numbers::pi * R);
    const double m01 = rho * std::numbers::pi * R * R * std::pow(std::cyl_bessel_j(1.0, j01), 2);
    const double K01 = std::pow(2.0 * std::numbers::pi * f01, 2) * m01;
    CHECK(K01 == Approx(14.9e3).epsilon(0.02));
    const double phi = std::cyl_bessel_j(0.0, j01 * strikeRadius);
    const double halfPeriod = std::numbers::pi * std::sqrt((M * phi * phi + m01) / K01);

    CHECK(vOut > 0.0); // it moves up after the contact
    CHECK(vOut < v0);  // having given energy to the head
    CHECK(contactTime > 0.35e-3);
    CHECK(contactTime > 0.5 * halfPeriod);
    CHECK(contactTime < 2.0 * halfPeriod);
    CHECK(peakCompression < rigidCompression);
    // The peak force is at least the mean force M (v0 + vOut) / t_c that turned the mallet.
    const double meanForce = M * (v0 + vOut) / contactTime;
    CHECK(kappa * std::pow(peakCompression, alpha) > meanForce);
    CHECK_FALSE(drum.mallet(0).inPlay()); // risen past 1 cm and taken back
}

TEST_CASE("strikes with bad values are ignored and never produce non-finite output", "[mallet]")
{
    const DrumConfig cfg = test::lossyHead();
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.strike(std::nan(""), 0.3, 0.0);
    drum.strike(-1.0, 0.3, 0.0);
    drum.strike(5.0, std::numeric_limits<double>::infinity(), 0.0);
    CHECK(drum.energy().injected_J == 0.0); // no mallet was launched
    for (int n = 0; n < 100; ++n)
        REQUIRE(drum.step() == 0.0);
    drum.strike(1000.0, 3.0, 3.0); // absurd speed and a point off the head: clamped, still finite
    // The speed is clamped to 50 m/s: the mallet brings (1/2) M (50 m/s)^2.
    CHECK(drum.energy().injected_J == Approx(0.5 * cfg.mallet.mass_kg * 50.0 * 50.0).epsilon(1e-12));
    double peak = 0.0;
    for (int n = 0; n < 2000; ++n)
    {
        const double y = drum.step();
        REQUIRE(std::isfinite(y));
        peak = std::max(peak, std::abs(y));
    }
    CHECK(peak > 0.0);
}

TEST_CASE("velocity curve spans pianissimo to fortissimo", "[mallet]")
{
    CHECK(strikeSpeedFromVelocity(127, 6.0) == Approx(6.0));
    CHECK(strikeSpeedFromVelocity(1, 6.0) == Approx(6.0 / std::pow(10.0, 1.6)));
    for (int v = 2; v <= 127; ++v)
        CHECK(strikeSpeedFromVelocity(v, 6.0) > strikeSpeedFromVelocity(v - 1, 6.0));
    CHECK(strikeSpeedFromVelocity(0, 6.0) == strikeSpeedFromVelocity(1, 6.0));
    CHECK(strikeSpeedFromVelocity(200, 6.0) == strikeSpeedFromVelocity(127, 6.0));
}
