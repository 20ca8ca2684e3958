#include "SnareContact.h"

#include "CollisionSolve.h"
#include "VectorTarget.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

#if SNARESIM_VECTOR_TARGETS
#include <immintrin.h>
#endif

namespace snaresim
{
namespace
{
// a row of secantRows for n points: whole cache lines
int rowOf(int n) { return (n + 15) & ~15; }
} // namespace

SnareContact::SnareContact(const SnareSpec& spec, SnareWires& wires, Membrane& carry, double timeStep_s)
    : method(spec.scheme), hs(wires.spacing()), timeStep(timeStep_s), snares(wires), head(carry)
{
    setLaw(spec.stiffness, spec.exponent, spec.contactDamping_s_per_m);
    const auto& grid = carry.grid();
    const int M = wires.intervals(), stride = M + 1;
    std::map<int, std::pair<std::vector<int>, std::vector<int>>> byNode; // head node -> (points, ends)
    for (int i = 0; i < wires.count(); ++i)
        for (int l = 0; l <= M; ++l)
        {
            const int node = grid.nearestInterior(wires.nodeX(l), wires.wireY(i));
            if (node < 0)
                throw std::invalid_argument("the snare wires do not fit on the carry head: shorten them or narrow their spacing");
            const int wireNode = i * stride + l;
            if (l == 0 || l == M)
            {
                byNode[node].second.push_back((int) endWireNode.size());
                endWireNode.push_back(wireNode);
                endHeadNode.push_back(node);
            }
            else
            {
                byNode[node].first.push_back((int) pointWireNode.size());
                pointWireNode.push_back(wireNode);
                pointHeadNode.push_back(node);
            }
        }
    // Sort the groups into classes of equal size (by node within a class) and number each
    // class's points member-major (the layout in the header); pointOfWireNode maps the ids
    // above, which ran over the wires' interior nodes in order.
    std::map<int, std::vector<int>> nodesBySize;
    size_t largest = 1;
    for (const auto& [node, members] : byNode)
    {
        nodesBySize[(int) members.first.size()].push_back(node);
        largest = std::max(largest, members.first.size());
    }
    const size_t numPoints = pointWireNode.size();
    std::vector<int> wireNodeOrdered(numPoints), headNodeOrdered(numPoints);
    pointOfWireNode.assign(numPoints, 0);
    groupMembers.assign(numPoints, 0);
    int pointBegin = 0;
    for (const auto& [size, nodes] : nodesBySize)
    {
        const int groupBegin = (int) groupNode.size(), count = (int) nodes.size();
        classes.push_back({ size, groupBegin, count, pointBegin });
        for (int i = 0; i < count; ++i)
        {
            const auto& members = byNode[nodes[(size_t) i]];
            const int g = groupBegin + i;
            groupNode.push_back(nodes[(size_t) i]);
            groupEndBegin.push_back((int) groupEnds.size());
            groupEnds.insert(groupEnds.end(), members.second.begin(), members.second.end());
            if (! members.second.empty())
                endGroups.push_back(g);
            groupMemberBegin.push_back(pointBegin + i * size);
            for (int j = 0; j < size; ++j)
            {
                const int old = members.first[(size_t) j], t = pointBegin + j * count + i;
                pointOfWireNode[(size_t) old] = t;
                wireNodeOrdered[(size_t) t] = pointWireNode[(size_t) old];
                headNodeOrdered[(size_t) t] = pointHeadNode[(size_t) old];
                groupMembers[(size_t) (pointBegin + i * size + j)] = t;
            }
        }
        pointBegin += size * count;
    }
    groupMemberBegin.push_back(pointBegin);
    groupEndBegin.push_back((int) groupEnds.size());
    pointWireNode.assign(wireNodeOrdered.begin(), wireNodeOrdered.end());
    pointHeadNode.assign(headNodeOrdered.begin(), headNodeOrdered.end());
    wireInterior = M - 1;
    for (auto* v : { &groupW0, &groupCc, &groupW })
        v->assign(groupNode.size(), 0.0);
    for (auto* v : { &gq, &alphaQ, &betaQ, &uFree, &dampQ, &solveXiPrev, &solveXiNow, &solveXiNext, &solvePsi, &solveDropped })
        v->assign(numPoints, 0.0);
    secantRows.assign(3 * (size_t) rowOf(numPoints), 0.0f);
    pointGroup.assign(numPoints, 0);
    solvePointGroup.assign(numPoints, 0);
    for (const SizeClass& c : classes)
        for (int j = 0; j < c.size; ++j)
            for (int i = 0; i < c.groupCount; ++i)
                pointGroup[(size_t) (c.pointBegin + j * c.groupCount + i)] = c.groupBegin + i;
    for (auto* v : { &solveGroupW0, &solveGroupCc, &solveGroupS, &solveGroupW })
        v->assign(groupNode.size(), 0.0);
    groupReach.assign(groupNode.size(), 0.0);
    activePoints.assign(numPoints, 0);
    solveWireNode.assign(numPoints, 0);
    activeGroups.assign(groupNode.size(), 0);
    activeClasses.resize(classes.size());
    psiQ.assign(numPoints, 0.0);
    trialPsi = psiQ;
    rLast.assign(numPoints, std::numeric_limits<double>::quiet_NaN());
    xiNext.assign(numPoints, 0.0);
    xiNow = xiNext;
    xiPrev = xiNext;
    for (auto* v : { &a, &b, &r, &psi, &dpsi, &phiA, &damp })
        v->assign(largest, 0.0);
    active.assign(largest, 0);
}

void SnareContact::setLaw(double stiffness, double exponent, double damping_s_per_m)
{
    dampingPerStep = damping_s_per_m / (2.0 * timeStep);
    law.kappa = stiffness;
    law.alpha = exponent;
    gScale = std::sqrt(0.5 * stiffness * (exponent + 1.0));
    psiScale = std::sqrt(2.0 * stiffness / (exponent + 1.0));
    halfExponent = 0.5 * (exponent - 1.0);
    quarterPower = exponent == 1.5;
}

SnareSolveResult SnareContact::step()
{
    return method == CollisionScheme::quadratised ? stepQuadratised(head, snares) : stepNewton(head, snares);
}

void SnareContact::eliminateEnds(int g, const Membrane& carry, const SnareWires& wires, double c, double& W0, double& cc) const
{
    // Attached ends (eq. 32a, 48-49): u_e^{n+1} = W. With W = W* + c (H - sum lambda) and
    // u_e^{n+1} = u_e* + gammaE lambda_e, the ends act on the node as W = W0 + c' H.
    const double Wfree = carry.nextAt(groupNode[(size_t) g]);
    const int e0 = groupEndBegin[(size_t) g], e1 = groupEndBegin[(size_t) g + 1];
    double sumU = 0.0;
    for (int e = e0; e < e1; ++e)
        sumU += wires.uNext[(size_t) endWireNode[(size_t) groupEnds[(size_t) e]]];
    const double invGammaE = 1.0 / wires.endGain(); // end node u^{n+1} per unit force (N), inverted
    const double G = (e1 - e0) * invGammaE;
    const double D = ((e1 - e0) * Wfree - sumU) * invGammaE;
    W0 = Wfree - c * D / (1.0 + c * G);
    cc = c / (1.0 + c * G);
}

namespace
{
#define SNARESIM_KERNELS "SnareContactKernels.inl"
#include "PerVectorTarget.inl"
} // namespace

void SnareContact::coefficients(int count, const int* wireNode, const double* xiBefore, const double* xiAt, const double* psiBefore,
                                const int* group, const double* W0, const double* cc, double gammaS, const double* u)
{
    // f = A + B xi^{n+1} with B = g^2/4 + D, A = g psi^{n-1/2} - B xi^{n-1}, and
    // xi^{n+1} = xi* - gammaS f - cc h_s S, S = sum f over the group. Eliminating xi^{n+1}:
    // f = alpha - beta S with alpha = (A + B xi*) / (1 + gammaS B), beta = cc h_s B / (1 + gammaS B).
    // D = lambda Phi'(xi^n) / (2k) >= 0: the contact's damping (Hunt and Crossley), a force
    // D (xi^{n+1} - xi^{n-1}) whose work D (xi^{n+1} - xi^{n-1})^2 h_s / 2 is a loss.
    const bool damped = dampingPerStep > 0.0;
    if (quarterPower)
    {
        const auto kernel =
            damped ? SNARESIM_ON_VECTOR_TARGET(hertzCoefficients<true>) : SNARESIM_ON_VECTOR_TARGET(hertzCoefficients<false>);
        kernel(count, wireNode, xiBefore, xiAt, u, psiBefore, group, W0, cc, hs, psiScale, gammaS, dampingPerStep * law.kappa, gq.data(),
               alphaQ.data(), betaQ.data(), uFree.data(), dampQ.data(), secantRows.data(), secantRows.data() + rowOf(count),
               secantRows.data() + 2 * rowOf(count));
        return;
    }
    for (int t = 0; t < count; ++t)
    {
        const double us = u[wireNode[t]], a = xiBefore[t];
        const double predicted = us - W0[group[t]];
        const double gp = psiSlope(a, predicted);
        double B = 0.25 * gp * gp;
        if (damped)
        {
            dampQ[(size_t) t] = dampingPerStep * law.dphi(xiAt[t]);
            B += dampQ[(size_t) t];
        }
        const double d = 1.0 / (1.0 + gammaS * B);
        gq[(size_t) t] = gp;
        alphaQ[(size_t) t] = (gp * psiBefore[t] + B * (predicted - a)) * d;
        betaQ[(size_t) t] = cc[group[t]] * hs * B * d;
        uFree[(size_t) t] = us;
    }
}

SnareSolveResult SnareContact::stepQuadratised(Membrane& carry, SnareWires& wires)
{
    const double h = carry.grid().spacing();
    const double gammaS = wires.interiorGain(); // u^{n+1} per unit force density (N/m)
    double* u = wires.uNext.data();
    const int numGroups = (int) groupNode.size();

    // Per group: the head node as the ends leave it, W = W0 + cc H (eq. 48-49).
    const double gain = carry.forceGain() / (h * h); // w_c^{n+1} per unit force (N) at a node, times its response
    const double* response = carry.responseScale();
    carry.nextAt(groupNode.data(), groupW0.data(), numGroups);
    if (response)
        SNARESIM_ON_VECTOR_TARGET(gatherScaled)(numGroups, groupNode.data(), response, gain, groupCc.data());
    else
        std::fill(groupCc.begin(), groupCc.begin() + numGroups, gain);
    for (int g : endGroups)
        eliminateEnds(g, carry, wires, groupCc[(size_t) g], groupW0[(size_t) g], groupCc[(size_t) g]);

    // Per point: g^n is the slope of psi(xi) = sqrt(2 Phi(xi)) from xi^{n-1} to the prediction
    // xi* = u* - W0 (no contact force), so psi follows sqrt(2 Phi) closely where the prediction
    // is good, and g = 0 (no force, psi stays zero) where both are apart. Each point reads its
    // group's W0 by the group's index (pointGroup, solvePointGroup), so that every per-point loop runs
    // once over all points.
    const int n = (int) pointWireNode.size();
    // The groups holding a point that takes part, and those holding wire ends (their node moves
    // with the ends), are solved; the others keep xi* and their free node, as their solve would
    // leave them. The work is at most that of every point touching.
    const int numClasses = (int) classes.size();
    SNARESIM_ON_VECTOR_TARGET(predictClasses)
    (classes.data(), numClasses, pointWireNode.data(), u, groupW0.data(), xiPrev.data(), psiQ.data(), xiNext.data(), groupReach.data());
    for (int g : endGroups)
        groupReach[(size_t) g] = 1.0;
    int solvedGroups = 0, solvedPoints = 0;
    const int numActive = SNARESIM_ON_VECTOR_TARGET(listReachingClasses)(classes.data(), numClasses, groupReach.data(), activeGroups.data(),
                                                                         activeClasses.data(), solvedGroups, solvedPoints);
    // Most points taking part (a fortissimo strike; or a test's reference, solveEveryPoint):
    // every group is solved in place, without gathering, which is the all-touching case's work.
    const bool whole = solveEveryPoint || 4 * solvedPoints > 3 * n;
    const int m = whole ? n : solvedPoints;
    lastSolvedPoints = m;
    const int* group = activeGroups.data();
    const int* point = activePoints.data();
    const SizeClass* layout = whole ? classes.data() : activeClasses.data();
    const int layoutClasses = whole ? numClasses : numActive;
    const int* wireNode = pointWireNode.data();
    const int* ofPoint = whole ? pointGroup.data() : solvePointGroup.data(); // each point's group in the solve's group arrays
    const double *before = xiPrev.data(), *now = xiNow.data(), *W0 = groupW0.data(), *cc = groupCc.data();
    double *psiSolved = psiQ.data(), *xiSolved = xiNext.data(), *W = groupW.data();
    if (! whole)
    {
        // the groups taking part and their points, member-major by class, gathered
        SNARESIM_ON_VECTOR_TARGET(listPoints)
        (classes.data(), activeClasses.data(), numActive, activeGroups.data(), activePoints.data(), solvePointGroup.data());
        SNARESIM_ON_VECTOR_TARGET(gatherSolvedPoints)
        (m, point, pointWireNode.data(), xiPrev.data(), xiNow.data(), psiQ.data(), solveWireNode.data(), solveXiPrev.data(),
         solveXiNow.data(), solvePsi.data());
        SNARESIM_ON_VECTOR_TARGET(gatherPoints<double>)(solvedGroups, group, groupW0.data(), solveGroupW0.data());
        SNARESIM_ON_VECTOR_TARGET(gatherPoints<double>)(solvedGroups, group, groupCc.data(), solveGroupCc.data());
        wireNode = solveWireNode.data();
        before = solveXiPrev.data();
        now = solveXiNow.data();
        W0 = solveGroupW0.data();
        cc = solveGroupCc.data();
        psiSolved = solvePsi.data();
        xiSolved = solveXiNext.data();
        W = solveGroupW.data();
    }
    coefficients(m, wireNode, before, now, psiSolved, ofPoint, W0, cc, gammaS, u);

    // Per group: S = sum alpha / (1 + sum beta) and W; then the node and the ends (eq. 32a).
    // Only the solved groups' nodes are written (the others keep their free value W0), keyed by
    // their group's index, so that the head's running sum of w^{n+1} (Membrane::setNextAt) is
    // the same to the last bit whichever groups were solved.
    SNARESIM_ON_VECTOR_TARGET(solveClasses)(layout, layoutClasses, alphaQ.data(), betaQ.data(), W0, cc, hs, solveGroupS.data(), W);
    carry.setNextAt(groupNode.data(), W, whole ? nullptr : group, whole ? numGroups : solvedGroups);
    if (! whole)
        SNARESIM_ON_VECTOR_TARGET(scatterPoints)(solvedGroups, group, solveGroupW.data(), groupW.data()); // the ends' groups below
    for (int g : endGroups)
        for (int e = groupEndBegin[(size_t) g]; e < groupEndBegin[(size_t) g + 1]; ++e)
            u[endWireNode[(size_t) groupEnds[(size_t) e]]] = groupW[(size_t) g];

    // Per point: the force, the wire, the gap and psi at n+1/2, put back in place.
    const auto finish =
        dampingPerStep > 0.0 ? SNARESIM_ON_VECTOR_TARGET(finishPoints<true>) : SNARESIM_ON_VECTOR_TARGET(finishPoints<false>);
    finish(m, alphaQ.data(), betaQ.data(), gq.data(), ofPoint, solveGroupS.data(), W, gammaS, before, now, dampQ.data(), uFree.data(),
           xiSolved, psiSolved, solveDropped.data());
    SNARESIM_ON_VECTOR_TARGET(scatterPoints)(m, wireNode, uFree.data(), u);
    if (! whole)
        SNARESIM_ON_VECTOR_TARGET(scatterSolvedPoints)(m, point, solveXiNext.data(), solvePsi.data(), xiNext.data(), psiQ.data());

    // The points left out are apart (xi* <= 0) and hold no psi: the deepest gap, the points
    // touching, psi's resets and the damping's work are among those solved.
    SnareSolveResult result;
    const double sumRemoved =
        SNARESIM_ON_VECTOR_TARGET(summarise)(m, xiSolved, solveDropped.data(), result.maxPenetration_m, result.contacts);
    lastCorrection = 0.5 * hs * sumRemoved;
    return result;
}

SnareSolveResult SnareContact::stepNewton(Membrane& carry, SnareWires& wires)
{
    SnareSolveResult result;
    lastCorrection = 0.0; // the damping's work, summed over the groups solved
    const double* u = wires.uNext.data();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int g = 0; g < (int) groupNode.size(); ++g)
    {
        const int* p0 = groupMembers.data() + groupMemberBegin[(size_t) g];
        const int* p1 = groupMembers.data() + groupMemberBegin[(size_t) g + 1];
        if (groupEndBegin[(size_t) g] == groupEndBegin[(size_t) g + 1])
        {
            // Fast path for a node without wire ends where no point can touch: the free
            // update stands and the gaps follow from it.
            const double W = carry.nextAt(groupNode[(size_t) g]);
            bool touching = false;
            for (const int* m = p0; m < p1 && ! touching; ++m)
                touching = xiPrev[(size_t) *m] > 0.0 || u[pointWireNode[(size_t) *m]] - W > 0.0;
            if (! touching)
            {
                for (const int* m = p0; m < p1; ++m)
                {
                    const int p = *m;
                    xiNext[(size_t) p] = u[pointWireNode[(size_t) p]] - W;
                    rLast[(size_t) p] = nan;
                }
                continue;
            }
        }
        solveGroup(g, carry, wires, result);
    }
    result.maxPenetration_m = maxPenetration();
    return result;
}

void SnareContact::solveGroup(int g, Membrane& carry, SnareWires& wires, SnareSolveResult& result)
{
    const int node = groupNode[(size_t) g];
    const double gammaS = wires.interiorGain(); // u^{n+1} per unit force density (N/m)
    double* u = wires.uNext.data();
    double W0 = 0.0, cc = 0.0;
    const double h = carry.grid().spacing();
    eliminateEnds(g, carry, wires, carry.forceGainAt(node) / (h * h), W0, cc);
    const double coupling = cc * hs; // node response to a contact force density at any of its points

    // Collisions (eq. 50) restricted to this node: r_m + gammaS F_m + coupling sum F + b_m = 0,
    // r = xi^{n+1} - xi^{n-1}, a = xi^{n-1}, b = a - (u* - W0), F = psi(r; a) + D r with the
    // contact's damping D = lambda Phi'(xi^n) / (2k) (Hunt and Crossley; 0 while apart at n).
    // Forces are >= 0 and only lift the node, so points apart at n-1 and apart without forces
    // stay apart.
    const int* p0 = groupMembers.data() + groupMemberBegin[(size_t) g];
    const int* p1 = groupMembers.data() + groupMemberBegin[(size_t) g + 1];
    int m = 0;
    for (const int* q = p0; q < p1; ++q)
    {
        const int p = *q;
        const double aPrev = xiPrev[(size_t) p];
        const double xiFree = u[pointWireNode[(size_t) p]] - W0;
        if (aPrev > 0.0 || xiFree > 0.0)
        {
            active[(size_t) m] = p;
            a[(size_t) m] = aPrev;
            phiA[(size_t) m] = law.phi(aPrev);
            b[(size_t) m] = aPrev - xiFree;
            damp[(size_t) m] = dampingPerStep * law.dphi(xiNow[(size_t) p]);
            ++m;
        }
    }

    double H = 0.0; // total contact force on the node (N)
    if (m == 1)
    {
        // (1 + G D) r + G psi + b = 0 with G = gammaS + coupling: eq. (50)'s form, scaled
        int its = 0;
        const double scale = 1.0 / (1.0 + (gammaS + coupling) * damp[0]);
        r[0] = solveCollision(law, (gammaS + coupling) * scale, a[0], b[0] * scale, its, rLast[(size_t) active[0]]);
        result.iterations = std::max(result.iterations, its);
    }
    else if (m > 1)
    {
        int its = 0;
        if (! solveGroupNewton(m, gammaS, coupling, its))
        {
            result.fallback = true;
            int more = 0;
            if (! solveGroupReduced(m, gammaS, coupling, more))
                solveFallback(m, gammaS, coupling);
        }
        result.iterations = std::max(result.iterations, its);
    }
    for (const int* q = p0; q < p1; ++q)
        rLast[(size_t) *q] = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < m; ++i)
    {
        psi[(size_t) i] = law.psi(r[(size_t) i], a[(size_t) i]) + damp[(size_t) i] * r[(size_t) i]; // eq. (30), and the damping
        lastCorrection += 0.5 * hs * damp[(size_t) i] * r[(size_t) i] * r[(size_t) i];
        H += hs * psi[(size_t) i];
        rLast[(size_t) active[(size_t) i]] = r[(size_t) i];
    }

    // Update the node, the touching points and the ends.
    const double W = W0 + cc * H;
    carry.setNextAt(node, W);
    for (int i = 0; i < m; ++i)
        u[pointWireNode[(size_t) active[(size_t) i]]] -= gammaS * psi[(size_t) i];
    for (int e = groupEndBegin[(size_t) g]; e < groupEndBegin[(size_t) g + 1]; ++e)
        u[endWireNode[(size_t) groupEnds[(size_t) e]]] = W; // eq. (32a)
    for (const int* q = p0; q < p1; ++q)
    {
        const int p = *q;
        xiNext[(size_t) p] = u[pointWireNode[(size_t) p]] - W;
        if (xiNext[(size_t) p] > 0.0)
            ++result.contacts;
    }
}

bool SnareContact::solveGroupNewton(int m, double gammaS, double coupling, int& iterations)
{
    // Newton on eq. (50) for the node: J = diag(1 + gammaS F') + coupling 1 F'^T (F = psi + D r),
    // solved by Sherman-Morrison in O(m), from the last step's roots (or r = -b, no force).
    for (int i = 0; i < m; ++i)
    {
        const double last = rLast[(size_t) active[(size_t) i]];
        r[(size_t) i] = std::isfinite(last) ? last : -b[(size_t) i];
    }
    double lastStep = std::numeric_limits<double>::infinity();
    for (int it = 0; it < maxNewtonIterations; ++it)
    {
        ++iterations;
        double sumPsi = 0.0;
        for (int i = 0; i < m; ++i)
        {
            const auto sec = law.secant(r[(size_t) i], a[(size_t) i], phiA[(size_t) i]);
            psi[(size_t) i] = sec.psi + damp[(size_t) i] * r[(size_t) i];
            dpsi[(size_t) i] = sec.dpsi + damp[(size_t) i];
            sumPsi += psi[(size_t) i];
        }
        double vy = 0.0, vz = 0.0;
        for (int i = 0; i < m; ++i)
        {
            const double d = 1.0 + gammaS * dpsi[(size_t) i];
            const double F = r[(size_t) i] + gammaS * psi[(size_t) i] + coupling * sumPsi + b[(size_t) i];
            vy += dpsi[(size_t) i] * F / d;
            vz += dpsi[(size_t) i] * coupling / d;
        }
        const double ratio = vy / (1.0 + vz);
        double stepSize = 0.0, scale = 0.0;
        for (int i = 0; i < m; ++i)
        {
            const double d = 1.0 + gammaS * dpsi[(size_t) i];
            const double F = r[(size_t) i] + gammaS * psi[(size_t) i] + coupling * sumPsi + b[(size_t) i];
            const double delta = (F - coupling * ratio) / d;
            r[(size_t) i] -= delta;
            stepSize = std::max(stepSize, std::abs(delta));
            scale = std::max(scale, std::abs(r[(size_t) i]) + std::abs(a[(size_t) i]) + std::abs(b[(size_t) i]));
        }
        if (! std::isfinite(stepSize))
            return false;
        // Converged, or stalled at round-off after quadratic convergence: the secants of
        // eq. (30) cancel where r << a, which leaves a floor of up to about 1e-10 of the scale.
        if (stepSize <= tolerance * scale || (stepSize >= lastStep && stepSize <= 1.0e-9 * scale))
            return true;
        lastStep = stepSize;
    }
    return false;
}

double SnareContact::solvePoint(int i, double gamma, double bi, int& iterations) const
{
    // r + gamma (psi + D r) + b = 0 is eq. (50)'s scalar form with gamma and b over 1 + gamma D
    const double scale = 1.0 / (1.0 + gamma * damp[(size_t) i]);
    return solveCollision(law, gamma * scale, a[(size_t) i], bi * scale, iterations);
}

bool SnareContact::solveGroupReduced(int m, double gammaS, double coupling, int& iterations)
{
    // Eq. (50) on one node: the points see each other only through S = sum F, so for a given
    // S each point solves its own scalar equation (bracketed, solveCollision) and
    // the group reduces to the monotone scalar equation g(S) = S - sum F_m(S) = 0, solved by
    // Newton with g'(S) = 1 + sum coupling F'_m / (1 + gammaS F'_m) >= 1, kept in its bracket.
    auto evaluate = [&](double S, double& derivative) {
        double sum = 0.0;
        derivative = 1.0;
        int inner = 0;
        for (int i = 0; i < m; ++i)
        {
            r[(size_t) i] = solvePoint(i, gammaS, b[(size_t) i] + coupling * S, inner);
            const double slope = law.dpsi(r[(size_t) i], a[(size_t) i]) + damp[(size_t) i];
            sum += law.psi(r[(size_t) i], a[(size_t) i]) + damp[(size_t) i] * r[(size_t) i];
            derivative += coupling * slope / (1.0 + gammaS * slope);
        }
        iterations += inner;
        return S - sum;
    };
    double derivative = 1.0;
    double lo = 0.0;
    double hi = -evaluate(0.0, derivative); // g(0) = -sum psi(0) <= 0; the root lies in [0, sum psi(0)]
    if (hi <= 0.0)
        return true;
    double S = 0.0, g = -hi;
    for (int it = 0; it < maxNewtonIterations; ++it)
    {
        ++iterations;
        double next = S - g / derivative;
        if (! (next >= lo && next <= hi))
            next = 0.5 * (lo + hi);
        const double change = std::abs(next - S);
        S = next;
        g = evaluate(S, derivative);
        if (g > 0.0)
            hi = S;
        else
            lo = S;
        // g carries the inner solves' round-off (about 1e-12 of S): stop at that floor.
        if (std::abs(g) <= groupTolerance * S || change <= tolerance * S || hi - lo <= groupTolerance * hi)
            return true;
    }
    return false;
}

double SnareContact::solveFallback(int m, double gammaS, double coupling)
{
    // Bracketed fallback: for a given total S = sum F every point solves its own scalar
    // equation; sum F(S) is non-increasing in S, so S = sum F(S) has one root, found by
    // bisection. Always finite; the iteration count is bounded.
    auto total = [&](double S) {
        double sum = 0.0;
        for (int i = 0; i < m; ++i)
        {
            int its = 0;
            r[(size_t) i] = solvePoint(i, gammaS, b[(size_t) i] + coupling * S, its);
            sum += law.psi(r[(size_t) i], a[(size_t) i]) + damp[(size_t) i] * r[(size_t) i];
        }
        return sum;
    };
    double lo = 0.0, hi = total(0.0);
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it)
    {
        const double mid = 0.5 * (lo + hi);
        if (total(mid) > mid)
            lo = mid;
        else
            hi = mid;
    }
    return total(0.5 * (lo + hi));
}

double SnareContact::energy() const
{
    if (method == CollisionScheme::quadratised)
        return quadratisedEnergy();
    double e = 0.0;
    for (size_t i = 0; i < xiNext.size(); ++i)
        e += law.phi(xiNext[i]) + law.phi(xiNow[i]);
    return 0.5 * hs * e;
}

double SnareContact::energyBeforeStep() const
{
    if (method == CollisionScheme::quadratised)
        return quadratisedEnergy(); // psi is stored at the half step: the same value before and after
    double e = 0.0;
    for (size_t i = 0; i < xiNow.size(); ++i)
        e += law.phi(xiNow[i]) + law.phi(xiPrev[i]);
    return 0.5 * hs * e;
}

double SnareContact::maxPenetration() const
{
    double worst = 0.0;
    for (double x : xiNext)
        worst = std::max(worst, x);
    return worst;
}

void SnareContact::advance()
{
    std::swap(xiPrev, xiNow);
    std::swap(xiNow, xiNext);
}

void SnareContact::layOnHead()
{
    auto lay = [&](int wireNode, int headNode) {
        snares.uNow[(size_t) wireNode] = snares.uNext[(size_t) wireNode] = head.nowAt(headNode);
        snares.uPrev[(size_t) wireNode] = head.prevAt(headNode);
    };
    for (size_t p = 0; p < pointWireNode.size(); ++p)
        lay(pointWireNode[p], pointHeadNode[p]);
    for (size_t e = 0; e < endWireNode.size(); ++e)
        lay(endWireNode[e], endHeadNode[e]);
    clear();
}

double SnareContact::quadratisedEnergy() const
{
    double e = 0.0;
    for (double v : psiQ)
        e += v * v;
    return 0.5 * hs * e;
}

double SnareContact::gapAt(int wire, int l) const { return xiNow[(size_t) pointOfWireNode[(size_t) (wire * wireInterior + l - 1)]]; }

void SnareContact::clear()
{
    std::fill(psiQ.begin(), psiQ.end(), 0.0);
    lastCorrection = 0.0;
    std::fill(rLast.begin(), rLast.end(), std::numeric_limits<double>::quiet_NaN());
    std::fill(xiNext.begin(), xiNext.end(), 0.0);
    std::fill(xiNow.begin(), xiNow.end(), 0.0);
    std::fill(xiPrev.begin(), xiPrev.end(), 0.0);
}

} // namespace snaresim
