#pragma once
// The near field's mass on the heads' higher modes (NearFieldAir.h) attached to both heads
// (NearFieldCoupling.h): an AttachedAir (AttachedAir.h). Inactive without it.

#include "AttachedAir.h"
#include "DrumConfig.h"
#include "EnergyTerm.h"
#include "NearFieldAir.h"
#include "NearFieldCoupling.h"

namespace snaresim
{

class AttachedNearField
{
public:
    AttachedNearField(const DrumConfig& c, Membrane& batter, Membrane& carry, double k)
        : air(c.nearFieldSpec(), k), coupling(batter, carry, air, c.cavity.modeCellSize_m, c.outside.nearFieldCellSize_m)
    {}

    bool active() const { return air.active(); }
    void beforeHeads(HeadPressure&, HeadPressure&) noexcept
    {
        air.computeFree();
        coupling.applyPressures(); // the near field at n, on the heads' cells
    }
    void afterHeads(const CellSums& taken) noexcept // q^{n+1}, on the cell sums taken already where they fit
    {
        coupling.step({ taken.at(0, coupling.cellSide(0)), taken.at(1, coupling.cellSide(1)) });
    }
    const double* blockSums(int head, int side) const { return coupling.blockSums(head, side); }
    void advance() noexcept { air.advance(); }
    void clear() noexcept { air.clear(); }
    void setSpec(const DrumConfig& c) noexcept { air.setSpec(c.nearFieldSpec()); }
    auto energyTerm() const { return EnergyTerm("near_field", air).listedIf(air.active()); } // NearFieldAir.h

    const NearFieldAir& component() const { return air; }

private:
    NearFieldAir air;
    NearFieldCoupling coupling;
};

} // namespace snaresim
