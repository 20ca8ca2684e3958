#pragma once
// The air models attached to the heads explicitly (the cavity's modes, the outside air, the
// near field): each a component with the coupling that attaches it, built from the drum's
// config. Their pressures at time n act in the heads' free updates; once every force on the
// heads is in, their couplings take q^{n+1} (eq. 22-23 with the air's load explicit). Drum holds
// them in one Attachments list (Attachments.h) and steps them in its order: adding one is its own
// files and one entry of that list (Drum.h).
//
// An attachment A provides:
//   A(const DrumConfig&, Membrane& batter, Membrane& carry, double k)
//   bool active() const                       inactive: never stepped, 0 J, no ledger column
//   void beforeHeads(HeadPressure& onBatter, HeadPressure& onCarry)
//                                             its free update; its pressures at n on the heads
//                                             (on their cells, or added to the uniform and tilt parts)
//   void afterHeads(const CellSums& taken)    q^{n+1}; `taken`: the heads' cell sums of this step
//                                             that the attachments before it have taken
//   const double* blockSums(int head, int side) const   its own cell sums of this step, or nullptr
//   void advance(), void clear()
//   void setSpec(const DrumConfig&) noexcept  a live change (Drum::applyLive)
//   auto energyTerm() const                   its ledger term (EnergyTerm.h)

#include "Attachments.h"
#include "OutsideAirCoupling.h"

#include <array>

namespace snaresim
{

// The heads' cell sums (Membrane::blockSumsNext) the attachments have taken this step, so that
// another coupling or the microphones at the same cells need no pass of their own. Up to
// maxSources attachments; allocation-free.
class CellSums
{
public:
    static constexpr int maxSources = 8;

    template <class A>
    void add(const A& attachment) noexcept
    {
        if (count == maxSources)
            return;
        owners[(size_t) count] = &attachment;
        readers[(size_t) count] = [](const void* a, int head, int side) { return static_cast<const A*>(a)->blockSums(head, side); };
        ++count;
    }

    // The first source's sums of this head at this side, else nullptr.
    const double* at(int head, int side) const noexcept
    {
        for (int i = 0; i < count; ++i)
            if (const double* s = readers[(size_t) i](owners[(size_t) i], head, side))
                return s;
        return nullptr;
    }

private:
    std::array<const void*, maxSources> owners {};
    std::array<const double* (*) (const void*, int, int), maxSources> readers {};
    int count = 0;
};

// What every attached air model shares: its component and the coupling that attaches it, built
// in that order (the coupling from the component), and the component's activity, time step and
// clearing.
template <class Component, class Coupling>
class AttachedPair
{
public:
    bool active() const { return part.active(); }
    void advance() { part.advance(); }
    void clear() { part.clear(); }
    const Component& component() const { return part; }

protected:
    // makeComponent() and makeCoupling(Component&) each return the part they build.
    template <class MakeComponent, class MakeCoupling>
    AttachedPair(MakeComponent&& makeComponent, MakeCoupling&& makeCoupling) : part(makeComponent()), coupling(makeCoupling(part))
    {}

    Component part;
    Coupling coupling;
};

} // namespace snaresim
