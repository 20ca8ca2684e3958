// Speed of the air box update against a bare 7-point stencil on the same grid, measured in
// the same run (measureAirSpeed, AirSpeed.h: the kinds timed in turns, each its fastest round).
// Prints figures; nothing about time can fail.
//   cmake --build build --target airbox_bench && ./build/Tests/Engine/airbox_bench

#include "AirBox.h"
#include "AirSpeed.h"
#include "HeadEmbedding.h"
#include "Membrane.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <thread>
#include <vector>

using namespace snaresim;

namespace
{
constexpr double fs = 44100.0;

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
    std::printf("  %-58s %7.2f us/step  %8.3g updates/s  %6.3f s per s of audio\n", what, 1e6 * perStep, points / perStep, perStep * fs);
}

void reportSpeed(const AirSpeed& a, const char* air)
{
    const double points = (double) a.points;
    report("bare 7-point stencil, double (no walls, no sigma_a)", points, a.bareStep_s);
    report("bare 7-point stencil, float", points, a.bareFloatStep_s);
    std::printf("  %s, 1 thread: %.2f us/step  %.3g updates/s  %.3f s per s of audio\n", air, 1e6 * a.airStep_s, a.airRate(),
                a.airStep_s * fs);
    std::printf("  %s, %d threads: %.2f us/step  %.3g updates/s  %.3f s per s of audio\n", air, a.threads, 1e6 * a.airThreadsStep_s,
                a.airThreadsRate(), a.airThreadsStep_s * fs);
    std::printf("  air / bare (updates per second): %.3f on 1 thread, %.3f on %d threads; float bare / double bare %.2f "
                "(%d rounds of %d steps, each kind its fastest round)\n",
                a.airRate() / a.bareRate(), a.airThreadsRate() / a.bareRate(), a.threads, a.bareFloatRate() / a.bareRate(), a.rounds,
                a.steps);
}

void benchCube(int threads)
{
    AirBoxSpec spec; // 0.6 m cube, sigma_a = 2e-6 m, absorbing walls, the default drum's shell (open)
    AirBox box(spec, 1.0 / fs);
    const int n = box.nx();
    const double points = (double) box.numPoints();
    std::printf("air box benchmark: 0.6 m cube at 44.1 kHz, h = %.3f mm, %d^3 = %.0f points, %d cut links (shell), absorbing walls\n",
                1e3 * box.spacing(), n, points, box.numCutLinks());
    reportSpeed(measureAirSpeed(box, threads, 9), "AirBox::computeNext, sigma_a = 2e-6");

    AirBoxSpec lossless = spec;
    lossless.sigma_m = 0.0;
    AirBox plain(lossless, 1.0 / fs);
    const AirSpeed noSigma = measureAirSpeed(plain, threads, 5);
    std::printf("  AirBox::computeNext, sigma_a = 0: %.2f us/step on 1 thread (%.3f of the bare stencil), %.2f on %d threads\n",
                1e6 * noSigma.airStep_s, noSigma.airRate() / noSigma.bareRate(), 1e6 * noSigma.airThreadsStep_s, noSigma.threads);

    const int repeats = 5;
    const double energy = secondsPerStep([&] { (void) box.energy(); }, 200, repeats);
    report("AirBox::energy (eq. 36), once", points, energy);

    // one head embedded: the coupled step against the air and the head alone
    const int steps = 2000;
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
    std::printf("  batter alone (%d nodes): %.3f us/step; air (no shell) + batter + HeadEmbedding::step: %.3f us/step (%.3f in the "
                "embedding), %.3f s per s of audio\n",
                head.grid().numInterior(), 1e6 * headAlone, 1e6 * coupled, 1e6 * inEmbed, coupled * fs);
    if (! std::isfinite(box.energy()))
        std::printf("  the air box's energy is not finite\n");
}

void benchLargeCube(int threads)
{
    AirBoxSpec spec;
    spec.size_m = { 1.0, 1.0, 1.0 };
    AirBox box(spec, 1.0 / fs);
    std::printf("air box benchmark: 1 m cube at 44.1 kHz, %d^3 = %ld points\n", box.nx(), box.numPoints());
    reportSpeed(measureAirSpeed(box, threads, 5), "AirBox::computeNext, sigma_a = 2e-6");
    if (! std::isfinite(box.energy()))
        std::printf("  the air box's energy is not finite\n");
}
} // namespace

int main()
{
    const int threads = (int) std::max(2u, std::thread::hardware_concurrency());
    benchCube(threads);
    benchLargeCube(threads);
    return 0;
}
