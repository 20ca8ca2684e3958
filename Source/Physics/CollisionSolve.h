#pragma once
// The scalar collision equation shared by the mallet (eq. 44) and the snare points (eq. 50 for
// one point):  r + gamma psi(r; a) + b = 0,  r = eta^{n+1} - eta^{n-1}, a = eta^{n-1}.
// psi >= 0 is non-decreasing, so the root is unique and lies in [-b - gamma psi(-b), -b].

#include "PowerLawPotential.h"

#include <limits>

namespace snaresim
{

// Newton step size below this times (|a| + |b| + bracket) counts as converged (round-off).
inline constexpr double collisionTolerance = 1.0e-14;

// Newton-Raphson kept inside the root's bracket (bisection when a step leaves it), so it
// always ends with a finite root in the bracket; at most 200 iterations, usually 2-6.
// guess: a starting point (the previous step's root), ignored when not finite.
double solveCollision(const PowerLawPotential& law, double gamma, double a, double b, int& iterations,
                      double guess = std::numeric_limits<double>::quiet_NaN());

} // namespace snaresim
