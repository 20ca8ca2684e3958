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

class AttachedCavityModes
{
public:
    AttachedCavityModes(const DrumConfig& c, Membrane& batter, Membrane& carry, double k)
        : modes(c.cavity, c.cavityModesUpTo_Hz(), c.batter.radius_m, k), coupling(batter, carry, modes, c.cavity.modeCellSize_m)
    {}

    bool active() const { return modes.active(); }
    void beforeHeads(HeadPressure&, HeadPressure&) noexcept
    {
        modes.computeFree();
        coupling.applyPressures(); // the modes at n, on the heads' cells
    }
    void afterHeads(const CellSums&) noexcept { coupling.step(); } // the modes' q^{n+1}
    const double* blockSums(int head, int side) const { return coupling.blockSums(head, side); }
    void advance() noexcept { modes.advance(); }
    void clear() noexcept { modes.clear(); }
    void setSpec(const DrumConfig& c) noexcept { modes.setSpec(c.cavity); }
    auto energyTerm() const { return EnergyTerm("cavity_modes", modes).listedIf(modes.active()); } // CavityModes.h

    const CavityModes& component() const { return modes; }

private:
    CavityModes modes;
    CavityModesCoupling coupling;
};

} // namespace snaresim
