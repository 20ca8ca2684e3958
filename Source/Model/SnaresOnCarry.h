#pragma once
// The snare wires (SnareWires.h) in contact with the carry head, their ends attached to it
// (SnareContact.h, eq. 28, 46-50): a HeadContact (HeadContact.h). Out of the model while thrown
// off (engaged false: no update, no solve, 0 J).

#include "DrumConfig.h"
#include "EnergyTerm.h"
#include "HeadContact.h"
#include "SnareContact.h"
#include "SnareWires.h"
#include "StepProfile.h"

#include <vector>

namespace snaresim
{

class SnaresOnCarry
{
public:
    static constexpr int head = 1;

    SnaresOnCarry(const DrumConfig& c, Membrane&, Membrane& carry, double k)
        : wires(c.fittedSnares(), c.carry.radius_m, k), coupling(c.snares, wires, carry, k), engaged(c.snares.engaged), saved(wires.uNext)
    {}

    template <class Lap>
    void computeFree(Lap& lap)
    {
        if (! engaged)
            return;
        wires.computeFree(); // eq. (28) without collision and end forces
        lap(StepPhase::wiresFree);
    }
    void solve(ContactSolves& solves)
    {
        if (! engaged)
            return;
        solves.snares = coupling.step(); // eq. (48)-(50)
        solves.snaresSolved = true;
    }
    template <class Lap>
    void lapSolve(Lap& lap)
    {
        lap(StepPhase::snareContact);
    }
    void saveTrial()
    {
        if (! engaged)
            return;
        saved = wires.uNext;
        coupling.saveTrial();
    }
    void restoreTrial()
    {
        if (! engaged)
            return;
        wires.uNext = saved;
        coupling.restoreTrial();
    }
    void advance()
    {
        if (! engaged)
            return;
        wires.advance();
        coupling.advance();
    }
    void clear()
    {
        wires.clear();
        coupling.clear();
    }
    auto energyTerm() const { return EnergyTerm("snares", wires, coupling).when(engaged); } // eq. (38)

    SnareWires wires;
    SnareContact coupling;
    bool engaged; // the snares on the head (Drum::setSnaresEngaged)

private:
    AlignedVector<double> saved; // the wires' free u^{n+1}, for the air box's trials
};

} // namespace snaresim
