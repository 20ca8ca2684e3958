#pragma once
// The enclosed air's own modes (CavityModes.h) attached to both heads (CavityModesCoupling.h):
// an AttachedAir (AttachedAir.h). Inactive in the air box and without air.

#include "AttachedAir.h"
#include "CavityModes.h"
#include "CavityModesCoupling.h"
#include "DrumConfig.h"
#include "EnergyTerm.h"

namespace snaresim
{

class AttachedCavityModes : public AttachedPair<CavityModes, CavityModesCoupling>
{
public:
    AttachedCavityModes(const DrumConfig& c, Membrane& batter, Membrane& carry, double k)
        : AttachedPair([&] { return CavityModes(c.cavity, c.cavityModesUpTo_Hz(), c.batter.radius_m, k); },
                       [&](CavityModes& modes) { return CavityModesCoupling(batter, carry, modes, c.cavity.modeCellSize_m); })
    {}

    void beforeHeads(HeadPressure&, HeadPressure&) noexcept
    {
        part.computeFree();
        coupling.applyPressures(); // the modes at n, on the heads' cells
    }
    void afterHeads(const CellSums&) noexcept { coupling.step(); } // the modes' q^{n+1}
    const double* blockSums(int head, int side) const { return coupling.blockSums(head, side); }
    void setSpec(const DrumConfig& c) noexcept { part.setSpec(c.cavity); }
    auto energyTerm() const { return EnergyTerm("cavity_modes", part).listedIf(part.active()); } // CavityModes.h
};

} // namespace snaresim
