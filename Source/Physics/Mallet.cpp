#include "Mallet.h"

#include <algorithm>

namespace snaresim
{

namespace
{
constexpr double kLargestPatch_m = 0.02; // the contact-radius control's maximum
}

Mallet::Mallet(const MalletSpec& spec, const CircularGrid& headGrid, double timeStep) : grid(headGrid), k(timeStep)
{
    g.reserve(grid.distributionCapacity(std::max(spec.contactRadius_m, kLargestPatch_m)));
    setSpec(spec);
}

void Mallet::setSpec(const MalletSpec& spec)
{
    M = spec.mass_kg;
    patchRadius = std::min(spec.contactRadius_m, kLargestPatch_m);
    contactLaw.kappa = spec.stiffness;
    contactLaw.alpha = spec.exponent;
}

double Mallet::energy() const
{
    if (! active)
        return 0.0;
    const double v = (zNext - zNow) / k;
    return 0.5 * M * v * v;
}

double Mallet::energyBeforeStep() const
{
    if (! active)
        return 0.0;
    const double v = (zNow - zPrev) / k;
    return 0.5 * M * v * v;
}

bool Mallet::aim(double x, double y)
{
    if (grid.makeDistribution(x, y, patchRadius, g))
        return true;
    park();
    return false;
}

void Mallet::launch(double headNow, double headPrev, double speed)
{
    const double travel = speed * k;
    const double gap = std::max(0.0, headPrev - headNow - travel); // keeps eta^{n-1} <= 0 too
    zNow = headNow + gap;
    zPrev = zNow + travel;
    etaNow = headNow - zNow;
    etaPrev = headPrev - zPrev;
    zNext = zNow;
    etaNext = etaNow;
    active = true;
}

void Mallet::park()
{
    active = false;
    zNext = zNow = zPrev = 0.0;
    etaNext = etaNow = etaPrev = 0.0;
}

void Mallet::advance()
{
    zPrev = zNow;
    zNow = zNext;
    etaPrev = etaNow;
    etaNow = etaNext;
}

} // namespace snaresim
