#pragma once
// A mallet: a lumped mass moving along z (eq. 9, 26), z measured from the batter's rest plane.
// A component: it owns its state, its free update, its contact patch g_b on the batter and its
// kinetic energy; the contact force and potential belong to MalletContact.

#include "CircularGrid.h"
#include "MalletSpec.h"
#include "PowerLawPotential.h"

namespace snaresim
{

class Mallet
{
public:
    Mallet(const MalletSpec& spec, const CircularGrid& grid, double timeStep_s);

    bool inPlay() const { return active; }
    double mass() const { return M; }
    const PowerLawPotential& potential() const { return contactLaw; }
    const GridDistribution& patch() const { return g; }

    // Position at time levels n+1, n, n-1 (m, up positive).
    double zNext = 0.0, zNow = 0.0, zPrev = 0.0;
    // Penetration eta = h^2 g^T w - z (eq. 27) at n+1, n, n-1.
    double etaNext = 0.0, etaNow = 0.0, etaPrev = 0.0;

    // Free update, z* = 2 z^n - z^{n-1} (eq. 43 without the contact force); MalletContact adds the force.
    void computeFree()
    {
        if (active)
            zNext = 2.0 * zNow - zPrev;
    }

    // Kinetic energy (M/2)(dt+ z)^2 at n+1/2, from zNext and zNow (first term of eq. 37); 0 when parked.
    double energy() const;
    double stepLoss() const { return 0.0; } // lossless
    // The same at n-1/2 (zNow, zPrev): what a new strike replaces, with MalletContact::potentialEnergyBeforeStep.
    double energyBeforeStep() const;

    // Move the contact patch to (x, y) on the head. Real-time safe (no allocation).
    // Returns false, and parks the mallet, when (x, y) is not on the head.
    bool aim(double x_m, double y_m);
    // Launch it just above the head, moving down at speed (m/s), so that it touches within
    // one step. headNow, headPrev: h^2 g^T w at n and n-1 under the new patch.
    void launch(double headNow, double headPrev, double speed_m_per_s);

    void setSpec(const MalletSpec& spec);
    void park();
    void advance();

private:
    const CircularGrid& grid;
    double k;
    double M;
    double patchRadius;
    PowerLawPotential contactLaw;
    GridDistribution g;
    bool active = false;
};

} // namespace snaresim
