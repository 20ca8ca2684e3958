#pragma once
// One channel of air between the heads and a mass (OutsideAir.h derives it): a compliance 1/K
// from the heads' coordinate q to the air's z, a mass M on z and a conductance Y = 1/R from it
// to rest (Y = 0: lossless). The heads feel P^n = -K (q^n - z^n), explicit; the port
//   p^n = K (q^n - (z^{n+1} + z^{n-1}) / 2),  M (v^{n+1/2} - v^{n-1/2}) / k = p^n,
//   (z^{n+1} - z^{n-1}) / 2k = (v^{n+1/2} + v^{n-1/2}) / 2 + Y p^n
// is implicit in z alone. Its energy at n+1/2 (portEnergy) changes over a step by exactly the
// heads' work on q minus k Y p^2 (portLoss).

namespace snaresim::airport
{

struct Step
{
    double zNext, vNext; // z^{n+1}, v^{n+1/2}
    double port;         // p^n
    double onHeads;      // P^n
};

inline Step step(double k, double K, double M, double Y, double qNow, double zPrev, double zNow, double vPrev)
{
    // With beta = k^2 / M + 2 k Y: z^{n+1} (1 + beta K / 2) = z^{n-1} (1 - beta K / 2) + 2 k v^{n-1/2} + beta K q^n.
    const double bk = 0.5 * (k * k / M + 2.0 * k * Y) * K;
    Step s;
    s.zNext = (zPrev * (1.0 - bk) + 2.0 * k * vPrev + 2.0 * bk * qNow) / (1.0 + bk);
    s.port = K * (qNow - 0.5 * (s.zNext + zPrev));
    s.vNext = vPrev + k / M * s.port;
    s.onHeads = -K * (qNow - zNow);
    return s;
}

// (K/2) [(mu q - mu z)^2 + ((dz + dq)^2 - 2 dq^2) / 4] + (M/2) v^{n+1/2}^2, at n+1/2.
inline double energy(double K, double M, double qNext, double qNow, double zNext, double zNow, double vNext)
{
    const double s = 0.5 * (qNext + qNow) - 0.5 * (zNext + zNow);
    const double dq = qNext - qNow, dz = zNext - zNow;
    return 0.5 * K * (s * s + 0.25 * ((dz + dq) * (dz + dq) - 2.0 * dq * dq)) + 0.5 * M * vNext * vNext;
}

inline double loss(double k, double Y, double port) { return k * Y * port * port; }

} // namespace snaresim::airport
