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

class AttachedNearField : public AttachedPair<NearFieldAir, NearFieldCoupling>
{
public:
    AttachedNearField(const DrumConfig& c, Membrane& batter, Membrane& carry, double k)
        : AttachedPair([&] { return NearFieldAir(c.nearFieldSpec(), k); },
                       [&](NearFieldAir& air) {
                           return NearFieldCoupling(batter, carry, air, c.cavity.modeCellSize_m, c.outside.nearFieldCellSize_m);
                       })
    {}

    void beforeHeads(HeadPressure&, HeadPressure&) noexcept
    {
        part.computeFree();
        coupling.applyPressures(); // the near field at n, on the heads' cells
    }
    void afterHeads(const CellSums& taken) noexcept // q^{n+1}, on the cell sums taken already where they fit
    {
        coupling.step({ taken.at(0, coupling.cellSide(0)), taken.at(1, coupling.cellSide(1)) });
    }
    const double* blockSums(int head, int side) const { return coupling.blockSums(head, side); }
    void setSpec(const DrumConfig& c) noexcept { part.setSpec(c.nearFieldSpec()); }
    auto energyTerm() const { return EnergyTerm("near_field", part).listedIf(part.active()); } // NearFieldAir.h
};

} // namespace snaresim
