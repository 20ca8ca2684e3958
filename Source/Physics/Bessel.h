#pragma once
// Zeros of the Bessel functions J_m and J_m' (std::cyl_bessel_j): the drum's modes, of the heads
// (J_m(j_mn) = 0, a fixed rim) and of the air in the rigid shell (J_m'(j'_mn) = 0, a rigid wall).

namespace snaresim
{

// The n-th positive zero of J_m (n >= 1).
double besselZero(int m, int n);
// The n-th positive zero of J_m' (n >= 1; for m = 0 the zero at the origin is not counted).
double besselPrimeZero(int m, int n);

} // namespace snaresim
