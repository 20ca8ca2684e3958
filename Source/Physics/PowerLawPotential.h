#pragma once
// The collision potential Phi(eta) = kappa/(alpha+1) [eta]_+^(alpha+1) (eq. 11, 16) and the
// discrete force psi(r) = (Phi(a + r) - Phi(a)) / r of eq. (27), (30), with r = eta^{n+1} - eta^{n-1}
// and a = eta^{n-1}. psi is the slope of a secant of a convex, non-decreasing function, so it
// is >= 0 and non-decreasing in r: eq. (44) and (50) have a unique root.

#include <cmath>

namespace snaresim
{

struct PowerLawPotential
{
    double kappa = 1.0e8;
    double alpha = 1.5;

    double phi(double eta) const { return eta > 0.0 ? kappa / (alpha + 1.0) * eta * power(eta) : 0.0; }
    double dphi(double eta) const { return eta > 0.0 ? kappa * power(eta) : 0.0; }
    double d2phi(double eta) const { return eta > 0.0 ? kappa * alpha * power(eta) / eta : 0.0; }

    // eta^alpha for eta > 0, without pow() for the common Hertz exponent 1.5 and whole ones.
    double power(double eta) const
    {
        if (alpha == 1.5)
            return eta * std::sqrt(eta);
        if (alpha == 1.0)
            return eta;
        if (alpha == 2.0)
            return eta * eta;
        if (alpha == 3.0)
            return eta * eta * eta;
        return std::pow(eta, alpha);
    }

    // Below this |r| / |a| the secant is replaced by its midpoint-tangent limit to avoid
    // cancellation; the energy identity f r = Phi(a+r) - Phi(a) then holds to O(r^3 Phi''').
    static constexpr double smallStep = 1.0e-6;

    double psi(double r, double a) const
    {
        if (a <= 0.0 && a + r <= 0.0)
            return 0.0;
        if (std::abs(r) <= smallStep * std::abs(a))
            return dphi(a + 0.5 * r);
        return (phi(a + r) - phi(a)) / r;
    }

    // psi and d psi / d r together, with Phi(a) given: one power evaluation, two where r is small
    // beside a (Newton's inner loop).
    struct Secant
    {
        double psi, dpsi;
    };
    Secant secant(double r, double a, double phiA) const
    {
        if (a <= 0.0 && a + r <= 0.0)
            return { 0.0, 0.0 };
        const double absA = std::abs(a);
        if (std::abs(r) <= smallStep * absA)
        {
            const double m = a + 0.5 * r;
            if (m <= 0.0)
                return { 0.0, 0.0 };
            const double pm = power(m);
            return { kappa * pm, 0.5 * kappa * alpha * pm / m };
        }
        const double x = a + r;
        double phiX = 0.0, dphiX = 0.0;
        if (x > 0.0)
        {
            const double px = power(x);
            dphiX = kappa * px;
            phiX = dphiX * x / (alpha + 1.0);
        }
        const double p = (phiX - phiA) / r;
        if (std::abs(r) <= 1.0e-4 * absA)
        {
            const double m = a + 0.5 * r;
            return { p, m > 0.0 ? 0.5 * kappa * alpha * power(m) / m : 0.0 };
        }
        return { p, (dphiX - p) / r };
    }

    // d psi / d r
    double dpsi(double r, double a) const
    {
        if (a <= 0.0 && a + r <= 0.0)
            return 0.0;
        if (std::abs(r) <= 1.0e-4 * std::abs(a))
            return 0.5 * d2phi(a + 0.5 * r);
        return (dphi(a + r) - psi(r, a)) / r;
    }
};

} // namespace snaresim
