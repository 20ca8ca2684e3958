#include "HostRateInterpolator.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace snaresim
{

namespace
{
constexpr double kPassEdge = 0.45; // of the simulated rate
constexpr double kStopEdge = 0.5;  // of the simulated rate
constexpr double kStop_dB = 100.0; // the images' least attenuation

double besselI0(double x)
{
    // power series of I0: sum ((x/2)^k / k!)^2, to round-off
    double sum = 1.0, term = 1.0;
    for (int k = 1; k < 200 && term > 1e-17 * sum; ++k)
    {
        term *= (0.5 * x / k) * (0.5 * x / k);
        sum += term;
    }
    return sum;
}
} // namespace

SimulatedRate simulatedRateFor(double hostRate_Hz, double gridCoarseness) noexcept
{
    SimulatedRate s { hostRate_Hz };
    while (s.rate_Hz * 0.5 >= 44100.0)
    {
        s.rate_Hz *= 0.5;
        s.up *= 2;
    }
    if (s.rate_Hz >= 44100.0 && s.rate_Hz <= 48000.0 && gridCoarseness >= kReducedRateCoarseness)
    {
        // two thirds, or three quarters where two thirds would fall below kReducedRate_Hz
        const int keep = s.rate_Hz * 2.0 / 3.0 >= kReducedRate_Hz ? 2 : 3;
        s.rate_Hz = s.rate_Hz * keep / (keep + 1); // exact for 44.1 and 48 kHz
        s.up *= keep + 1;
        s.down *= keep;
        const int common = std::gcd(s.up, s.down);
        s.up /= common;
        s.down /= common;
    }
    return s;
}

int HostRateInterpolator::perPhaseFor(int up) noexcept
{
    if (up <= 1)
        return 1;
    // Kaiser's estimate of the length for the transition (in cycles per sample at L times the
    // simulated rate) and the attenuation.
    const double transition = (kStopEdge - kPassEdge) / up;
    const int estimate = (int) std::ceil((kStop_dB - 8.0) / (2.285 * 2.0 * std::numbers::pi * transition)) + 1;
    return (estimate + 1 + up - 1) / up;
}

int HostRateInterpolator::tapsFor(int up) noexcept
{
    if (up <= 1)
        return 1;
    const int t = perPhaseFor(up) * up - 1;
    return t % 2 == 0 ? t - 1 : t; // odd, so that the delay is whole
}

HostRateInterpolator::HostRateInterpolator(int up, int down) : L(std::max(1, up)), M(std::clamp(down, 1, L))
{
    if (L > 1)
    {
        const double beta = 0.1102 * (kStop_dB - 8.7);
        perPhase = perPhaseFor(L);
        taps = tapsFor(L);
        const double cutoff = 0.5 * (kPassEdge + kStopEdge) / L; // cycles per sample at L times the rate
        const double centre = 0.5 * (taps - 1);
        std::vector<double> prototype((size_t) taps);
        for (int i = 0; i < taps; ++i)
        {
            const double t = i - centre;
            const double sinc = t == 0.0 ? 2.0 * cutoff : std::sin(2.0 * std::numbers::pi * cutoff * t) / (std::numbers::pi * t);
            const double r = t / centre;
            prototype[(size_t) i] = sinc * besselI0(beta * std::sqrt(std::max(0.0, 1.0 - r * r))) / besselI0(beta);
        }
        // each phase sums to one: a constant passes unchanged
        h.assign((size_t) (perPhase * L), 0.0);
        for (int p = 0; p < L; ++p)
        {
            double sum = 0.0;
            for (int m = 0; m < perPhase; ++m)
                if (p + m * L < taps)
                    sum += prototype[(size_t) (p + m * L)];
            for (int m = 0; m < perPhase; ++m)
                if (p + m * L < taps)
                    h[(size_t) (p * perPhase + m)] = prototype[(size_t) (p + m * L)] / sum;
        }
    }
    else
        h.assign(1, 1.0);
    ring.assign((size_t) (numChannels * 2 * perPhase), 0.0);
}

void HostRateInterpolator::push(const std::array<double, numChannels>& x) noexcept
{
    pos = pos == 0 ? perPhase - 1 : pos - 1;
    for (int c = 0; c < numChannels; ++c)
    {
        double* r = ring.data() + (size_t) (c * 2 * perPhase);
        r[pos] = r[pos + perPhase] = x[(size_t) c];
    }
}

double HostRateInterpolator::value(int c, int phase) const noexcept
{
    // y[n L + p] = sum_m h[p + m L] x[n - m]; the ring holds x[n - m] at pos + m
    const double* x = ring.data() + (size_t) (c * 2 * perPhase) + pos;
    const double* g = h.data() + (size_t) (phase * perPhase);
    double y = 0.0;
#pragma omp simd reduction(+ : y)
    for (int m = 0; m < perPhase; ++m)
        y += g[m] * x[m];
    return y;
}

void HostRateInterpolator::clear() noexcept
{
    std::fill(ring.begin(), ring.end(), 0.0);
    pos = 0;
}

double longestLatencySamples(double hostRate_Hz) noexcept
{
    double longest = 0.0;
    for (const double coarseness : { 1.0, kReducedRateCoarseness })
    {
        const auto r = simulatedRateFor(hostRate_Hz, coarseness);
        longest = std::max(longest, (double) HostRateInterpolator::delayFor(r.up) / (double) r.down);
    }
    return longest;
}

} // namespace snaresim
