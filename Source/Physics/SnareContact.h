#pragma once
// Coupling between the snare wires and the carry head: the distributed collision of
// eq. (15)-(16), (30)-(31), solved each step from eq. (50) by Newton-Raphson, and the
// attached ends of eq. (17)-(18), (32)-(33) with their forces eliminated as in eq. (48)-(49).
// It owns those forces and the collision potential (last term of eq. 38).
//
// Structure of Gamma: each contact point maps to its nearest carry-head node (G_s is then a
// scaled selection), so points at different nodes do not interact within a step and Gamma is
// block diagonal, one block per head node. A block is gamma_s I + c' h_s 1 1^T (the string's
// own response plus the shared node), so its Newton step is a Sherman-Morrison solve, O(size).
// An attached end at the node is eliminated first: it only stiffens the node (c -> c').
//
// Layout: the node groups are sorted into classes of equal size; a class of G groups of K
// points stores its points member-major (member j of group i at j G + i), so that every
// per-point and per-group loop of the quadratised solve runs over contiguous arrays and
// vectorises: the per-group sums member by member over the class, the per-point loops once over
// all points, each reading its wire node's and its group's values by index (pointGroup).
//
// Two schemes for the collision term (SnareSpec::scheme):
// - newton: the paper's eq. (30), f = (Phi(xi^{n+1}) - Phi(xi^{n-1})) / (xi^{n+1} - xi^{n-1}),
//   solved per node group by Newton-Raphson; the energy term is h_s sum mu_t+ Phi(xi).
// - quadratised (energy quadratisation, Ducceschi et al., JASA 149(5), 2021): each point keeps
//   psi ~ sqrt(2 Phi(xi)) at half steps and, with a slope g^n known before the step,
//     f = g mu_t+ psi^{n-1/2},  psi^{n+1/2} = psi^{n-1/2} + (g/2)(xi^{n+1} - xi^{n-1}),
//   which is linear in xi^{n+1}: a node group is solved in one Sherman-Morrison pass, no
//   iteration. Its energy term is h_s sum (psi^{n+1/2})^2 / 2, and f (xi^{n+1} - xi^{n-1}) / 2 is
//   exactly its change, so the drum's energy identity holds as with Newton, for any g. The
//   tangent g = psi'(xi^n) lets psi fall far behind sqrt(2 Phi) when a wire arrives fast (a
//   contact begins with xi^n near 0 and a small g), and the wires then sink into the head; we
//   take g as the secant of psi from xi^{n-1} to the free prediction of xi^{n+1}, which is exact
//   when the prediction is. psi^{n+1/2} stands for the potential of xi^n and xi^{n+1}, so it
//   runs down to zero on the step after a point leaves the head; psi is evolved, not
//   recomputed, so a little can be left then. Where a point is apart at n and n+1 it is reset
//   to zero and the energy removed, h_s psi^2 / 2 >= 0, is booked as a loss (stepLoss()),
//   so the scheme stays passive and the ledger balances.
//   A point apart at n-1, apart in the prediction and holding no psi gets g = 0, no force and
//   keeps psi = 0: its node group is left out of the step unless another of its points takes
//   part, which gives the same numbers as solving it; the work per step is at most that of
//   every point touching. With the Hertz exponent (1.5) g is computed in single precision (any
//   g keeps the identity), everything that enters the energy in double.

#include "Membrane.h"
#include "PowerLawPotential.h"
#include "SnareWires.h"

#include <cmath>
#include <vector>

namespace snaresim
{

struct SnareSolveResult
{
    int iterations = 0;            // largest Newton iteration count over the node groups this step
    int contacts = 0;              // contact points touching the head at n+1
    bool fallback = false;         // some group needed the bracketed fallback
    double maxPenetration_m = 0.0; // largest xi^{n+1}, 0 when apart
};

class SnareContact
{
public:
    static constexpr int maxNewtonIterations = 50;
    static constexpr double tolerance = 1.0e-14;      // Newton step / (|r| + |a| + |b|)
    static constexpr double groupTolerance = 1.0e-12; // on the total force of a node group

    // The wires and the carry head it couples (both must outlive it); k, the time step.
    SnareContact(const SnareSpec& spec, SnareWires& wires, Membrane& carry, double timeStep_s);

    CollisionScheme scheme() const { return method; }

    // The force kappa [xi]_+^beta (1 + lambda dxi/dt) (Hunt and Crossley; lambda = 0: eq. 16's
    // elastic law): kappa, beta and lambda (s/m).
    void setLaw(double stiffness, double exponent, double damping_s_per_m);

    // After the free updates of the carry head and the wires: solve the collisions and the
    // attachments, and write w_c^{n+1} at the touched nodes and u^{n+1} of the wires.
    SnareSolveResult step();

    // The collision potential h_s sum mu_t+ Phi_s at n+1/2 (last term of eq. 38; quadratised:
    // h_s sum psi^2 / 2). The attached ends store none.
    double energy() const;
    double energyBeforeStep() const; // at n-1/2
    // Energy the last step removed: the contact's damping's work and, quadratised, psi reset at
    // separated points (h_s psi^2 / 2).
    double stepLoss() const { return lastCorrection; }
    double maxPenetration() const;    // largest xi^{n+1} (m), 0 when apart
    double quadratisedEnergy() const; // h_s sum psi^2 / 2
    int numPoints() const { return (int) pointWireNode.size(); }
    // xi = u - w_c per contact point at the latest completed step (after Drum::step), in the
    // coupling's own order (the class layout above)
    const AlignedVector<double>& gaps() const { return xiNow; }
    // the same gap for interior node l (1 ... M-1) of wire i
    double gapAt(int wire, int l) const;

    // The state a step changes beyond the wires' and the head's next levels (the quadratised
    // psi), saved before a step and put back to solve the same step again (DrumAir).
    void saveTrial() { trialPsi = psiQ; }
    void restoreTrial() { psiQ = trialPsi; }

    // The quadratised solve takes the node groups holding a point that touches at n-1, would
    // touch without contact forces, or holds psi (and the groups holding wire ends); the others
    // stay as their solve would leave them. Every group solved instead (a test's reference):
    void setSolveEveryPoint(bool every) { solveEveryPoint = every; }
    // the points the last quadratised step solved (at most numPoints())
    int solvedPoints() const { return lastSolvedPoints; }

    // A class of node groups of `size` points each (the layout above): groupCount groups from
    // groupBegin, their points from pointBegin.
    struct SizeClass
    {
        int size, groupBegin, groupCount, pointBegin;
    };

    void advance();
    // Lay the wires on the carry head as it is at n and n-1 (snares engaged): every node
    // moves with the head node it maps to, gaps are zero.
    void layOnHead();
    void clear();

private:
    SnareSolveResult stepNewton(Membrane& carry, SnareWires& wires);
    SnareSolveResult stepQuadratised(Membrane& carry, SnareWires& wires);
    // psi(xi) = sqrt(2 Phi(xi)) = sqrt(2 kappa / (beta + 1)) [xi]_+^((beta + 1) / 2), for an
    // exponent other than 1.5 (that one: hertzCoefficients)
    double psiOf(double x) const { return x > 0.0 ? psiScale * std::pow(x, halfExponent + 1.0) : 0.0; }
    // The slope g of psi from a = xi^{n-1} to b = xi* for an exponent other than 1.5 (that one:
    // hertzCoefficients): the secant where a contact begins or ends, the tangent at the midpoint
    // while both touch (equal to the secant to O((b - a)^2), without its cancellation).
    double psiSlope(double from, double to) const
    {
        if (from > 0.0 && to > 0.0)
        {
            const double mid = 0.5 * (from + to);
            return gScale * std::pow(mid, halfExponent);
        }
        if (from <= 0.0 && to <= 0.0)
            return 0.0;
        return (psiOf(to) - psiOf(from)) / (to - from);
    }
    // The ends of a group eliminated (eq. 48-49): W = W0 + cc H for a total contact force H.
    // c: w_c^{n+1} at a node per unit force (N) there.
    void eliminateEnds(int group, const Membrane& carry, const SnareWires& wires, double c, double& W0, double& cc) const;
    void solveGroup(int group, Membrane& carry, SnareWires& wires, SnareSolveResult& result);
    bool solveGroupNewton(int m, double gammaS, double coupling, int& iterations);
    bool solveGroupReduced(int m, double gammaS, double coupling, int& iterations);
    // point i of the group alone, its force's sum over the group held: r + gamma F + bi = 0
    double solvePoint(int i, double gamma, double bi, int& iterations) const;
    double solveFallback(int m, double gammaS, double coupling);

    PowerLawPotential law;
    CollisionScheme method;
    double hs;
    double timeStep;
    double dampingPerStep = 0.0; // lambda / (2k): D = dampingPerStep Phi'(xi^n)
    double gScale = 0.0;         // sqrt(kappa (beta + 1) / 2)
    double psiScale = 0.0;       // sqrt(2 kappa / (beta + 1))
    double halfExponent = 0.25;  // (beta - 1) / 2
    bool quarterPower = true;    // beta = 1.5: hertzCoefficients
    double lastCorrection = 0.0;
    // contact points (in class layout, above): wire-array index of the node, head node
    AlignedVector<int> pointWireNode, pointHeadNode;
    AlignedVector<int> endWireNode, endHeadNode;
    // groups (one per head node), class by class: the node, its points and its ends (CSR)
    AlignedVector<int> groupNode, groupMemberBegin, groupMembers, groupEndBegin, groupEnds;
    AlignedVector<int> endGroups; // groups holding wire ends
    std::vector<SizeClass> classes;
    AlignedVector<double> xiNext, xiNow, xiPrev;
    AlignedVector<double> rLast;        // last step's root per point (NaN when it was not solved): Newton's start
    AlignedVector<double> psiQ;         // quadratised: psi at n+1/2 (after step) / n-1/2 (before), per point
    AlignedVector<double> trialPsi;     // psiQ before the step (saveTrial)
    AlignedVector<int> pointOfWireNode; // wire i, interior node l -> point (i * (M - 1) + l - 1)
    int wireInterior = 0;               // interior nodes per wire, M - 1
    // Newton: per-group scratch (sized for the largest group)
    AlignedVector<int> active;
    AlignedVector<double> a, b, r, psi, dpsi, phiA, damp; // damp: D per point
    // quadratised: per group W0, c' and W (all groups); per point solved g,
    // alpha, beta, u*
    AlignedVector<double> groupW0, groupCc, groupW;
    AlignedVector<double> gq, alphaQ, betaQ, uFree, dampQ;  // dampQ: D per point
    AlignedVector<float> secantRows;                        // hertzCoefficients' gaps, span and secant in floats: three rows
    // each point's group: every point's (class layout), the solved points' (in the solve's groups)
    AlignedVector<int> pointGroup, solvePointGroup;
    // The solve's subset: per group its reach (predictClass: positive when it takes part), the
    // groups and points that do (the class layout over them: activeClasses), their values gathered.
    AlignedVector<double> groupReach;
    AlignedVector<int> activeGroups, activePoints, solveWireNode;
    std::vector<SizeClass> activeClasses; // as many as classes: those taking part first
    AlignedVector<double> solveXiPrev, solveXiNow, solveXiNext, solvePsi, solveDropped;
    AlignedVector<double> solveGroupW0, solveGroupCc, solveGroupS, solveGroupW;
    bool solveEveryPoint = false;
    int lastSolvedPoints = 0;
    // alpha, beta, g, u* and D of `count` points into alphaQ, betaQ, gq, uFree and dampQ
    // (xiBefore: xi^{n-1}, xiAt: xi^n; point t's group's W0 and cc at group[t])
    void coefficients(int count, const int* wireNode, const double* xiBefore, const double* xiAt, const double* psiBefore, const int* group,
                      const double* W0, const double* cc, double gammaS, const double* u);

    SnareWires& snares;
    Membrane& head; // the carry head
};

} // namespace snaresim
