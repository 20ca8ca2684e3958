#pragma once
// The outside air's radiation channels (OutsideAir.h) attached to both heads
// (OutsideAirCoupling.h): an AttachedAir (AttachedAir.h). Inactive in the air box (which holds
// the outside air itself) and when the outside air is off. Its spec is the model's own: a live
// change leaves it as built.

#include "AttachedAir.h"
#include "DrumConfig.h"
#include "EnergyTerm.h"
#include "OutsideAir.h"
#include "OutsideAirCoupling.h"

namespace snaresim
{

class AttachedOutsideAir : public AttachedPair<OutsideAir, OutsideAirCoupling>
{
public:
    AttachedOutsideAir(const DrumConfig& c, Membrane& batter, Membrane& carry, double k)
        : AttachedPair([&] { return OutsideAir(c.cavity.model == AirModel::airbox ? OutsideAirSpec {} : c.outside, c.batter, c.carry, k); },
                       [&](OutsideAir& air) { return OutsideAirCoupling(batter, carry, air); })
    {}

    void beforeHeads(HeadPressure& onBatter, HeadPressure& onCarry) noexcept
    {
        part.computeFree();
        const HeadPressure b = coupling.onBatter(), c = coupling.onCarry();
        onBatter = { onBatter.p0 + b.p0, onBatter.px + b.px, onBatter.py + b.py };
        onCarry = { onCarry.p0 + c.p0, onCarry.px + c.px, onCarry.py + c.py };
    }
    void afterHeads(const CellSums&) noexcept { coupling.step(); } // q^{n+1}
    const double* blockSums(int, int) const { return nullptr; }
    void setSpec(const DrumConfig&) noexcept {}
    auto energyTerm() const { return EnergyTerm("outside", part).listedIf(part.active()); } // OutsideAir.h
};

} // namespace snaresim
