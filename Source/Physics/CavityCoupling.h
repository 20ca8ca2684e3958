#pragma once
// Coupling between the heads and the cavity, in place of the air forces F_b^- (below the batter)
// and F_c^+ (above the carry head) of eq. (2)-(3): the cavity's pressure p^n = -K dV^n pushes the batter up (+p)
// and the carry head down (-p) in their free updates, and once the contact solves have moved
// the heads, their swept volumes give dV^{n+1} = h_b^2 sum(w_b^{n+1}) - h_c^2 sum(w_c^{n+1}).
// Explicit (see Cavity.h), so it has no solve. It stores no energy and removes none: the work
// the pressure does on the heads over a step is exactly the cavity's energy change.

#include "Cavity.h"
#include "Membrane.h"

namespace snaresim
{

class CavityCoupling
{
public:
    CavityCoupling(Membrane& batterHead, Membrane& carryHead, Cavity& cavity) : batter(batterHead), carry(carryHead), air(cavity) {}

    // The pressure (Pa, pushing up) on each head at time n, for its free update (eq. 22-23).
    double pressureOnBatter() const { return air.pressureNow(); }
    double pressureOnCarry() const { return -air.pressureNow(); }

    // After every force on the heads is in: dV^{n+1} from their swept volumes.
    void step() { air.setVolumeNext(batter.sweptVolumeNext() - carry.sweptVolumeNext()); }

    double energy() const { return 0.0; }
    double stepLoss() const { return 0.0; }

private:
    Membrane& batter;
    Membrane& carry;
    Cavity& air;
};

} // namespace snaresim
