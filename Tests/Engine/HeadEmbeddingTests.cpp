// A head embedded in the air box (eq. 7-8): J conserves volume, the coupling conserves the total
// energy to round-off on a head finer and one coarser than the air, a force on a head coarser
// than the air is solved with it in one go, and the air's mass lowers the head's (0,1) mode.

#include "AirBox.h"
#include "HeadEmbedding.h"
#include "Membrane.h"
#include "Pluck01.h"
#include "Report.h"
#include "SpectrumPeaks.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

using namespace snaresim;

namespace
{
constexpr double fs = 44100.0;

// coarseness 1: h = 2.98 mm, finer than the air (13.47 mm at 44.1 kHz); 5: h = 14.9 mm, coarser
MembraneSpec losslessBatter(double coarseness = 1.0)
{
    MembraneSpec s;             // R = 0.1778 m, rho = 0.353 kg/m^2
    s.tension_N_per_m = 3050.0; // (0,1) at 200 Hz in vacuum
    s.sigma0_per_s = 0.0;
    s.sigma1_m2_per_s = 0.0;
    s.gridCoarseness = coarseness;
    return s;
}

using test::pluck01;

// Frequency of the strongest peak of x in [lo, hi] Hz.
double peakFrequency(const std::vector<double>& x, double lo, double hi)
{
    const size_t pad = 8;
    const auto X = test::hannSpectrum(x, pad);
    const auto found = test::peaks(X, fs / (double) (pad * x.size()), lo, hi);
    REQUIRE_FALSE(found.empty());
    return found.front().frequency;
}

AirBoxSpec losslessBox()
{
    AirBoxSpec spec;
    spec.sigma_m = 0.0;
    spec.walls = AirWalls::reflecting;
    spec.shell = false;
    spec.size_m = { 0.6, 0.6, 0.6 };
    return spec;
}
} // namespace

TEST_CASE("the embedding's J conserves volume and links the head's nodes to the air's over it", "[airbox][embedding]")
{
    const double k = 1.0 / fs;
    AirBox air(losslessBox(), k);
    // h_m = 2.98, 8.5 (the default batter's), 14.9 and 40.2 mm (about 9 air nodes to a head node)
    for (double coarseness : { 1.0, 2.85, 5.0, 13.5 })
    {
        Membrane head(losslessBatter(coarseness), k);
        HeadEmbedding embed(air, head, 0.0);
        const CircularGrid& g = head.grid();
        snaresim::test::reportf(
            "embedding: head h = %.2f mm (%d nodes), air h = %.2f mm: %d air nodes over the head, %d groups, J reaches %d "
            "head nodes; volume the air sees / the head's %.15f\n",
            1e3 * g.spacing(), g.numInterior(), 1e3 * air.spacing(), embed.airNodes(), embed.groups(), embed.headNodes(),
            embed.volumeRatio());
        CHECK(embed.airCoarser() == (air.spacing() >= g.spacing()));
        CHECK(embed.volumeRatio() == Approx(1.0).margin(1e-12));
        if (embed.airCoarser())
        {
            CHECK(embed.headNodes() == g.numInterior()); // every head node has its air node
            CHECK(embed.groups() <= embed.airNodes());
        }
        else
        {
            CHECK(embed.headNodes() == embed.groups());       // one head node a group
            CHECK(embed.headNodes() > 0.9 * g.numInterior()); // all but nodes at the rim
        }
        // the head's response to a force: the diagonal of (1 + gamma J^T J)^{-1}, below 1 where J reaches
        int reached = 0;
        for (int j = 0; j < g.numNodes(); ++j)
            if (g.mask()[(size_t) j] != 0.0 && head.forceGainAt(j) != head.forceGain())
            {
                ++reached;
                CHECK(head.forceGainAt(j) < head.forceGain());
                CHECK(head.forceGainAt(j) > 0.5 * head.forceGain());
            }
        CHECK(reached == embed.headNodes());
    }
}

TEST_CASE("a head embedded in lossless air conserves the total energy to round-off", "[airbox][embedding][energy][slow]")
{
    const double k = 1.0 / fs;
    // the head finer than the air, coarser, and three times coarser (about 9 air nodes to a head node)
    const double coarseness = GENERATE(1.0, 5.0, 13.5);
    AirBox air(losslessBox(), k);
    Membrane head(losslessBatter(coarseness), k);
    HeadEmbedding embed(air, head, 0.0);
    snaresim::test::reportf(
        "embedding: head h = %.3f mm (%d nodes), air h = %.3f mm (%ld points); %d air nodes over the head, J reaches %d head nodes\n",
        1e3 * head.grid().spacing(), head.grid().numInterior(), 1e3 * air.spacing(), air.numPoints(), embed.airNodes(), embed.headNodes());
    REQUIRE(embed.airNodes() > 500);
    pluck01(head);

    const int steps = coarseness > 10.0 ? 2000 : 10000; // the coarsest head: its shape of groups, not its long run
    double e0 = 0.0, drift = 0.0, airMax = 0.0;
    for (int n = 0; n < steps; ++n)
    {
        air.computeNext();
        head.computeFree();
        embed.step();
        const double ea = air.energy(), e = head.energy() + ea;
        if (n == 0)
            e0 = e;
        drift = std::max(drift, std::abs(e - e0) / e0);
        airMax = std::max(airMax, ea / e0);
        air.advance();
        head.advance();
    }
    snaresim::test::reportf(
        "embedded head (h = %.2f mm), lossless: total energy relative variation %.3g over %d steps; the air held up to %.3g of it\n",
        1e3 * head.grid().spacing(), drift, steps, airMax);
    CHECK(drift < 1e-11);
    CHECK(airMax > 0.05); // the coupling really moved energy into the air
    CHECK(head.isFinite());
}

TEST_CASE("the air's mass lowers the head's (0,1) mode", "[airbox][embedding][slow]")
{
    const double k = 1.0 / fs;
    const int steps = 16384;
    const int centre = [&] {
        const Membrane probe(losslessBatter(), k);
        return probe.grid().nearestInterior(0.0, 0.0);
    }();

    std::vector<double> vacuum, inAir[2];
    {
        Membrane head(losslessBatter(), k);
        pluck01(head);
        for (int n = 0; n < steps; ++n)
        {
            head.computeFree();
            head.advance();
            vacuum.push_back(head.nowAt(centre));
        }
    }
    for (int walls = 0; walls < 2; ++walls)
    {
        AirBoxSpec spec = losslessBox();
        spec.walls = walls == 0 ? AirWalls::reflecting : AirWalls::absorbing;
        AirBox air(spec, k);
        Membrane head(losslessBatter(), k);
        HeadEmbedding embed(air, head, 0.0);
        pluck01(head);
        for (int n = 0; n < steps; ++n)
        {
            air.computeNext();
            head.computeFree();
            embed.step();
            air.advance();
            head.advance();
            inAir[walls].push_back(head.nowAt(centre));
        }
    }
    const double f0 = peakFrequency(vacuum, 100.0, 300.0);
    const double fr = peakFrequency(inAir[0], 60.0, 300.0), fa = peakFrequency(inAir[1], 60.0, 300.0);
    snaresim::test::reportf(
        "(0,1) mode of the batter (T = 3050 N/m): %.1f Hz in vacuum, %.1f Hz in a 0.6 m box of air with reflecting walls, "
        "%.1f Hz with absorbing walls\n",
        f0, fr, fa);
    CHECK(f0 == Approx(200.0).epsilon(0.01));
    CHECK(fr < 0.95 * f0);
    CHECK(fa < 0.95 * f0);

    // The air's added mass m_a lowers f by 1 / sqrt(1 + m_a / m), m = rho pi R^2 J1(j01)^2 the
    // mode's own mass. In an infinite baffle, the air on one side of the head adds
    // m_1 = rho_a / (2 pi) int |V(kappa)|^2 dkappa (V the mode shape's Hankel transform; at low
    // frequency, incompressible). The head alone has air on both sides: no more than 2 m_1
    // (the baffle only constrains the flow, and the flow without it has the least kinetic
    // energy: Kelvin), and the flow round the rim relieves it towards m_1 (a rigid disc without
    // a baffle carries exactly m_1, 8 rho_a R^3 / 3).
    const double R = losslessBatter().radius_m, rho = losslessBatter().density_kg_per_m2, j01 = 2.404825557695773;
    const double modal = rho * std::numbers::pi * R * R * std::pow(std::cyl_bessel_j(1.0, j01), 2.0);
    double one = 0.0;
    const double k0 = j01 / R, dk = 0.002 / R, scale = 2.0 * std::numbers::pi * R * k0 * std::cyl_bessel_j(1.0, j01);
    for (double kappa = 0.5 * dk; kappa < 5000.0 / R; kappa += dk)
    {
        const double V = scale * std::cyl_bessel_j(0.0, kappa * R) / (k0 * k0 - kappa * kappa);
        one += V * V * dk;
    }
    one *= 1.21 / (2.0 * std::numbers::pi);
    const double fOne = f0 / std::sqrt(1.0 + one / modal), fTwo = f0 / std::sqrt(1.0 + 2.0 * one / modal);
    // Decay: with reflecting walls nothing leaves the box; absorbing walls take what the head radiates.
    const double rr = test::bandDecay_dB_per_s(inAir[0], fs, fr), ra = test::bandDecay_dB_per_s(inAir[1], fs, fa);
    snaresim::test::reportf(
        "(0,1) mode: drop %.1f %% (reflecting) and %.1f %% (absorbing); a baffled head with air on one side %.1f Hz (%.1f %%), "
        "on both %.1f Hz (%.1f %%); decay %.3f dB/s (reflecting), %.1f dB/s (absorbing, T60 %.2f s)\n",
        100.0 * (1.0 - fr / f0), 100.0 * (1.0 - fa / f0), fOne, 100.0 * (1.0 - fOne / f0), fTwo, 100.0 * (1.0 - fTwo / f0), rr, ra,
        60.0 / ra);
    for (double f : { fr, fa })
    {
        CHECK(f < fOne);
        CHECK(f > fTwo);
    }
    // Lossless: no slope beyond the beating with the box's air, 1 dB over the fit's span (at most 80 % of the record).
    CHECK(std::abs(rr) < 1.0 / (0.8 * steps / fs));
    CHECK(ra > 10.0);
}

TEST_CASE("a force on a head coarser than the air is solved with the air in one trial", "[airbox][embedding]")
{
    // Each head node has its own air nodes, so (1 + gamma J^T J)^{-1} is diagonal: the force's
    // response through Membrane::forceGainAt is already the joint solution, and correct() finds
    // nothing to change. On a head finer than the air a force at one node also pulls the other
    // nodes of its air node's group, and one more trial settles it.
    const double k = 1.0 / fs;
    for (double coarseness : { 5.0, 1.0 })
    {
        AirBox air(losslessBox(), k);
        Membrane head(losslessBatter(coarseness), k);
        HeadEmbedding embed(air, head, 0.0);
        pluck01(head);
        for (int n = 0; n < 50; ++n)
        {
            air.computeNext();
            head.computeFree();
            embed.step();
            air.advance();
            head.advance();
        }
        GridDistribution point;
        point.reserve(head.grid().distributionCapacity(0.0));
        REQUIRE(head.grid().makeDistribution(0.031, -0.017, 0.0, point)); // bilinear: four nodes
        air.computeNext();
        head.computeFree();
        embed.solveFree();
        head.applyForce(point, 2.0);
        const double first = embed.correct() / embed.scale();
        double second = 0.0;
        if (first > 1e-15)
        {
            embed.retry();
            head.applyForce(point, 2.0); // a force that does not depend on the head
            second = embed.correct() / embed.scale();
        }
        embed.finish();
        snaresim::test::reportf(
            "a 2 N force at four nodes, head h = %.2f mm: mismatch after the first trial %.3g of max |w|, after the second %.3g\n",
            1e3 * head.grid().spacing(), first, second);
        if (! embed.airCoarser())
            CHECK(first <= 1e-15);
        else
        {
            CHECK(first > 1e-12);
            CHECK(second <= 1e-15);
        }
        CHECK(head.isFinite());
    }
}
