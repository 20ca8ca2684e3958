#include "OutsideAir.h"

#include "AirPort.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace snaresim
{

namespace
{
const RadiationChannelSpec& channelSpec(const OutsideAirSpec& s, int c)
{
    switch (c)
    {
        case OutsideAir::monopole: return s.monopole;
        case OutsideAir::dipole: return s.dipole;
        case OutsideAir::tiltSumX:
        case OutsideAir::tiltSumY: return s.tiltSum;
        default: return s.tiltDiff;
    }
}

double area(const MembraneSpec& m) { return std::numbers::pi * m.radius_m * m.radius_m; }
double secondMoment(const MembraneSpec& m) { return 0.25 * std::numbers::pi * std::pow(m.radius_m, 4.0); } // int x^2 dA
} // namespace

// The explicit coupling's energy dips by at most (K/4)(dt+ q)^2 k^2 per channel (OutsideAir.h).
// The monopole and dipole share the heads' volumes a, b: (K_m/4)(a - b)^2 + (K_d/4)(a + b)^2
// <= (max(K_m, K_d) / 2)(a^2 + b^2), and on one head (dt+ V)^2 <= A h^2 |dt+ w|^2; the tilt
// channels likewise share the first moments, (dt+ X)^2 <= I h^2 |dt+ w|^2, I = pi R^4 / 4, and
// a head's first moments are orthogonal to its volume and to each other. Against the kinetic
// energy (rho / 2) h^2 |dt+ w|^2 the shares are max(K_m, K_d) A k^2 / rho and
// max(K_s, K_t) I k^2 / rho (K_s, K_t: the tilt channels' sum and difference); each K is the largest that keeps its share within spec.reserve
// on the lighter head, and sqrt(K / M) within cornerLimit.
OutsideAir::Values OutsideAir::stiffnesses(const OutsideAirSpec& s, const MembraneSpec& batter, const MembraneSpec& carry, double k)
{
    Values K {};
    if (! s.enabled)
        return K;
    const double w = 2.0 * std::numbers::pi * s.cornerLimit_Hz;
    const double rhoMin = std::min(batter.density_kg_per_m2, carry.density_kg_per_m2);
    const double volumeLimit = s.reserve * rhoMin / (area(batter) * k * k);
    const double tiltLimit = s.reserve * rhoMin / (secondMoment(batter) * k * k);
    for (int c = 0; c < numChannels; ++c)
        K[(size_t) c] = std::min(channelSpec(s, c).mass * w * w, c <= dipole ? volumeLimit : tiltLimit);
    return K;
}

double OutsideAir::kineticReserve(const OutsideAirSpec& s, const MembraneSpec& batter, const MembraneSpec& carry, double k, bool ofBatter)
{
    if (! s.enabled)
        return 0.0;
    const Values K = stiffnesses(s, batter, carry, k);
    const MembraneSpec& head = ofBatter ? batter : carry;
    const double kk = k * k / head.density_kg_per_m2;
    return std::max(std::max(K[monopole], K[dipole]) * area(head) * kk, std::max(K[tiltSumX], K[tiltDiffX]) * secondMoment(head) * kk);
}

OutsideAir::OutsideAir(const OutsideAirSpec& s, const MembraneSpec& batter, const MembraneSpec& carry, double timeStep)
    : on(s.enabled), k(timeStep), K(stiffnesses(s, batter, carry, timeStep))
{
    for (int c = 0; c < numChannels; ++c)
    {
        M[(size_t) c] = channelSpec(s, c).mass;
        Y[(size_t) c] = 1.0 / channelSpec(s, c).resistance; // infinite R: 0
    }
}

void OutsideAir::computeFree()
{
    for (size_t c = 0; c < numChannels; ++c)
    {
        const airport::Step s = airport::step(k, K[c], M[c], Y[c], qNow[c], zPrev[c], zNow[c], vPrev[c]);
        zNext[c] = s.zNext;
        vNext[c] = s.vNext;
        p[c] = s.port;
        P[c] = s.onHeads;
    }
}

double OutsideAir::energy() const
{
    double e = 0.0;
    for (size_t c = 0; c < numChannels; ++c)
        e += airport::energy(K[c], M[c], qNext[c], qNow[c], zNext[c], zNow[c], vNext[c]);
    return e;
}

double OutsideAir::stepLoss() const
{
    double q = 0.0;
    for (size_t c = 0; c < numChannels; ++c)
        q += airport::loss(k, Y[c], p[c]);
    return q;
}

void OutsideAir::advance()
{
    qNow = qNext;
    zPrev = zNow;
    zNow = zNext;
    vPrev = vNext;
}

void OutsideAir::clear()
{
    for (Values* v : { &qNow, &qNext, &zPrev, &zNow, &zNext, &vPrev, &vNext, &P, &p })
        v->fill(0.0);
}

} // namespace snaresim
