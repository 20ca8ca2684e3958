// The head: grid from the stability bound (eq. 39) and its modes against the ideal membrane.

#include "Parameters.h"
#include "SpectrumPeaks.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

using namespace snaresim;

TEST_CASE("the head grid follows the stability bound eq. 39", "[membrane]")
{
    const DrumConfig cfg = test::losslessHead();
    const Membrane head(cfg.batter, 1.0 / cfg.sampleRate_Hz);
    const double c = std::sqrt(cfg.batter.tension_N_per_m / cfg.batter.density_kg_per_m2);
    // h = sqrt(2) c k at the bound: 2.98 mm and about 11 000 points.
    CHECK(head.grid().spacing() == Approx(std::sqrt(2.0) * c / 44100.0).epsilon(1e-12));
    CHECK(head.grid().spacing() == Approx(2.98e-3).epsilon(0.01));
    // The head is the nodes within R - h/2 of the centre (CircularGrid): as many as the area of
    // that disc holds cells, pi ((R - h/2) / h)^2, to the lattice count's error, O((R/h)^(2/3)),
    // about 0.1 % at 60 nodes per radius. (With R itself the count would be 1.7 % higher.)
    const double h = head.grid().spacing();
    CHECK(head.grid().numInterior() == Approx(std::numbers::pi * std::pow((0.1778 - 0.5 * h) / h, 2)).epsilon(0.005));

    // Coarser: a multiple of the bound of the step itself, or of a shorter design step
    // (MembraneSpec::gridTimeStep_s: the grid of that rate, where it is stable).
    MembraneSpec coarse = cfg.batter;
    coarse.gridCoarseness = 2.0;
    coarse.gridTimeStep_s = 0.0;
    CHECK(Membrane(coarse, 1.0 / 44100.0).grid().spacing() == Approx(2.0 * head.grid().spacing()));
    coarse.gridTimeStep_s = 1.0 / 48000.0;
    CHECK(Membrane(coarse, 1.0 / 44100.0).grid().spacing() == Approx(2.0 * std::sqrt(2.0) * c / 48000.0).epsilon(1e-12));
    coarse.gridCoarseness = 1.05; // 1.05 bounds at 48 kHz are finer than one at 44.1 kHz: the bound
    CHECK(Membrane(coarse, 1.0 / 44100.0).grid().spacing() == Approx(head.grid().spacing()).epsilon(1e-12));
}

TEST_CASE("impossible grids are refused with a clear message", "[membrane]")
{
    DrumConfig finer = test::losslessHead();
    finer.batter.gridCoarseness = 0.9; // below the stability bound
    CHECK_THROWS_WITH(Drum(finer), Catch::Contains("stability bound"));

    DrumConfig tooCoarse = test::losslessHead();
    tooCoarse.sampleRate_Hz = 8000.0;
    tooCoarse.batter.gridCoarseness = 4.0;
    CHECK_THROWS_WITH(Drum(tooCoarse), Catch::Contains("fewer than 4 points"));

    DrumConfig badRate = test::losslessHead();
    badRate.sampleRate_Hz = 0.0;
    CHECK_THROWS_WITH(Drum(badRate), Catch::Contains("sample rate"));

    DrumConfig badTension = test::losslessHead();
    badTension.batter.tension_N_per_m = -3.0;
    CHECK_THROWS_AS(Drum(badTension), std::invalid_argument);
}

namespace
{
// The batter's ring after an off-centre strike (0.55 R, 2 m/s), heard alone at a point off
// every nodal line of the first six modes (its velocity there): `count` samples once the mallet
// has left.
std::vector<double> batterRing(DrumConfig cfg, std::size_t count)
{
    Drum drum(cfg);
    const double R = cfg.batter.radius_m;
    GridDistribution point;
    point.reserve(4);
    drum.batter().grid().makeDistribution(0.5 * R * std::cos(0.35), 0.5 * R * std::sin(0.35), 0.0, point);
    drum.strike(2.0, 0.55, 0.0);
    for (int n = 0; n < 4000 && drum.mallet(0).inPlay(); ++n) // past the contact
        drum.step();
    REQUIRE_FALSE(drum.mallet(0).inPlay());
    std::vector<double> x(count);
    for (auto& v : x)
    {
        drum.step();
        v = drum.batter().sampleNext(point) - drum.batter().sampleNow(point);
    }
    return x;
}
} // namespace

TEST_CASE("the lossless head's modes match the ideal membrane (Bessel zeros)", "[membrane]")
{
    DrumConfig cfg = test::losslessHead();
    const double fs = cfg.sampleRate_Hz;
    const auto x = batterRing(cfg, 1u << 16);

    const double c = std::sqrt(cfg.batter.tension_N_per_m / cfg.batter.density_kg_per_m2);
    const double f01 = 2.4048 * c / (2.0 * std::numbers::pi * cfg.batter.radius_m);
    // Ideal circular membrane, Bessel zeros over j01: (0,1) (1,1) (2,1) (0,2) (3,1)
    const double ratios[] = { 1.0, 3.8317 / 2.4048, 5.1356 / 2.4048, 5.5201 / 2.4048, 6.3802 / 2.4048 };
    // The five strongest peaks below 2.8 f01, in ascending frequency.
    const auto spectrum = test::hannSpectrum(x);
    const auto found = test::peaks(spectrum, fs / (2.0 * (double) spectrum.size()), 0.5 * f01, 2.8 * f01);
    REQUIRE(found.size() >= 5);
    std::vector<double> peaks;
    for (int i = 0; i < 5; ++i)
        peaks.push_back(found[(size_t) i].frequency);
    std::sort(peaks.begin(), peaks.end());
    for (int i = 0; i < 5; ++i)
    {
        INFO("mode " << i << ": " << peaks[(size_t) i] << " Hz, ratio " << peaks[(size_t) i] / peaks[0] << " vs " << ratios[i]);
        CHECK(peaks[(size_t) i] / peaks[0] == Approx(ratios[i]).epsilon(0.01));
    }
    INFO("fundamental " << peaks[0] << " Hz vs 2.4048 c / (2 pi R) = " << f01 << " Hz");
    CHECK(peaks[0] == Approx(f01).epsilon(0.01));
}

TEST_CASE("the product's grids keep the low batter modes at the Bessel frequencies", "[membrane][slow]")
{
    // The product's grids (makeDrumConfig at 48 kHz, designed for the largest tension the
    // control allows) at Quality 2 (twice the bound) and 1, the batter alone (no air, neither
    // the cavity nor the outside air) and lossless, with its state in double and in single
    // precision. Run with -s to see the frequencies.
    const double quality = GENERATE(2.0, 1.0);
    const double precision = GENERATE(0.0, 1.0); // head_precision: double, single
    ParameterSet p;
    p.set(ParamId::headPrecision, precision);
    p.set(ParamId::snaresEngaged, 0.0);
    p.set(ParamId::airModel, 0.0);
    p.set(ParamId::outsideAir, 0.0);
    p.set(ParamId::bandwidth, qualityBandwidth_Hz(quality));
    DrumConfig cfg = makeDrumConfig(p, 48000.0).lossless();
    cfg.outputRate_Hz = 0.0; // at its simulated rate (32 kHz at Quality 2), a step a sample
    Drum drum(cfg);
    const auto x = batterRing(cfg, 1u << 17);

    const double c = std::sqrt(cfg.batter.tension_N_per_m / cfg.batter.density_kg_per_m2);
    const double f01 = 2.4048 * c / (2.0 * std::numbers::pi * cfg.batter.radius_m);
    // Bessel zeros of (0,1) (1,1) (2,1) (0,2) (3,1) (1,2)
    const double zeros[] = { 2.4048, 3.8317, 5.1356, 5.5201, 6.3802, 7.0156 };
    const auto spectrum = test::hannSpectrum(x);
    const auto found = test::peaks(spectrum, cfg.sampleRate_Hz / (2.0 * (double) spectrum.size()), 0.5 * f01, 3.0 * f01);
    // The six strongest peaks, a window's side lobes (within 3 % of a stronger peak) left out.
    std::vector<double> modes;
    for (const auto& peak : found)
    {
        const bool lobe = std::any_of(modes.begin(), modes.end(), [&](double f) { return std::abs(peak.frequency / f - 1.0) < 0.03; });
        if (! lobe)
            modes.push_back(peak.frequency);
        if (modes.size() == 6)
            break;
    }
    REQUIRE(modes.size() == 6);
    std::sort(modes.begin(), modes.end());
    for (int i = 0; i < 6; ++i)
    {
        const double ideal = zeros[i] / zeros[0] * f01;
        INFO("Quality " << quality << (precision > 0.5 ? ", single" : ", double") << ", h " << drum.batter().grid().spacing() * 1e3
                        << " mm, mode " << i << ": " << modes[(size_t) i] << " Hz vs " << ideal << " Hz");
        CHECK(modes[(size_t) i] == Approx(ideal).epsilon(0.005));
    }
}

namespace
{
Membrane losslessHeadIn(HeadPrecision precision)
{
    DrumConfig cfg = test::losslessHead();
    cfg.batter.precision = precision;
    return Membrane(cfg.batter, 1.0 / cfg.sampleRate_Hz);
}
// w^{n+1} with structure at every scale on the disc: x (1 + level) + 2 y^2 (its sign flipped at
// level 1) + a ripple
void setStructured(Membrane& head, int level)
{
    const CircularGrid& g = head.grid();
    const int n = g.width();
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix)
        {
            const int i = g.index(ix, iy);
            if (g.mask()[(size_t) i] > 0.5)
                head.setNextAt(i, 1e-4 * (g.x(ix) * (1 + level) + 2.0 * g.x(iy) * g.x(iy) * (level == 1 ? -1.0 : 1.0) +
                                          0.01 * std::sin(ix * 1.3 + iy * 0.7 + level)));
        }
}
} // namespace

TEST_CASE("the heads' block sums equal the plain sums over their blocks, any side, either precision", "[membrane][mics]")
{
    for (const HeadPrecision precision : { HeadPrecision::double_precision, HeadPrecision::single_precision })
    {
        Membrane head = losslessHeadIn(precision);
        const CircularGrid& g = head.grid();
        const int n = g.width();
        setStructured(head, 0);
        for (int side = 1; side <= 13; ++side) // 1-8 have their own loops, the others share one
        {
            INFO("side " << side << (precision == HeadPrecision::single_precision ? ", single" : ", double"));
            const int blocks = (n + side - 1) / side;
            std::vector<double> got((size_t) (blocks * blocks)), expected((size_t) (blocks * blocks), 0.0);
            head.blockSumsNext(side, got.data());
            for (int iy = 0; iy < n; ++iy)
                for (int ix = 0; ix < n; ++ix)
                    expected[(size_t) ((iy / side) * blocks + ix / side)] += head.nextAt(g.index(ix, iy));
            for (size_t b = 0; b < got.size(); ++b)
                CHECK(got[b] == Approx(expected[b]).margin(1e-13));
        }
    }
}

TEST_CASE("the heads' block accelerations equal the plain second differences over a rectangle's blocks, scaled into every stride-th float", "[membrane][mics]")
{
    for (const HeadPrecision precision : { HeadPrecision::double_precision, HeadPrecision::single_precision })
    {
        Membrane head = losslessHeadIn(precision);
        const CircularGrid& g = head.grid();
        const int n = g.width();
        const double h = g.spacing();
        for (int level = 0; level < 3; ++level) // three time levels
        {
            if (level > 0)
                head.advance();
            setStructured(head, level);
        }
        const int ix0 = n / 5, iy0 = n / 4, columns = n / 2 + 1, rows = n / 2 - 1;
        for (int side = 1; side <= 9; ++side)
        {
            INFO("side " << side << (precision == HeadPrecision::single_precision ? ", single" : ", double"));
            const int bxs = (columns + side - 1) / side, bys = (rows + side - 1) / side;
            std::vector<double> expected((size_t) (bxs * bys), 0.0);
            constexpr int stride = 3;               // every third float, the others untouched
            constexpr double scale = 1.0 / 1.0e-8; // 1 / k^2, as the microphones scale them
            std::vector<float> got((size_t) (bxs * bys * stride), -1.0f);
            head.blockAccelerationsIn(side, ix0, iy0, columns, rows, scale, got.data(), stride);
            for (int iy = 0; iy < rows; ++iy)
                for (int ix = 0; ix < columns; ++ix)
                {
                    const int i = g.index(ix0 + ix, iy0 + iy);
                    expected[(size_t) ((iy / side) * bxs + ix / side)] += h * h * (head.nextAt(i) - 2.0 * head.nowAt(i) + head.prevAt(i));
                }
            for (size_t b = 0; b < expected.size(); ++b)
            {
                CHECK(got[b * stride] == Approx(scale * expected[b]).epsilon(1e-6).margin(1e-9));
                CHECK(got[b * stride + 1] == -1.0f);
            }
        }
    }
}

TEST_CASE("the heads' taken sums equal the plain sums of their state after every change, any side", "[membrane][mics]")
{
    // takeSumsWithBlocks: the volume, the first moments and the blocks' sums taken from the
    // state once the forces are in, against sums in long double over the state as it is, and
    // against the same head keeping running sums.
    for (const HeadPrecision precision : { HeadPrecision::single_precision, HeadPrecision::double_precision })
        for (int side = 1; side <= 13; ++side) // 1-4 have their own loops, the others share one
        {
            const bool single = precision == HeadPrecision::single_precision;
            INFO("side " << side << (single ? ", single" : ", double"));
            Membrane taken = losslessHeadIn(precision);
            Membrane kept = losslessHeadIn(precision);
            taken.takeSumsWithBlocks(side);
            const CircularGrid& g = taken.grid();
            const int n = g.width();
            const double h = g.spacing();
            for (Membrane* head : { &taken, &kept })
            {
                head->keepMoments();
                for (int level = 0; level < 2; ++level)
                {
                    if (level > 0)
                        head->advance();
                    setStructured(*head, level);
                }
                head->computeFree(30.0, -400.0, 250.0); // a tilted pressure: the free update's moments
            }
            const auto check = [&](const char* when) {
                INFO(when);
                long double sum = 0.0L, sx = 0.0L, sy = 0.0L;
                const int blocks = (n + side - 1) / side;
                std::vector<double> got((size_t) (blocks * blocks)), expected((size_t) (blocks * blocks), 0.0);
                for (int iy = 0; iy < n; ++iy)
                    for (int ix = 0; ix < n; ++ix)
                    {
                        const double w = taken.nextAt(g.index(ix, iy));
                        sum += w;
                        sx += (long double) (single ? (double) (float) g.x(ix) : g.x(ix)) * w; // x and y as the state holds them
                        sy += (long double) (single ? (double) (float) g.x(iy) : g.x(iy)) * w;
                        expected[(size_t) ((iy / side) * blocks + ix / side)] += w;
                    }
                const double scale = (double) (std::abs(sum) + std::abs(sx) / 0.1778 + std::abs(sy) / 0.1778);
                CHECK(taken.sweptVolumeNext() == Approx((double) (h * h * sum)).margin(1e-13 * h * h * scale));
                CHECK(taken.tiltNext()[0] == Approx((double) (h * h * sx)).margin(1e-13 * h * h * 0.1778 * scale));
                CHECK(taken.tiltNext()[1] == Approx((double) (h * h * sy)).margin(1e-13 * h * h * 0.1778 * scale));
                CHECK(kept.sweptVolumeNext() == Approx(taken.sweptVolumeNext()).margin(1e-12 * h * h * scale));
                CHECK(kept.tiltNext()[0] == Approx(taken.tiltNext()[0]).margin(1e-12 * h * h * 0.1778 * scale));
                taken.blockSumsNext(side, got.data());
                for (size_t b = 0; b < got.size(); ++b)
                    CHECK(got[b] == Approx(expected[b]).margin(1e-13));
            };
            check("after the free update");
            // the contacts' changes: nodes set one by one and together, a spread force
            const int a = g.index(n / 2, n / 3), b = g.index(n / 3, n / 2), c = g.index(2 * n / 3, n / 2);
            for (Membrane* head : { &taken, &kept })
                head->setNextAt(a, 3e-4);
            check("after a node was set");
            const int nodes[] = { b, c };
            const double values[] = { -2e-4, 5e-4 };
            for (Membrane* head : { &taken, &kept })
                head->setNextAt(nodes, values, nullptr, 2);
            check("after two nodes were set together");
            for (Membrane* head : { &taken, &kept })
                head->clear();
            check("after a clear");
        }
}
