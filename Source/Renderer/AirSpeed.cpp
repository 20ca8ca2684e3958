#include "AirSpeed.h"

#include "VectorTarget.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace snaresim
{

namespace
{
#define SNARESIM_KERNELS "AirSpeedKernels.inl"
#include "PerVectorTarget.inl"

// Three levels of the bare stencil, rotated each step as the air box's are.
template <class T>
struct Bare
{
    Bare(int x, int y, int z) : nx(x), ny(y), nz(z)
    {
        const size_t total = (size_t) (nx + 2) * (size_t) (ny + 2) * (size_t) (nz + 2);
        store.assign(3 * total, T(0));
        for (size_t i = 0; i < 2 * total; ++i)
            store[total + i] = T(1e-3 * std::sin(0.001 * (double) (i % total)));
        for (int l = 0; l < 3; ++l)
            lvl[l] = store.data() + (size_t) l * total;
    }
    void step()
    {
        const T l2 = T(1.0 / 3.0);
        SNARESIM_ON_VECTOR_TARGET(bareLoop<T>)(lvl[0], lvl[1], lvl[2], nx, ny, nz, T(2) - T(6) * l2, l2);
        T* t = lvl[2];
        lvl[2] = lvl[1];
        lvl[1] = lvl[0];
        lvl[0] = t;
    }
    int nx, ny, nz;
    std::vector<T> store;
    T* lvl[3] {};
};

double secondsFor(const std::function<void()>& step, int steps)
{
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s)
        step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

AirSpeed measureAirSpeed(AirBox& box, int threads, int rounds, double roundSeconds)
{
    AirSpeed r;
    r.points = box.numPoints();
    r.spacing_m = box.spacing();
    r.threads = std::max(1, threads);
    r.rounds = std::max(1, rounds);

    const int previous = box.threads();
    box.setThreads(1);
    box.setPotential([](double x, double y, double z) { return std::exp(-(x * x + y * y + z * z) / 0.002); });
    Bare<double> bare(box.nx(), box.ny(), box.nz());
    Bare<float> bareF(box.nx(), box.ny(), box.nz());
    const auto airStep = [&] {
        box.computeNext();
        box.advance();
    };

    // steps per round from one warm-up step of the slowest kind (the air box on one thread)
    airStep();
    const double once = secondsFor(airStep, 3) / 3.0;
    r.steps = (int) std::clamp(roundSeconds / std::max(once, 1e-9), 3.0, 100000.0);

    double bareBest = 1e30, floatBest = 1e30, airBest = 1e30, threadsBest = 1e30;
    for (int round = 0; round < r.rounds; ++round)
    {
        bareBest = std::min(bareBest, secondsFor([&] { bare.step(); }, r.steps));
        floatBest = std::min(floatBest, secondsFor([&] { bareF.step(); }, r.steps));
        box.setThreads(1);
        airBest = std::min(airBest, secondsFor(airStep, r.steps));
        if (r.threads > 1)
        {
            box.setThreads(r.threads);
            r.threads = box.threads();
            airStep(); // the threads started
            threadsBest = std::min(threadsBest, secondsFor(airStep, r.steps));
        }
    }
    r.bareStep_s = bareBest / r.steps;
    r.bareFloatStep_s = floatBest / r.steps;
    r.airStep_s = airBest / r.steps;
    r.airThreadsStep_s = r.threads > 1 ? threadsBest / r.steps : r.airStep_s;
    box.setThreads(previous);
    return r;
}

} // namespace snaresim
