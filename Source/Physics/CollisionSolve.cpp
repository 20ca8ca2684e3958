#include "CollisionSolve.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace snaresim
{

double solveCollision(const PowerLawPotential& phi, double gamma, double a, double b, int& iterations, double guess)
{
    // Root bracket: psi >= 0 and non-decreasing, so r* in [-b - gamma psi(-b), -b].
    double hi = -b;
    const double psiHi = phi.psi(hi, a);
    if (psiHi == 0.0)
        return hi;
    double lo = hi - gamma * psiHi;
    const double phiA = phi.phi(a);
    const double scale = std::abs(a) + std::abs(b) + std::abs(lo);
    // Start from the guess (the last step's root) clamped into the bracket; without one, from -b.
    double r = std::isfinite(guess) ? std::clamp(guess, lo, hi) : hi;
    double lastStep = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 200; ++it)
    {
        ++iterations;
        const auto sec = phi.secant(r, a, phiA);
        const double F = r + gamma * sec.psi + b;
        if (F > 0.0)
            hi = r;
        else if (F < 0.0)
            lo = r;
        else
            return r;
        const double dF = 1.0 + gamma * sec.dpsi;
        double next = r - F / dF;
        if (! (next >= lo && next <= hi)) // Newton left the bracket: bisect
            next = 0.5 * (lo + hi);
        const double stepSize = std::abs(next - r);
        r = next;
        // Converged, or stalled at the round-off of F after converging.
        if (stepSize <= collisionTolerance * scale || hi - lo <= 4.0e-16 * scale || (stepSize >= lastStep && stepSize <= 1.0e-11 * scale))
            return r;
        lastStep = stepSize;
    }
    return r;
}

} // namespace snaresim
