#include "AirSpeed.h"

#include "VectorClones.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

namespace snaresim
{

namespace
{
// The bare loop: out = a0 u + a1 (6 neighbours) - up over every node of a padded nx x ny x nz grid.
// Inlined into one function per precision, each built for the vector targets.
template <class T>
[[gnu::always_inline]] inline void bareLoop(T* __restrict out, const T* __restrict u, const T* __restrict up, int nx, int ny,
                                            int nz, T a0, T a1)
{
    const long sx = nx + 2, sxy = sx * (ny + 2);
    for (int iz = 1; iz <= nz; ++iz)
        for (int iy = 1; iy <= ny; ++iy)
        {
            const long r = iz * sxy + iy * sx + 1;
            const T* v = u + r;
            const T* vp = up + r;
            T* o = out + r;
            for (int m = 0; m < nx; ++m)
            {
                const T nb = (v[m - 1] + v[m + 1]) + (v[m - sx] + v[m + sx]) + (v[m - sxy] + v[m + sxy]);
                o[m] = a0 * v[m] + a1 * nb - vp[m];
            }
        }
}

SNARESIM_WIDE_VECTOR_CLONES void bareDouble(double* __restrict out, const double* __restrict u, const double* __restrict up,
                                            int nx, int ny, int nz, double a0, double a1)
{
    bareLoop(out, u, up, nx, ny, nz, a0, a1);
}

SNARESIM_WIDE_VECTOR_CLONES void bareFloat(float* __restrict out, const float* __restrict u, const float* __restrict up, int nx,
                                           int ny, int nz, float a0, float a1)
{
    bareLoop(out, u, up, nx, ny, nz, a0, a1);
}

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
        if constexpr (sizeof(T) == sizeof(double))
            bareDouble(lvl[0], lvl[1], lvl[2], nx, ny, nz, 2.0 - 6.0 * l2, l2);
        else
            bareFloat(lvl[0], lvl[1], lvl[2], nx, ny, nz, T(2) - T(6) * l2, l2);
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
