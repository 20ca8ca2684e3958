#pragma once
// The parts of the implicit solve in contact with a head (eq. 44-50): the mallets on the batter,
// the snare wires on the carry head, each a component with the contact coupling that solves for
// its forces, built from the drum's config. Drum holds them in one Attachments list
// (Attachments.h) and steps them in its order, on both of its step paths (with the reduced air,
// and in the air box, where each head's contacts are solved jointly with its air): adding one is
// its own files and one entry of that list (Drum.h).
//
// A contact C provides:
//   C(const DrumConfig&, Membrane& batter, Membrane& carry, double k)
//   static constexpr int head                0 batter, 1 carry: the head it acts on
//   template <class Lap> void computeFree(Lap&)   its component's free update, then lap(its phase)
//   void solve(ContactSolves&)               its coupling's solve, added to the free updates; its result noted
//   template <class Lap> void lapSolve(Lap&) lap(its solve's phase) (the reduced air's path)
//   void saveTrial(), void restoreTrial()    the air box's joint solve tries the contacts again
//   void advance(), void clear()
//   auto energyTerm() const                  its ledger term (EnergyTerm.h)

#include "MalletContact.h"
#include "SnareContact.h"

namespace snaresim
{

// What a step's contact solves found (SolverStats): each contact notes its own.
struct ContactSolves
{
    ContactSolveResult mallets;
    SnareSolveResult snares;
    bool snaresSolved = false;
};

} // namespace snaresim
