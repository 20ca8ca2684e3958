#include "Bessel.h"

#include <cmath>

namespace snaresim
{

namespace
{
double besselJ(int m, double x) { return std::cyl_bessel_j((double) m, x); }

// J_m'(x)
double besselPrime(int m, double x)
{
    if (m == 0)
        return -besselJ(1, x);
    return 0.5 * (besselJ(m - 1, x) - besselJ(m + 1, x));
}

// The n-th sign change of f above 0.5 (steps of 0.05, closer than any two zeros of these
// functions there), bisected to round-off; 0 if none below 200.
template <class F>
double nthZero(F&& f, int n)
{
    constexpr double step = 0.05;
    double a = 0.5, fa = f(a);
    int found = 0;
    for (double b = a + step; b < 200.0; a = b, b += step)
    {
        const double fb = f(b);
        if ((fa < 0.0) == (fb < 0.0))
        {
            fa = fb;
            continue;
        }
        if (++found == n)
        {
            double lo = a, hi = b;
            for (int i = 0; i < 60; ++i)
            {
                const double mid = 0.5 * (lo + hi);
                if ((f(mid) < 0.0) == (fa < 0.0))
                    lo = mid;
                else
                    hi = mid;
            }
            return 0.5 * (lo + hi);
        }
        fa = fb;
    }
    return 0.0;
}
} // namespace

double besselZero(int m, int n)
{
    return nthZero([m](double x) { return besselJ(m, x); }, n);
}

double besselPrimeZero(int m, int n)
{
    return nthZero([m](double x) { return besselPrime(m, x); }, n);
}

} // namespace snaresim
