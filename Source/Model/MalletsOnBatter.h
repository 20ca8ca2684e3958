#pragma once
// The mallets (Mallet.h) in contact with the batter (MalletContact.h, eq. 43-45): a HeadContact
// (HeadContact.h). Never resized after construction.

#include "DrumConfig.h"
#include "EnergyTerm.h"
#include "HeadContact.h"
#include "Mallet.h"
#include "MalletContact.h"
#include "StepProfile.h"

#include <array>
#include <span>
#include <vector>

namespace snaresim
{

class MalletsOnBatter
{
public:
    static constexpr int head = 0;

    MalletsOnBatter(const DrumConfig& c, Membrane& batter, Membrane&, double k) : mallets(make(c, batter, k)), coupling(batter, mallets) {}

    template <class Lap>
    void computeFree(Lap& lap)
    {
        for (auto& m : mallets)
            m.computeFree(); // eq. (43) without the contact force
        lap(StepPhase::malletsFree);
    }
    void solve(ContactSolves& solves) { solves.mallets = coupling.step(); } // eq. (44)-(45)
    template <class Lap>
    void lapSolve(Lap& lap)
    {
        lap(StepPhase::malletContact);
    }
    void saveTrial()
    {
        for (size_t i = 0; i < mallets.size(); ++i)
            saved[i] = mallets[i].zNext;
    }
    void restoreTrial()
    {
        for (size_t i = 0; i < mallets.size(); ++i)
            mallets[i].zNext = saved[i];
    }
    void advance()
    {
        for (auto& m : mallets)
            m.advance();
    }
    void clear()
    {
        for (auto& m : mallets)
            m.park();
    }
    auto energyTerm() const { return EnergyTerm("mallets", mallets, coupling); } // eq. (37)

    std::vector<Mallet> mallets;
    MalletContact coupling;

private:
    static std::vector<Mallet> make(const DrumConfig& c, const Membrane& batter, double k)
    {
        std::vector<Mallet> list;
        list.reserve((size_t) c.numMallets);
        for (int i = 0; i < c.numMallets; ++i)
            list.emplace_back(c.mallet, batter.grid(), k);
        return list;
    }

    std::array<double, MalletContact::maxMallets> saved {};
};

} // namespace snaresim
