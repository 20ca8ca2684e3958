#pragma once
// The enclosed air's own modes, above the uniform pressure of Cavity (docs/MODEL.md, "Cavity
// modes"): eq. 5-8 inside the rigid shell, reduced to the modes of a rigid cylinder of radius R
// and depth H, the batter at z = 0 and the carry head at z = H,
//   Phi = J_m(j'_mn r / R) {cos, sin}(m theta) cos(p pi z / H),
//   omega = c_a sqrt((j'_mn / R)^2 + (p pi / H)^2),
// j'_mn the n-th positive zero of J_m' (the uniform mode, omega = 0, is Cavity's). A component:
// each mode is an AirPort channel, lossless, whose coordinate q is the heads' volume weighted
// by Phi at their faces (CavityModesCoupling),
//   q = int_batter Phi w_b dA - int_carry Phi w_c dA,
// with K = rho_a c_a^2 / int Phi^2 dV and M = K / omega^2: the pressure Phi P = -Phi K (q - z)
// on the heads is the mode's, p'' + omega^2 p = -(rho_a c_a^2 / int Phi^2 dV) q'' (modal
// expansion of eq. 5 with the heads' accelerations as its boundary source). Below its
// frequency a mode is the air's inertia (sloshing across the drum); above, its stiffness.

#include "AirPort.h"
#include "CavitySpec.h"

#include <vector>

namespace snaresim
{

struct CavityMode
{
    int m = 0, n = 0, p = 0; // azimuthal order, radial index (1: the first zero of J_m' above 0), axial order
    bool sine = false;       // sin(m theta), else cos
    double zero = 0.0;       // j'_mn
    int shape = 0;           // index of its face shape (m, n, sine) among the drum's
};

class CavityModes
{
public:
    CavityModes(const CavitySpec& spec, double upTo_Hz, double radius_m, double timeStep_s);

    // The modes up to upTo_Hz at the spec's depth (none with AirModel other than cavity; the
    // drum's cutoff: DrumConfig::cavityModesUpTo_Hz), by frequency; their face shapes (m, n, sine)
    // numbered in order of first use.
    static std::vector<CavityMode> below(const CavitySpec& spec, double upTo_Hz, double radius_m);
    // J_m(j'_mn r / R) {cos, sin}(m theta): a mode's shape on the heads' plane (the batter's face;
    // the carry head's is (-1)^p times it).
    static double faceShape(const CavityMode& mode, double radius_m, double x_m, double y_m);
    // Share of a head's kinetic energy the modes' explicit coupling needs (CavityModes.cpp).
    static double kineticReserve(const CavitySpec& spec, double upTo_Hz, double radius_m, double density_kg_per_m2, double timeStep_s);

    // A new depth (not below the grid's design depth: Cavity::setSpec): K and omega, from the face
    // integrals kept since construction (no Bessel function here). Real-time safe.
    void setSpec(const CavitySpec& spec);

    bool active() const { return ! modes.empty(); }
    int size() const { return (int) modes.size(); }
    int shapes() const { return numShapes; }
    const CavityMode& mode(int i) const { return modes[(size_t) i]; }
    double frequency_Hz(int i) const;

    // Step n's port updates and the pressures P^n on the modes (Pa per unit of Phi).
    void computeFree();
    double pressure(int i) const { return at.P[(size_t) i]; }
    // q^{n+1}, from the heads (CavityModesCoupling).
    double* coordinatesNext() { return at.qNext.data(); }

    double energy() const;                  // at n + 1/2
    double stepLoss() const { return 0.0; } // lossless
    void advance();
    void clear();

private:
    std::vector<CavityMode> modes;
    int numShapes = 0;
    double k = 0.0;
    double radius = 0.0, depth = 0.0, speed = 0.0;
    std::vector<double> faceArea; // int Phi^2 dA over a face, per mode (the radius is the grid's)
    std::vector<double> K, M;
    airport::Levels at; // the modes' time levels and pressures
};

} // namespace snaresim
