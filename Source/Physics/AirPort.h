#pragma once
// One channel of air between the heads and a mass (OutsideAir.h derives it): a compliance 1/K
// from the heads' coordinate q to the air's z, a mass M on z and a conductance Y = 1/R from it
// to rest (Y = 0: lossless). The heads feel P^n = -K (q^n - z^n), explicit; the port
//   p^n = K (q^n - (z^{n+1} + z^{n-1}) / 2),  M (v^{n+1/2} - v^{n-1/2}) / k = p^n,
//   (z^{n+1} - z^{n-1}) / 2k = (v^{n+1/2} + v^{n-1/2}) / 2 + Y p^n
// is implicit in z alone. Its energy at n+1/2 (energy) changes over a step by exactly the
// heads' work on q minus k Y p^2 (loss).

#include <algorithm>
#include <utility>
#include <vector>

namespace snaresim::airport
{

// The time levels of a set of channels (the heads' coordinates q, the ports z, the velocities
// v^{n-1/2} and v^{n+1/2}) and the pressures P^n on the heads: sized once, moved on after a step,
// cleared. Each step writes the next levels whole before they are read again.
struct Levels
{
    std::vector<double> qPrev, qNow, qNext, zPrev, zNow, zNext, vPrev, vNext, P;

    void assign(size_t n)
    {
        for (auto* v : { &qPrev, &qNow, &qNext, &zPrev, &zNow, &zNext, &vPrev, &vNext, &P })
            v->assign(n, 0.0);
    }
    void advance()
    {
        std::swap(qPrev, qNow);
        std::swap(qNow, qNext);
        std::swap(zPrev, zNow);
        std::swap(zNow, zNext);
        std::swap(vPrev, vNext);
    }
    void clear()
    {
        for (auto* v : { &qPrev, &qNow, &qNext, &zPrev, &zNow, &zNext, &vPrev, &vNext, &P })
            std::fill(v->begin(), v->end(), 0.0);
    }
};

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

// The lossless channel (Y = 0) with a damper D across the compliance (NearFieldAir.h), on
// s = z - q by its backward difference, known before the step: F^n = D (s^n - s^{n-1}) / k pushes
// the heads (P^n = -K (q^n - z^n) + F^n) and holds the mass back (M dt v = p^n - F^n). The heads'
// work minus the loss k D (dt. s)^2 is then the change of energy() - (D k / 4) (dt+ s)^2
// (dampedEnergy), since (dt- s)(dt. s) = (dt. s)^2 - (k / 4) dt-[(dt+ s)^2]. That is at least
// (K/2)(mu q - mu z)^2 - (3K/4)(q^{n+1} - q^n)^2 for D <= K k / 4 ((dz - dq)^2 <= 2 (dz + dq)^2
// + 8 dq^2, and energy()'s (K/8)(dz + dq)^2 covers the first).
inline Step dampedStep(double k, double K, double M, double D, double qPrev, double qNow, double zPrev, double zNow, double vPrev)
{
    const double F = D * ((zNow - qNow) - (zPrev - qPrev)) / k;
    const double bk = 0.5 * k * k / M * K;
    Step s;
    s.zNext = (zPrev * (1.0 - bk) + 2.0 * k * vPrev - k * k / M * F + 2.0 * bk * qNow) / (1.0 + bk);
    s.port = K * (qNow - 0.5 * (s.zNext + zPrev));
    s.vNext = vPrev + k / M * (s.port - F);
    s.onHeads = -K * (qNow - zNow) + F;
    return s;
}

// energy() - (D k / 4) (dt+ s)^2 at n+1/2.
inline double dampedEnergy(double k, double K, double M, double D, double qNext, double qNow, double zNext, double zNow, double vNext)
{
    const double ds = (zNext - qNext) - (zNow - qNow);
    return energy(K, M, qNext, qNow, zNext, zNow, vNext) - 0.25 * D / k * ds * ds;
}

// k D (dt. s)^2: what the damper took over the step from n-1/2 to n+1/2.
inline double damperLoss(double k, double D, double qNext, double qPrev, double zNext, double zPrev)
{
    const double ds = (zNext - qNext) - (zPrev - qPrev);
    return 0.25 * D / k * ds * ds;
}

} // namespace snaresim::airport
