// The 3D air box (eq. 5, 25, 36, 41, 51): grid bound, energy to round-off, absorbing walls,
// free-field propagation.

#include "AirBox.h"
#include "Report.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace snaresim;

namespace
{
constexpr double fs = 44100.0;

// A smooth Gaussian of Psi (at rest), width w, centred at (x0, y0, z0).
auto gaussian(double x0, double y0, double z0, double w)
{
    return [=](double x, double y, double z) {
        const double r2 = (x - x0) * (x - x0) + (y - y0) * (y - y0) + (z - z0) * (z - z0);
        return std::exp(-r2 / (2.0 * w * w));
    };
}
} // namespace

TEST_CASE("the air grid follows the stability bound eq. 41", "[airbox]")
{
    AirBoxSpec spec;
    spec.shell = false;
    const double k = 1.0 / fs, c = spec.soundSpeed_m_per_s, sig = spec.sigma_m;
    const AirBox box(spec, k);
    // h^2 = 3 c^2 k^2 + 6 c sigma k: 13.47 mm at 44.1 kHz (sigma_a = 2e-6 m adds 0.03 %)
    CHECK(box.spacing() == Approx(std::sqrt(3.0 * c * c * k * k + 6.0 * c * sig * k)).epsilon(1e-14));
    CHECK(box.spacing() == Approx(13.47e-3).epsilon(0.001));
    // a 0.6 m cube: ceil(0.6 / h) = 45 points a side, 91 125 in all
    snaresim::test::reportf("air box 0.6 m cube at 44.1 kHz: h = %.5f m, %d x %d x %d = %ld points\n", box.spacing(), box.nx(), box.ny(),
                            box.nz(), box.numPoints());
    CHECK(box.nx() == 45);
    CHECK(box.numPoints() == 91125);

    AirBoxSpec coarse = spec;
    coarse.gridCoarseness = 1.5;
    CHECK(AirBox(coarse, k).spacing() == Approx(1.5 * box.spacing()).epsilon(1e-14));
    // the grid is built for the largest sigma_a allowed, so changing sigma_a below it keeps the grid
    AirBoxSpec design = spec;
    design.gridSigma_m = 1e-4;
    CHECK(AirBox(design, k).spacing() == Approx(std::sqrt(3.0 * c * c * k * k + 6.0 * c * 1e-4 * k)).epsilon(1e-14));
}

TEST_CASE("air boxes that cannot be built are refused with a readable message", "[airbox]")
{
    AirBoxSpec spec;
    CHECK_THROWS_AS(AirBox(spec, 0.0), std::invalid_argument);
    CHECK_THROWS_WITH(AirBox(spec, 0.0), Catch::Contains("sample rate"));
    CHECK_THROWS_WITH(AirBox(spec, -1.0 / fs), Catch::Contains("sample rate"));

    AirBoxSpec fine = spec;
    fine.gridCoarseness = 0.9;
    CHECK_THROWS_WITH(AirBox(fine, 1.0 / fs), Catch::Contains("stability bound"));

    AirBoxSpec tiny = spec;
    tiny.shell = false;
    tiny.size_m = { 0.6, 0.02, 0.6 };
    CHECK_THROWS_WITH(AirBox(tiny, 1.0 / fs), Catch::Contains("fewer than 3 points"));

    AirBoxSpec small = spec;
    small.size_m = { 0.3, 0.6, 0.6 }; // narrower than the drum
    CHECK_THROWS_WITH(AirBox(small, 1.0 / fs), Catch::Contains("does not fit"));

    AirBoxSpec huge = spec;
    huge.size_m = { 10.0, 10.0, 10.0 };
    CHECK_THROWS_WITH(AirBox(huge, 1.0 / 192000.0), Catch::Contains("more than the limit"));

    AirBoxSpec flat = spec;
    flat.size_m = { 0.0, 0.6, 0.6 };
    CHECK_THROWS_WITH(AirBox(flat, 1.0 / fs), Catch::Contains("size must be positive"));
}

TEST_CASE("lossless air in a reflecting box with the shell conserves its energy to round-off", "[airbox][energy]")
{
    AirBoxSpec spec;
    spec.sigma_m = 0.0;
    spec.walls = AirWalls::reflecting;
    spec.size_m = { 0.5, 0.5, 0.4 };
    spec.shellEnds = ShellEnds::closed;
    AirBox box(spec, 1.0 / fs);
    REQUIRE(box.numCutLinks() > 0);
    // one pulse inside the shell, one outside it
    const auto in = gaussian(0.03, -0.02, 0.01, 0.03), out = gaussian(-0.2, 0.15, 0.12, 0.025);
    box.setPotential([&](double x, double y, double z) { return in(x, y, z) - 0.7 * out(x, y, z); });

    box.computeNext();
    const double e0 = box.energy();
    REQUIRE(e0 > 0.0);
    double drift = 0.0;
    for (int step = 0; step < 10000; ++step)
    {
        box.advance();
        box.computeNext();
        drift = std::max(drift, std::abs(box.energy() - e0) / e0);
    }
    snaresim::test::reportf(
        "lossless air box, reflecting walls, shell closed, %ld points: energy relative variation %.3g over 10 000 steps\n", box.numPoints(),
        drift);
    CHECK(drift < 1e-11);
}

TEST_CASE("the air's losses are exactly what its energy loses", "[airbox][energy]")
{
    // sigma_a > 0, absorbing walls, open shell: energy(n+1/2) + stepLoss = energy(n-1/2)
    AirBoxSpec spec;
    spec.sigma_m = 2e-5; // ten times the paper's value, so the sigma term is large
    spec.walls = AirWalls::absorbing;
    spec.size_m = { 0.5, 0.5, 0.4 };
    spec.shellEnds = ShellEnds::open;
    AirBox box(spec, 1.0 / fs);
    box.setPotential(gaussian(0.05, 0.0, 0.05, 0.03));
    box.computeNext();
    const double e0 = box.energy();
    double prev = e0, worst = 0.0, lost = 0.0;
    for (int step = 0; step < 2000; ++step)
    {
        box.advance();
        box.computeNext();
        const double e = box.energy(), q = box.stepLoss();
        CHECK(q >= 0.0);
        worst = std::max(worst, std::abs(e + q - prev) / e0);
        lost += q;
        prev = e;
    }
    snaresim::test::reportf(
        "lossy air box: |energy(n+1) + loss - energy(n)| / energy(0) at most %.3g; %.3g of the energy lost, %.3g left\n", worst, lost / e0,
        prev / e0);
    CHECK(worst < 1e-13);
}

TEST_CASE("absorbing walls let a pulse leave the box and the energy never rises", "[airbox][energy]")
{
    AirBoxSpec spec; // sigma_a = 2e-6 m, absorbing walls
    spec.shell = false;
    spec.size_m = { 0.6, 0.6, 0.6 };
    AirBox box(spec, 1.0 / fs);
    box.setPotential(gaussian(0.02, -0.03, 0.01, 0.03));
    box.computeNext();
    const double e0 = box.energy();
    double prev = e0, rise = 0.0;
    // the pulse crosses the box's half-width in 0.3 / 343 s = 39 steps; run 10 crossings
    const int steps = (int) std::ceil(10 * 0.3 / 343.0 * fs);
    for (int step = 0; step < steps; ++step)
    {
        box.advance();
        box.computeNext();
        const double e = box.energy();
        rise = std::max(rise, (e - prev) / e0);
        prev = e;
    }
    snaresim::test::reportf(
        "absorbing walls: largest rise from one step to the next %.3g of energy(0); after %d steps %.3g of the energy is left\n", rise,
        steps, prev / e0);
    CHECK(rise < 1e-14);     // within round-off of the total
    CHECK(prev < 0.05 * e0); // most of it has left
}

TEST_CASE("a pulse in free field arrives after r / c and falls as 1 / r", "[airbox]")
{
    AirBoxSpec spec;
    spec.shell = false;
    spec.size_m = { 0.8, 0.8, 0.8 };
    AirBox box(spec, 1.0 / fs);
    const double h = box.spacing(), c = box.soundSpeed();
    box.setPotential(gaussian(0.0, 0.0, 0.0, 2.5 * h));

    // From Psi at rest, r Psi = (1/2)(r - ct) g(r - ct) outgoing (g the Gaussian), so the pressure
    // rho dt Psi has its main lobe, negative, at t = r / c and its size falls exactly as 1 / r.
    // Two microphones on a diagonal away from the axes (where the 7-point scheme is most accurate).
    const double dir[3] = { 0.6, 0.48, 0.64 }; // unit vector
    const double r1 = 0.1, r2 = 0.25;
    double best[2] = { 0, 0 };
    int at[2] = { 0, 0 };
    std::vector<double> p[2];
    const int steps = (int) (0.3 / c * fs) + 20;
    for (int step = 0; step < steps; ++step)
    {
        box.computeNext();
        for (int m = 0; m < 2; ++m)
        {
            const double r = m == 0 ? r1 : r2;
            p[m].push_back(-box.pressure(r * dir[0], r * dir[1], r * dir[2]));
            if (p[m].back() > best[m])
            {
                best[m] = p[m].back();
                at[m] = step;
            }
        }
        box.advance();
    }
    double arrival[2];
    for (int m = 0; m < 2; ++m)
    {
        REQUIRE(at[m] > 0);
        REQUIRE(at[m] + 1 < (int) p[m].size());
        const double a = p[m][(size_t) at[m] - 1], b = p[m][(size_t) at[m]], d = p[m][(size_t) at[m] + 1];
        const double offset = 0.5 * (a - d) / (a - 2.0 * b + d);
        arrival[m] = (at[m] + 0.5 + offset) / fs; // p from Psi^{n+1} - Psi^n is at (n + 1/2) k
    }
    const double ratio = best[0] / best[1];
    snaresim::test::reportf("free field: arrival at %.3f m after %.4f ms (r/c = %.4f ms), at %.3f m after %.4f ms (r/c = %.4f ms); "
                            "h / c = %.4f ms; peak ratio %.4f against r2/r1 = %.4f\n",
                            r1, 1e3 * arrival[0], 1e3 * r1 / c, r2, 1e3 * arrival[1], 1e3 * r2 / c, 1e3 * h / c, ratio, r2 / r1);
    CHECK(std::abs(arrival[0] - r1 / c) < h / c);
    CHECK(std::abs(arrival[1] - r2 / c) < h / c);
    CHECK(ratio == Approx(r2 / r1).epsilon(0.05));
}

TEST_CASE("the closed shell keeps the air inside it", "[airbox]")
{
    // With closed ends the shell is a rigid can (eq. 6): a pulse inside never reaches a node
    // outside. (The cut links are taken back from the full stencil's sum, so round-off leaks.)
    AirBoxSpec spec;
    spec.walls = AirWalls::reflecting;
    spec.size_m = { 0.45, 0.45, 0.3 };
    spec.shellEnds = ShellEnds::closed;
    AirBox box(spec, 1.0 / fs);
    box.setPotential([](double x, double y, double z) {
        const double r2 = x * x + y * y;
        return r2 < 0.1 * 0.1 && std::abs(z) < 0.04 ? std::exp(-(r2 + z * z) / (2.0 * 0.03 * 0.03)) : 0.0;
    });
    double outside = 0.0, inside = 0.0;
    for (int step = 0; step < 500; ++step)
    {
        box.computeNext();
        box.advance();
    }
    for (int iz = 0; iz < box.nz(); ++iz)
        for (int iy = 0; iy < box.ny(); ++iy)
            for (int ix = 0; ix < box.nx(); ++ix)
            {
                const double x = box.coordinate(0, ix), y = box.coordinate(1, iy), z = box.coordinate(2, iz);
                const double v = std::abs(box.now()[box.index(ix, iy, iz)]);
                const bool in = x * x + y * y < spec.shellRadius_m * spec.shellRadius_m && std::abs(z) < 0.5 * spec.shellDepth_m;
                (in ? inside : outside) = std::max(in ? inside : outside, v);
            }
    snaresim::test::reportf("closed shell: after 500 steps |Psi| at most %.3g inside, %.3g outside\n", inside, outside);
    CHECK(inside > 1e-3);
    CHECK(outside < 1e-12 * inside);
}

TEST_CASE("the air update split over threads gives the same numbers", "[airbox]")
{
    AirBoxSpec spec;
    spec.size_m = { 0.45, 0.45, 0.4 };
    AirBox one(spec, 1.0 / fs), two(spec, 1.0 / fs);
    two.setThreads(2);
    REQUIRE(two.threads() == 2);
    const auto f = gaussian(0.05, 0.02, -0.06, 0.03);
    one.setPotential(f);
    two.setPotential(f);
    double worst = 0.0;
    for (int step = 0; step < 200; ++step)
    {
        one.computeNext();
        two.computeNext();
        for (int iz = 0; iz < one.nz(); ++iz)
            for (int iy = 0; iy < one.ny(); ++iy)
                for (int ix = 0; ix < one.nx(); ++ix)
                {
                    const long i = one.index(ix, iy, iz);
                    worst = std::max(worst, std::abs(one.next()[i] - two.next()[i]));
                }
        one.advance();
        two.advance();
    }
    CHECK(worst == 0.0);
    two.setThreads(1);
    CHECK(two.threads() == 1);
}

TEST_CASE("the update in two parts gives the listed layers first, and the same numbers as in one", "[airbox]")
{
    AirBoxSpec spec;
    spec.size_m = { 0.45, 0.45, 0.4 };
    const int threads = GENERATE(1, 2, 3);
    AirBox whole(spec, 1.0 / fs), parts(spec, 1.0 / fs);
    parts.setThreads(threads);
    REQUIRE(parts.threads() == threads);
    // two heads' pairs of layers, as DrumAir lists them, and a closed disc between one pair
    const int lower = parts.layerBelow(-0.07), upper = parts.layerBelow(0.07);
    const int layers[4] = { lower, lower + 1, upper, upper + 1 };
    whole.cutDisc(upper, 0.0, 0.0, 0.15);
    parts.cutDisc(upper, 0.0, 0.0, 0.15);
    const auto f = gaussian(0.03, -0.02, 0.05, 0.03);
    whole.setPotential(f);
    parts.setPotential(f);
    double worstListed = 0.0, worst = 0.0;
    for (int step = 0; step < 100; ++step)
    {
        whole.computeNext();
        parts.beginNext(layers);
        // the listed layers are final before finishNext (the threads may still be computing the rest)
        for (int l : layers)
            for (int iy = 0; iy < whole.ny(); ++iy)
                for (int ix = 0; ix < whole.nx(); ++ix)
                {
                    const long i = whole.index(ix, iy, l);
                    worstListed = std::max(worstListed, std::abs(whole.next()[i] - parts.next()[i]));
                }
        // a coupling's write on the listed layers, as a head's embedding makes it
        const long centre = whole.index(whole.nx() / 2, whole.ny() / 2, upper);
        whole.next()[centre] += 1e-3;
        parts.next()[centre] += 1e-3;
        parts.finishNext();
        for (int iz = -1; iz <= whole.nz(); ++iz) // ghost layers included
            for (int iy = -1; iy <= whole.ny(); ++iy)
                for (int ix = -1; ix <= whole.nx(); ++ix)
                {
                    if ((ix < 0 || ix >= whole.nx()) + (iy < 0 || iy >= whole.ny()) + (iz < 0 || iz >= whole.nz()) > 1)
                        continue; // the ghosts' edges and corners are never read
                    const long i = whole.index(ix, iy, iz);
                    worst = std::max(worst, std::abs(whole.next()[i] - parts.next()[i]));
                }
        whole.advance();
        parts.advance();
    }
    CHECK(worstListed == 0.0);
    CHECK(worst == 0.0);
}
