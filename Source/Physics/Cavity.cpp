#include "Cavity.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace snaresim
{

namespace
{
double cavityStiffness(const CavitySpec& s, double radius, double depth)
{
    if (s.model != AirModel::cavity) // no air, or the air box (DrumAir)
        return 0.0;
    const double V0 = std::numbers::pi * radius * radius * depth;
    return s.airDensity_kg_per_m3 * s.soundSpeed_m_per_s * s.soundSpeed_m_per_s / V0;
}
} // namespace

Cavity::Cavity(const CavitySpec& spec, double radius) : K(cavityStiffness(spec, radius, spec.shellDepth_m)) {}

void Cavity::setSpec(const CavitySpec& spec, double radius)
{
    const double depth = spec.gridShellDepth_m > 0.0 ? std::max(spec.shellDepth_m, spec.gridShellDepth_m) : spec.shellDepth_m;
    K = cavityStiffness(spec, radius, depth);
}

double Cavity::kineticReserve(const CavitySpec& spec, double radius, double density, double k)
{
    CavitySpec design = spec;
    design.model = AirModel::cavity; // same grid with or without air, so the two compare
    const double depth = spec.gridShellDepth_m > 0.0 ? std::min(spec.gridShellDepth_m, spec.shellDepth_m) : spec.shellDepth_m;
    const double Kmax = cavityStiffness(design, radius, depth);
    const double area = std::numbers::pi * radius * radius;
    // (K k^2/8)(dt+ dV)^2 <= (K k^2/4)(h^4 N |v_b|^2 + ...) with N h^2 <= A: a share
    // K k^2 A / (2 rho) of (rho h^2/2)|v|^2; doubled for margin.
    return 2.0 * Kmax * k * k * area / (2.0 * density);
}

} // namespace snaresim
