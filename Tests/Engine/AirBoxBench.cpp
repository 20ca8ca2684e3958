// Speed of the air box update against a bare 7-point stencil on the same grid, measured in
// the same run. Prints figures; nothing about time can fail.
//   cmake --build build --target airbox_bench && ./build/Tests/Engine/airbox_bench

#include "AirBox.h"
#include "HeadEmbedding.h"
#include "Membrane.h"
#include "VectorClones.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

using namespace snaresim;

namespace
{
constexpr double fs = 44100.0;

// The bare loop: out = a0 u + a1 (6 neighbours) - up over every node of a padded n^3 grid.
SNARESIM_VECTOR_CLONES void bareStencil(double* __restrict out, const double* __restrict u, const double* __restrict up, int n,
                                        double a0, double a1)
{
    const long sx = n + 2, sxy = sx * sx;
    for (int iz = 1; iz <= n; ++iz)
        for (int iy = 1; iy <= n; ++iy)
        {
            const long r = iz * sxy + iy * sx + 1;
            const double* v = u + r;
            const double* vp = up + r;
            double* o = out + r;
            for (int m = 0; m < n; ++m)
            {
                const double nb = (v[m - 1] + v[m + 1]) + (v[m - sx] + v[m + sx]) + (v[m - sxy] + v[m + sxy]);
                o[m] = a0 * v[m] + a1 * nb - vp[m];
            }
        }
}

// Best time per step of `steps` steps, over `repeats` runs.
double secondsPerStep(const std::function<void()>& step, int steps, int repeats)
{
    double best = 1e30;
    for (int r = 0; r < repeats; ++r)
    {
        const auto t0 = std::chrono::steady_clock::now();
        for (int s = 0; s < steps; ++s)
            step();
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        best = std::min(best, t / steps);
    }
    return best;
}

void report(const char* what, double points, double perStep)
{
    std::printf("  %-58s %7.3f us/step  %6.3g updates/s  %6.3f s per s of audio\n", what, 1e6 * perStep, points / perStep,
                perStep * fs);
}
void benchCube()
{
    const int steps = 2000, repeats = 5;
    AirBoxSpec spec; // 0.6 m cube, sigma_a = 2e-6 m, absorbing walls, the default drum's shell (open)
    AirBox box(spec, 1.0 / fs);
    const int n = box.nx();
    const double points = (double) box.numPoints();
    std::printf("air box benchmark: 0.6 m cube at 44.1 kHz, h = %.3f mm, %d^3 = %.0f points, %d cut links (shell), %d steps, best of %d\n",
                1e3 * box.spacing(), n, points, box.numCutLinks(), steps, repeats);

    // the bare loop on arrays of the same padded size
    const size_t total = (size_t) (n + 2) * (n + 2) * (n + 2);
    std::vector<double> a(total, 0.0), b(total, 0.0), c(total, 0.0);
    for (size_t i = 0; i < total; ++i)
        a[i] = b[i] = 1e-3 * std::sin(0.001 * (double) i);
    double* lv[3] = { c.data(), a.data(), b.data() };
    const double l2 = 1.0 / 3.0;
    const double bare = secondsPerStep(
        [&] {
            bareStencil(lv[0], lv[1], lv[2], n, 2.0 - 6.0 * l2, l2);
            std::swap(lv[2], lv[1]);
            std::swap(lv[1], lv[0]);
        },
        steps, repeats);

    box.setPotential([](double x, double y, double z) { return std::exp(-(x * x + y * y + z * z) / 0.002); });
    const auto airStep = [&] {
        box.computeNext();
        box.advance();
    };
    const double full = secondsPerStep(airStep, steps, repeats);

    AirBoxSpec lossless = spec;
    lossless.sigma_m = 0.0;
    AirBox plain(lossless, 1.0 / fs);
    plain.setPotential([](double x, double y, double z) { return std::exp(-(x * x + y * y + z * z) / 0.002); });
    const double noSigma = secondsPerStep(
        [&] {
            plain.computeNext();
            plain.advance();
        },
        steps, repeats);

    box.setThreads(2);
    const double twoThreads = secondsPerStep(airStep, steps, repeats);
    box.setThreads(1);

    const double energy = secondsPerStep([&] { (void) box.energy(); }, 200, repeats);

    // one head embedded: the coupled step against the air and the head alone
    AirBoxSpec open = spec;
    open.shell = false;
    AirBox air(open, 1.0 / fs);
    MembraneSpec batter;
    batter.tension_N_per_m = 3050.0;
    batter.sigma0_per_s = 3.0 * std::log(10.0) / 1.5;
    batter.sigma1_m2_per_s = 1e-3;
    Membrane head(batter, 1.0 / fs);
    HeadEmbedding embed(air, head, 0.07);
    const double headAlone = secondsPerStep(
        [&] {
            head.computeFree();
            head.advance();
        },
        steps, repeats);
    double inEmbed = 0.0;
    const double coupled = secondsPerStep(
        [&] {
            air.computeNext();
            head.computeFree();
            const auto t0 = std::chrono::steady_clock::now();
            embed.step();
            inEmbed += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            air.advance();
            head.advance();
        },
        steps, repeats);
    inEmbed /= steps * repeats;

    report("bare 7-point stencil, lossless, no walls", points, bare);
    report("AirBox::computeNext, sigma_a = 2e-6, absorbing walls, shell", points, full);
    report("AirBox::computeNext, sigma_a = 0, absorbing walls, shell", points, noSigma);
    report("AirBox::computeNext, sigma_a = 2e-6, 2 threads", points, twoThreads);
    report("AirBox::energy (eq. 36), once", points, energy);
    std::printf("  batter alone (%d nodes): %.3f us/step; air (no shell) + batter + HeadEmbedding::step: %.3f us/step (%.3f in the embedding), %.3f s per s of audio\n",
                head.grid().numInterior(), 1e6 * headAlone, 1e6 * coupled, 1e6 * inEmbed, coupled * fs);
    std::printf("  AirBox (sigma_a > 0) / bare: %.2f; sigma_a = 0 / bare: %.2f; 2 threads speed-up %.2f\n", full / bare, noSigma / bare,
                full / twoThreads);
    if (! std::isfinite(box.energy()))
        std::printf("  the air box's energy is not finite\n");
}

void benchLargeCube()
{
    const int steps = 400, repeats = 3;
    AirBoxSpec spec;
    spec.size_m = { 1.0, 1.0, 1.0 };
    AirBox box(spec, 1.0 / fs);
    box.setPotential([](double x, double y, double z) { return std::exp(-(x * x + y * y + z * z) / 0.002); });
    const double points = (double) box.numPoints();
    const auto airStep = [&] {
        box.computeNext();
        box.advance();
    };
    std::printf("air box benchmark: 1 m cube at 44.1 kHz, %d^3 = %.0f points, %d steps, best of %d\n", box.nx(), points, steps, repeats);
    const double one = secondsPerStep(airStep, steps, repeats);
    box.setThreads(2);
    const double two = secondsPerStep(airStep, steps, repeats);
    report("AirBox::computeNext, sigma_a = 2e-6, 1 thread", points, one);
    report("AirBox::computeNext, sigma_a = 2e-6, 2 threads", points, two);
    if (! std::isfinite(box.energy()))
        std::printf("  the air box's energy is not finite\n");
}
} // namespace

int main()
{
    benchCube();
    benchLargeCube();
    return 0;
}
