#pragma once
// Coupling between the snare wires and the carry head: the distributed collision of
// eq. (15)-(16), (30)-(31), solved each step from eq. (50) by Newton-Raphson, and the
// attached ends of eq. (17)-(18), (32)-(33) with their forces eliminated as in eq. (48)-(49).
//
// Structure of Gamma: each contact point maps to its nearest carry-head node (G_s is then a
// scaled selection), so points at different nodes do not interact within a step and Gamma is
// block diagonal, one block per head node. A block is gamma_s I + c' h_s 1 1^T (the string's
// own response plus the shared node), so its Newton step is a Sherman-Morrison solve, O(size).
// An attached end at the node is eliminated first: it only stiffens the node (c -> c').

#include "Membrane.h"
#include "PowerLawPotential.h"
#include "SnareWires.h"

#include <vector>

namespace snaresim
{

struct SnareSolveResult
{
    int iterations = 0;     // largest Newton iteration count over the node groups this step
    int contacts = 0;       // contact points touching the head at n+1
    bool fallback = false;  // some group needed the bracketed fallback
};

class SnareContact
{
public:
    static constexpr int maxNewtonIterations = 50;
    static constexpr double tolerance = 1.0e-14; // Newton step / (|r| + |a| + |b|)
    static constexpr double groupTolerance = 1.0e-12; // on the total force of a node group

    SnareContact(const SnareSpec& spec, const SnareWires& wires, const Membrane& carry);

    void setLaw(double stiffness, double exponent);

    // After the free updates of the carry head and the wires: solve the collisions and the
    // attachments, and write w_c^{n+1} at the touched nodes and u^{n+1} of the wires.
    SnareSolveResult step(Membrane& carry, SnareWires& wires);

    // h_s sum mu_t+ Phi_s at n+1/2 (last term of eq. 38).
    double potentialEnergy() const;
    double potentialEnergyBeforeStep() const; // at n-1/2
    double maxPenetration() const; // largest xi^{n+1} (m), 0 when apart
    int numPoints() const { return (int) pointWireNode.size(); }
    // xi = u - w_c per contact point at the latest completed step (after Drum::step)
    const std::vector<double>& gaps() const { return xiNow; }

    void advance();
    // Lay the wires on the carry head as it is at n and n-1 (snares engaged): every node
    // moves with the head node it maps to, gaps are zero.
    void layOnHead(const Membrane& carry, SnareWires& wires);
    void clear();

private:
    void solveGroup(int group, Membrane& carry, SnareWires& wires, SnareSolveResult& result);
    bool solveGroupNewton(int m, double gammaS, double coupling, int& iterations);
    bool solveGroupReduced(int m, double gammaS, double coupling, int& iterations);
    double solveFallback(int m, double gammaS, double coupling);

    PowerLawPotential law;
    double hs;
    int firstNode = 0;
    // contact points: wire-array index of the node, head node, grouped by head node (CSR)
    std::vector<int> pointWireNode, pointHeadNode;
    std::vector<int> endWireNode, endHeadNode;
    std::vector<int> groupNode, groupPointBegin, groupEndBegin;
    std::vector<int> groupPoints, groupEnds;
    std::vector<double> xiNext, xiNow, xiPrev;
    std::vector<double> rLast; // last step's root per point (NaN when it was not solved): Newton's start
    // per-group scratch (sized for the largest group)
    std::vector<int> active;
    std::vector<double> a, b, r, psi, dpsi, phiA;
};

} // namespace snaresim
