#pragma once
// The air outside the reduced cavity's drum, reduced to six radiation channels (docs/MODEL.md,
// "Outside air"): the air box's (eq. 5-8) loading of the heads' lowest modes without its grid.
// A component. Each channel c has a coordinate q_c set by OutsideAirCoupling from the heads,
//   monopole  V_b - V_c  the volume the drum pushes out (V = h^2 sum(w), both heads up-positive)
//   dipole    V_b + V_c  the volume carried up through the drum
//   tilt sum x, y   X_b + X_c, Y_b + Y_c  both heads tilting the same way (X = h^2 sum(x w), Y likewise)
//   tilt diff x, y  X_b - X_c, Y_b - Y_c  the heads tilting against each other
// (the drum is mirror-symmetric about its mid-plane, so the air's masses on the two heads'
// volumes, and on their first moments, are symmetric matrices with equal diagonals: these sums
// and differences are their eigenvectors)
// and the air's impedance on it is a mass M_c in parallel with a resistance R_c (the radiation
// impedance of a source small against the wavelength: mass loading below R_c / M_c, radiation
// damping above), behind a compliance 1 / K_c that keeps the heads' coupling explicit:
//   P_c = -K_c (q_c - z_c)             the generalised pressure on q_c (Pa, Pa/m)
//   M_c dv_c/dt = p_c,  dz_c/dt = v_c + p_c / R_c,  p_c = K_c (q_c - z_c)
// with z_c the volume (moment) that has flowed into the outside air. The scheme
//   P^n = -K (q^n - z^n)                                  on the heads at n, explicit
//   p^n = K (q^n - (z^{n+1} + z^{n-1}) / 2)               on the port, implicit in z alone
//   M (v^{n+1/2} - v^{n-1/2}) / k = p^n
//   (z^{n+1} - z^{n-1}) / 2k = (v^{n+1/2} + v^{n-1/2}) / 2 + p^n / R
// has the energy, at n+1/2,
//   E_c = (K/2) [q^{n+1} q^n - q^{n+1} z^n - q^n z^{n+1} + (z^{n+1}^2 + z^n^2) / 2] + (M/2) v^{n+1/2}^2
// whose change over a step is exactly the heads' work on the channels minus k p^2 / R (the sound
// radiated): energy + losses stay constant to round-off, and the air takes no energy it did not
// get (passive). E_c >= (K/2)(mu q - mu z)^2 - (K/4)(q^{n+1} - q^n)^2: the heads keep that
// share of their kinetic energy in their grids (kineticReserve), as for the cavity.

#include "MembraneSpec.h"
#include "OutsideAirSpec.h"

#include <array>
#include <cstddef>

namespace snaresim
{

class OutsideAir
{
public:
    enum Channel
    {
        monopole,
        dipole,
        tiltSumX,
        tiltSumY,
        tiltDiffX,
        tiltDiffY,
        numChannels
    };
    using Values = std::array<double, numChannels>;

    // The channels' compliances K_c from the spec, the heads' densities and the time step k.
    OutsideAir(const OutsideAirSpec& spec, const MembraneSpec& batter, const MembraneSpec& carry, double timeStep_s);

    bool active() const { return on; }
    // K_c (Pa per unit of q_c), 0 for an inactive drum.
    static Values stiffnesses(const OutsideAirSpec& spec, const MembraneSpec& batter, const MembraneSpec& carry, double timeStep_s);
    // Share of a head's kinetic energy the channels' explicit coupling needs (0 when off).
    static double kineticReserve(const OutsideAirSpec& spec, const MembraneSpec& batter, const MembraneSpec& carry, double timeStep_s,
                                 bool ofBatter);

    // Step n's port updates (z^{n+1}, v^{n+1/2}) and the pressures P^n on the channels.
    void computeFree();
    double pressure(Channel c) const { return P[(size_t) c]; }

    // q^{n+1}, from the heads once every force is in (OutsideAirCoupling).
    void setCoordinatesNext(const Values& q) { qNext = q; }

    double energy() const;   // at n + 1/2
    double stepLoss() const; // k sum p^2 / R: radiated over the step
    void advance();
    void clear();

private:
    bool on = false;
    double k;
    Values K {}, M {}, Y {}; // compliance stiffness, mass, conductance 1 / R (0: lossless)
    Values qNow {}, qNext {};
    Values zPrev {}, zNow {}, zNext {};
    Values vPrev {}, vNext {}; // v^{n-1/2}, v^{n+1/2}
    Values P {}, p {};         // on the heads, on the ports
};

} // namespace snaresim
