#pragma once
// The enclosed air as a uniform-pressure adiabatic cavity, in place of the paper's air box
// (eq. 5-8; docs/MODEL.md, "Cavity"). A component: its state is the volume change dV, its
// energy (K/2) dV^{n+1} dV^n. CavityCoupling ties it to the heads: with both heads'
// displacements positive upward dV = h_b^2 sum(w_b) - h_c^2 sum(w_c) and
// p = -(rho_a c_a^2 / V0) dV; the pressure pushes the batter up (+p) and the carry head down (-p).
//
// Explicit form: p^n from dV^n. Its energy is (K/2) dV^{n+1} dV^n, which can dip below
// (K/2)(mu_t+ dV)^2 by at most (K k^2 / 8)(dt+ dV)^2; Membrane reserves that share of its
// kinetic energy in the grid (kineticReserve()), so the coupled scheme is stable for every
// tension the grid allows.

#include "CavitySpec.h"

namespace snaresim
{

class Cavity
{
public:
    Cavity(const CavitySpec& spec, double radius_m);

    // Change the air model or the shell depth (not below the grid's design depth). Real-time safe.
    void setSpec(const CavitySpec& spec, double radius_m);

    // K = rho_a c_a^2 / V0 (Pa/m^3); 0 without air.
    double stiffness() const { return K; }
    // Share of a head's kinetic energy the explicit coupling may need, for the grid of a head
    // of this radius and surface density at time step k: K_max k^2 A / rho, A = pi R^2 (twice
    // the bound K_max k^2 A / (2 rho), for margin).
    static double kineticReserve(const CavitySpec& spec, double radius_m, double density_kg_per_m2, double timeStep_s);

    double pressureNow() const { return -K * dVNow; } // p^n, Pa
    void setVolumeNext(double dV) { dVNext = dV; }
    double energy() const { return 0.5 * K * dVNext * dVNow; } // at n+1/2
    double stepLoss() const { return 0.0; }                    // adiabatic, lossless
    void advance() { dVNow = dVNext; }
    void clear() { dVNow = dVNext = 0.0; }

private:
    double K;
    double dVNow = 0.0, dVNext = 0.0;
};

} // namespace snaresim
