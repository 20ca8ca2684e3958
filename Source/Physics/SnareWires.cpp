#include "SnareWires.h"

#include "VectorTarget.h"

#include <algorithm>
#include <cmath>

namespace snaresim
{

double SnareWires::minimumSpacing(const SnareSpec& s, double k)
{
    const double T = s.gridTension_N > 0.0 ? s.gridTension_N : s.tension_N;
    const double sigma1 = s.gridSigma1_m2_per_s >= 0.0 ? s.gridSigma1_m2_per_s : s.sigma1_m2_per_s;
    // eq. (40): h_s^2 >= k^2 T_s / rho_s + 4 sigma1_s k
    return std::sqrt(k * k * T / s.linearDensity_kg_per_m + 4.0 * sigma1 * k);
}

SnareWires::SnareWires(const SnareSpec& s, double, double timeStep)
    : numWires(s.count), length(s.length_m), pitch(s.spacing_m), k(timeStep), kk(timeStep * timeStep), rho(s.linearDensity_kg_per_m),
      maxT(s.gridTension_N > 0.0 ? s.gridTension_N : s.tension_N),
      maxSigma1(s.gridSigma1_m2_per_s >= 0.0 ? s.gridSigma1_m2_per_s : s.sigma1_m2_per_s)
{
    M = std::max(2, (int) std::floor(length / gridSpacing(s, k)));
    hs = length / M;
    y0 = -0.5 * (numWires - 1) * pitch;
    const size_t n = (size_t) numWires * (size_t) (M + 1);
    uNext.assign(n, 0.0);
    uNow = uNext;
    uPrev = uNext;
    setCoefficients(s.tension_N, s.sigma0_per_s, s.sigma1_m2_per_s);
}

void SnareWires::setCoefficients(double tension, double s0, double s1)
{
    T = std::clamp(tension, 0.0, maxT);
    sigma0 = std::max(0.0, s0);
    sigma1 = std::clamp(s1, 0.0, maxSigma1);
    q = 1.0 + sigma0 * k;
    const double lambda2 = kk * T / (rho * hs * hs);
    const double s = 2.0 * sigma1 * k / (hs * hs);
    // interior, eq. (28): u+ = [2u - (1 - sigma0 k) u- + lambda^2 L u + s (L u - L u-)] / q
    a0 = (2.0 - 2.0 * lambda2 - 2.0 * s) / q;
    a1 = (lambda2 + s) / q;
    b0 = -(1.0 - sigma0 * k - 2.0 * s) / q;
    b1 = -s / q;
    // end node, half a cell of mass: the one neighbour counts twice as much
    e0 = (2.0 - 2.0 * lambda2 - 2.0 * s) / q;
    e1 = 2.0 * (lambda2 + s) / q;
    f0 = -(1.0 - sigma0 * k - 2.0 * s) / q;
    f1 = -2.0 * s / q;
}

namespace
{
#define SNARESIM_KERNELS "SnareWiresKernels.inl"
#include "PerVectorTarget.inl"
} // namespace

void SnareWires::computeFree()
{
    SNARESIM_ON_VECTOR_TARGET(freeUpdate)(numWires, M, uNow.data(), uPrev.data(), uNext.data(), a0, a1, b0, b1, e0, e1, f0, f1);
}

double SnareWires::energyOf(const AlignedVector<double>& uNext, const AlignedVector<double>& uNow) const
{
    const int stride = M + 1;
    double kinetic = 0.0, potential = 0.0, sigma1Term = 0.0;
    for (int i = 0; i < numWires; ++i)
    {
        const size_t base = (size_t) i * (size_t) stride;
        for (int l = 0; l <= M; ++l)
        {
            const double v = uNext[base + (size_t) l] - uNow[base + (size_t) l];
            kinetic += (l == 0 || l == M ? 0.5 : 1.0) * v * v;
        }
        for (int l = 0; l < M; ++l)
        {
            const size_t j = base + (size_t) l;
            const double dNow = uNow[j + 1] - uNow[j], dNext = uNext[j + 1] - uNext[j];
            potential += dNow * dNext;
            sigma1Term += (dNext - dNow) * (dNext - dNow);
        }
    }
    return 0.5 * rho * hs * kinetic / kk + 0.5 * T * potential / hs - 0.5 * rho * sigma1 * sigma1Term / (k * hs);
}

double SnareWires::stepLoss() const
{
    if (sigma0 == 0.0 && sigma1 == 0.0)
        return 0.0;
    const int stride = M + 1;
    double v2 = 0.0, g2 = 0.0;
    for (int i = 0; i < numWires; ++i)
    {
        const size_t base = (size_t) i * (size_t) stride;
        for (int l = 0; l <= M; ++l)
        {
            const double d = uNext[base + (size_t) l] - uPrev[base + (size_t) l];
            v2 += (l == 0 || l == M ? 0.5 : 1.0) * d * d;
        }
        for (int l = 0; l < M; ++l)
        {
            const size_t j = base + (size_t) l;
            const double d = (uNext[j + 1] - uPrev[j + 1]) - (uNext[j] - uPrev[j]);
            g2 += d * d;
        }
    }
    // k q^n = k [2 rho sigma0 h_s sum w_l (dt. u)^2 + 2 rho sigma1 / h_s sum (d dt. u)^2]
    return k * (2.0 * rho * sigma0 * hs * v2 + 2.0 * rho * sigma1 * g2 / hs) / (4.0 * kk);
}

void SnareWires::advance()
{
    std::swap(uPrev, uNow);
    std::swap(uNow, uNext);
}

void SnareWires::clear()
{
    std::fill(uNext.begin(), uNext.end(), 0.0);
    std::fill(uNow.begin(), uNow.end(), 0.0);
    std::fill(uPrev.begin(), uPrev.end(), 0.0);
}

bool SnareWires::isFinite() const
{
    for (double v : uNow)
        if (! std::isfinite(v))
            return false;
    return true;
}

} // namespace snaresim
