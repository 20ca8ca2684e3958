#pragma once
// The air's near field on the heads' higher modes (docs/MODEL.md, "The air's mass on the
// higher modes"). A head mode of wavenumber k = j_mn / R moves far slower than sound (the heads'
// waves run at 90-140 m/s), so the air beside it only sloshes to and fro: a field falling as
// exp(-k |z|) whose pressure is rho_a / k times the head's acceleration on the open side, and
// rho_a coth(k H) / k inside a shell of depth H (the incompressible limit of eq. 5 above a plane
// wave on the head). The reduced cavity and the outside air's channels load only the heads'
// volumes and first moments, and so the lowest modes, (0,1) and (1,1); this loads the heads'
// higher modes, J_m(j_mn r / R) {cos, sin}(m theta) for every j_mn / R up to
// OutsideAirSpec::nearFieldUpTo_per_m (for m = 0 less its mean, for m = 1 less its part along x
// or y: what the channels leave of them), each with the areal mass
//   mu = rho_a (1 + coth(k H)) / k
// (the inner share only with the uniform cavity: the cavity's modes carry their own, and no air
// has none). The air box gives the same to 2 % for m >= 2 (Tests/Engine/DrumAirTests.cpp). For
// m = 0 the volume channels also carry the enclosed column's mass, which they put on the higher
// modes' volume too: (0,2) falls 4 % below the box's (without the near field on its rest, 4.5 %
// above; (0,3) 2 % below against 5 % above).
//
// A component: each shape s is an AirPort channel whose coordinate q_s is the head's volume
// weighted by the shape's mean over its cells (NearFieldCoupling). For the mode itself to carry
// mu, the channel's mass seen at the mode's loaded frequency omega is
//   M_eff = mu A_head / A_cells^2
// (A_head: int of the shape squared over the head; A_cells: the same of its cells' means, which
// also scale q and the force); a compliance 1 / K behind the mass keeps the coupling explicit
// (omega_c = sqrt(K / M), the channel's corner) and M = M_eff (1 - omega^2 / omega_c^2) keeps M_eff
// at omega. A channel alone would ring at about omega_c, the head's shape against the air's mass:
// a damper D = K k / 4 across the compliance (AirPort.h's dampedStep; damping ratio about
// omega_c k / 8) takes it out, and barely touches the mode below it (the compliance hardly moves
// there). The channel's energy is at least -(3K/4)(q^{n+1} - q^n)^2 and
// (q^{n+1} - q^n)^2 <= A_cells k^2 h^2 |dt+ w|^2 (Cauchy-Schwarz); a head's shapes are orthogonal,
// so the head keeps max_s (3/2) K_s A_cells,s k^2 / rho of its kinetic energy for them, doubled
// for margin (the cells make them nearly, not exactly, orthogonal). omega_c is the largest that
// keeps that within OutsideAirSpec::nearFieldReserve.

#include "AirPort.h"
#include "NearFieldSpec.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace snaresim
{

struct NearFieldShape
{
    int head = 0;      // 0 the batter, 1 the carry head
    int m = 2, n = 1;  // azimuthal order, radial index (1: the first zero of J_m)
    bool sine = false; // sin(m theta), else cos
    double zero = 0.0; // j_mn
};

class NearFieldAir
{
public:
    NearFieldAir(const NearFieldSpec& spec, double timeStep_s);

    // The shapes the spec loads (none unless the outside air is on, outside the air box), by
    // head, then by j_mn: every (m, n) but (0,1) and (1,1).
    static std::vector<NearFieldShape> shapes(const NearFieldSpec& spec);
    // J_m(j_mn r / R) {cos, sin}(m theta) at (x, y) on a head of radius R (0 beyond it); for m = 0
    // and 1 less its parts along the volume (first moment) and the lowest mode (0,1) ((1,1)), which
    // the outside air's channels load.
    static double shapeValue(const NearFieldShape& s, double radius_m, double x_m, double y_m);
    // The same with J_m(j_mn r / R) and J_m(j_m1 r / R) given (from tables, for many points).
    static double shapeValue(const NearFieldShape& s, double radius_m, double x_m, double y_m, double radial, double lowest);
    // Share of a head's kinetic energy the channels' explicit coupling needs (0 without them;
    // allocates nothing).
    static double kineticReserve(const NearFieldSpec& spec, bool ofBatter);

    bool active() const { return ! list.empty(); }
    int size() const { return (int) list.size(); }
    const NearFieldShape& shape(int i) const { return list[(size_t) i]; }
    // The areal mass mu the air puts on shape i's mode (kg/m^2), the mode's frequency with it (the
    // continuum's, which the channel is set for) and the channel's corner sqrt(K / M).
    double arealMass(int i) const { return mu[(size_t) i]; }
    double modeFrequency_Hz(int i) const { return omega[(size_t) i] / (2.0 * std::numbers::pi); }
    double corner_Hz(int i) const
    {
        return K[(size_t) i] > 0.0 ? std::sqrt(K[(size_t) i] / M[(size_t) i]) / (2.0 * std::numbers::pi) : 0.0;
    }

    // Shape i's norms on its head's grid (m^2): int of the cells' means squared and of the shape
    // squared, node by node. Sets the channel; NearFieldCoupling calls it once for every shape,
    // before the first step.
    void setNorms(int i, double cellArea, double headArea);
    // New tensions and depth (live; the modes' frequencies move the channels' masses); the shapes
    // and whether the inner share counts stay the construction's. Real-time safe.
    void setSpec(const NearFieldSpec& spec);

    // Step n's port updates and the pressures P^n (Pa per unit of the shape).
    void computeFree();
    const double* pressures() const { return at.P.data(); }
    // q^{n+1}, from the heads (NearFieldCoupling).
    double* coordinatesNext() { return at.qNext.data(); }

    double energy() const;   // at n + 1/2
    double stepLoss() const; // the dampers' k D (dt. s)^2 over the step
    void advance();
    void clear();

private:
    void setChannel(size_t i);

    std::vector<NearFieldShape> list;
    double k;
    double budget = 0.0;  // nearFieldReserve
    double damping = 0.0; // nearFieldDamping
    bool inside = false;  // the inner share counts (the uniform cavity)
    std::array<double, 2> radius {}, density {}, tension {};
    double airDensity = 0.0, depth = 0.0;
    std::vector<double> mu, omega, cellArea, headArea; // per shape
    std::vector<double> K, M, D;
    airport::Levels at; // the channels' time levels and pressures
};

} // namespace snaresim
