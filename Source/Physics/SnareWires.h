#pragma once
// The snare wires: N lossy strings (eq. 12), discretised as eq. (28) on a grid of spacing h_s
// chosen from eq. (40). Each wire lies under the carry head along a chord (the affine map pi
// of eq. 13). End nodes carry half a cell of mass (no ghost point, so eq. 32b-33 are not used)
// and are held to the head by the attachment forces of SnareContact (eq. 17-18, 32a, 48-49);
// interior nodes collide with the head.
// Energy (eq. 38 without the collision potential, which SnareContact owns):
//   h_s sum_l w_l rho/2 (dt+ u_l)^2 + T/(2 h_s) sum_seg du^n du^{n+1} - rho sigma1/(2 k h_s) sum_seg (d(u^{n+1}-u^n))^2,
// with trapezoid weights w_0 = w_M = 1/2; h^{n+1/2} - h^{n-1/2} = -k q^n exactly, q^n >= 0.
// A component: its state, free update (computeFree), energy() and stepLoss().

#include "CacheAligned.h"
#include "GridDesign.h"
#include "SnareSpec.h"

#include <vector>

namespace snaresim
{

class SnareWires
{
public:
    SnareWires(const SnareSpec& spec, double headRadius_m, double timeStep_s);

    // Grid spacing from eq. (40) for the design tension and sigma1 (before fitting to the length).
    static double minimumSpacing(const SnareSpec& spec, double timeStep_s);
    // The spacing the grid is built for: minimumSpacing times the coarseness factor, at the
    // design step below the design rate (designedSpacing).
    static double gridSpacing(const SnareSpec& spec, double timeStep_s)
    {
        return designedSpacing(spec.gridCoarseness, timeStep_s, spec.gridTimeStep_s,
                               [&](double step) { return minimumSpacing(spec, step); });
    }

    int count() const { return numWires; }
    int intervals() const { return M; } // nodes per wire: M + 1
    int nodesPerWire() const { return M + 1; }
    double spacing() const { return hs; }
    double density() const { return rho; }
    double tension() const { return T; }

    // Position on the head of node l of wire i (the map pi).
    double nodeX(int l) const { return -0.5 * length + l * hs; }
    double wireY(int i) const { return y0 + i * pitch; }

    void setCoefficients(double tension_N, double sigma0_per_s, double sigma1_m2_per_s);

    // u^{n+1} for every node with no collision or attachment force.
    void computeFree();
    // Response of u^{n+1} to a force: interior node, per unit force density (N/m) pushing down;
    // end node, per unit force (N) pulling up.
    double interiorGain() const { return kk / (rho * q); }
    double endGain() const { return kk / (0.5 * rho * hs * q); }

    double energy() const { return energyOf(uNext, uNow); }           // at n+1/2
    double energyBeforeStep() const { return energyOf(uNow, uPrev); } // at n-1/2
    double stepLoss() const;                                          // k q^n
    void advance();
    void clear();

    AlignedVector<double> uNext, uNow, uPrev; // flat: wire i, node l at i * (M + 1) + l
    bool isFinite() const;

private:
    double energyOf(const AlignedVector<double>& later, const AlignedVector<double>& earlier) const;

    int numWires, M;
    double length, hs, pitch, y0;
    double k, kk, rho, T = 0, sigma0 = 0, sigma1 = 0, maxT, maxSigma1, q = 1;
    double a0 = 0, a1 = 0, b0 = 0, b1 = 0; // interior stencil
    double e0 = 0, e1 = 0, f0 = 0, f1 = 0; // end stencil (half-cell mass)
};

} // namespace snaresim
