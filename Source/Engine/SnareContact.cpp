#include "SnareContact.h"

#include "CollisionSolve.h"
#include "VectorClones.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace snaresim
{

SnareContact::SnareContact(const SnareSpec& spec, SnareWires& wires, Membrane& carry)
    : method(spec.scheme), hs(wires.spacing()), snares(wires), head(carry)
{
    setLaw(spec.stiffness, spec.exponent);
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
    // Number the points group by group, so that a group's points are contiguous (the ids above
    // ran over the wires' interior nodes in order: pointOfWireNode maps them).
    size_t largest = 1;
    std::vector<int> wireNodeByGroup, headNodeByGroup;
    pointOfWireNode.assign(pointWireNode.size(), 0);
    for (const auto& [node, members] : byNode)
    {
        const int g = (int) groupNode.size();
        groupNode.push_back(node);
        groupPointBegin.push_back((int) wireNodeByGroup.size());
        groupEndBegin.push_back((int) groupEnds.size());
        for (const int old : members.first)
        {
            pointOfWireNode[(size_t) old] = (int) wireNodeByGroup.size();
            wireNodeByGroup.push_back(pointWireNode[(size_t) old]);
            headNodeByGroup.push_back(pointHeadNode[(size_t) old]);
        }
        groupEnds.insert(groupEnds.end(), members.second.begin(), members.second.end());
        (members.second.empty() ? openGroups : endGroups).push_back(g);
        largest = std::max(largest, members.first.size());
    }
    groupPointBegin.push_back((int) wireNodeByGroup.size());
    groupEndBegin.push_back((int) groupEnds.size());
    pointWireNode = std::move(wireNodeByGroup);
    pointHeadNode = std::move(headNodeByGroup);
    wireInterior = M - 1;
    mayTouch.assign(pointWireNode.size() + 8, 0);
    for (auto* v : { &solveGroups, &slotEnd })
        v->assign(groupNode.size(), 0);
    for (auto* v : { &slotW0, &slotCc, &slotS, &slotW })
        v->assign(groupNode.size(), 0.0);
    for (auto* v : { &flatPoint, &flatSlot })
        v->assign(pointWireNode.size(), 0);
    for (auto* v : { &gq, &alphaQ, &betaQ })
        v->assign(pointWireNode.size(), 0.0);
    psiQ.assign(pointWireNode.size(), 0.0);
    trialPsi = psiQ;
    rLast.assign(pointWireNode.size(), std::numeric_limits<double>::quiet_NaN());
    xiNext.assign(pointWireNode.size(), 0.0);
    xiNow = xiNext;
    xiPrev = xiNext;
    for (auto* v : { &a, &b, &r, &psi, &dpsi, &phiA })
        v->assign(largest, 0.0);
    active.assign(largest, 0);
}

void SnareContact::setLaw(double stiffness, double exponent)
{
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
// Free gaps xi* = u - w_c at n+1 for every contact point (two gathers per point; vectorises
// on AVX2), and per point whether it may touch: xi* > 0, or it touched at n or n-1.
SNARESIM_VECTOR_CLONES void computeGaps(double* __restrict xi, unsigned char* __restrict mayTouch, const double* __restrict u,
                                        const double* __restrict w, const double* __restrict xiNow,
                                        const double* __restrict xiPrev,
                                        const int* __restrict wireNode, const int* __restrict headNode, int n)
{
    for (int p = 0; p < n; ++p)
    {
        const double x = u[wireNode[p]] - w[headNode[p]];
        xi[p] = x;
        mayTouch[p] = (unsigned char) ((x > 0.0) | (xiNow[p] > 0.0) | (xiPrev[p] > 0.0));
    }
}

// The per-point coefficients of the quadratised solve for the Hertz exponent (beta = 1.5, so
// psi = psiScale xi^(5/4) and psi' = gScale xi^(1/4)), branch-free so that it vectorises:
// g is the tangent at the midpoint while xi^{n-1} and xi* both touch, else the secant.
SNARESIM_VECTOR_CLONES void hertzCoefficients(int count, const int* __restrict flatPoint, const int* __restrict flatSlot,
                                              const int* __restrict wireNode, const double* __restrict xiPrev,
                                              const double* __restrict u, const double* __restrict psi,
                                              const double* __restrict W0, const double* __restrict cc, double hs,
                                              double gScale, double psiScale, double gammaS, double* __restrict gq,
                                              double* __restrict alpha, double* __restrict beta)
{
    for (int k = 0; k < count; ++k)
    {
        const int p = flatPoint[k], j = flatSlot[k];
        const double a = xiPrev[p];
        const double b = u[wireNode[p]] - W0[j];
        const double ap = a > 0.0 ? a : 0.0, bp = b > 0.0 ? b : 0.0;
        const double span = b - a;
        const double secant = psiScale * (bp * std::sqrt(std::sqrt(bp)) - ap * std::sqrt(std::sqrt(ap))) / (span != 0.0 ? span : 1.0);
        const double tangent = gScale * std::sqrt(std::sqrt(0.5 * (ap + bp)));
        const double g = (a > 0.0) & (b > 0.0) ? tangent : secant;
        const double B = 0.25 * g * g;
        const double d = 1.0 / (1.0 + gammaS * B);
        gq[k] = g;
        alpha[k] = (g * psi[p] + B * (b - a)) * d;
        beta[k] = cc[j] * hs * B * d;
    }
}
} // namespace

SnareSolveResult SnareContact::stepQuadratised(Membrane& carry, SnareWires& wires)
{
    // Free gaps xi* = u* - w_c* at n+1 for every point (no contact or end forces yet): the
    // prediction g is built from, and xi^{n+1} itself for the points of groups left alone.
    const int n = (int) pointWireNode.size();
    computeGaps(xiNext.data(), mayTouch.data(), wires.uNext.data(), carry.nextDisplacement().data(), xiNow.data(), xiPrev.data(),
                pointWireNode.data(), pointHeadNode.data(), n);

    // The groups to solve (those holding wire ends first, then those with a point that may
    // touch) and their points in one flat list, so that the per-point work of all groups runs
    // as one loop without dependencies between points. A group's points are consecutive, so
    // its flags are read at once (eight bytes; mayTouch is padded).
    int numSolve = 0, numFlat = 0;
    auto enlist = [&](int g) {
        solveGroups[(size_t) numSolve] = g;
        for (int p = groupPointBegin[(size_t) g]; p < groupPointBegin[(size_t) g + 1]; ++p)
        {
            flatPoint[(size_t) numFlat] = p;
            flatSlot[(size_t) numFlat++] = numSolve;
        }
        slotEnd[(size_t) numSolve++] = numFlat;
    };
    for (int g : endGroups)
        enlist(g);
    const unsigned char* flags = mayTouch.data();
    for (int g : openGroups)
    {
        const int p0 = groupPointBegin[(size_t) g], size = groupPointBegin[(size_t) g + 1] - p0;
        bool any = false;
        if (size <= 8)
        {
            std::uint64_t word = 0;
            std::memcpy(&word, flags + p0, sizeof word);
            any = (word & (~std::uint64_t { 0 } >> (64 - 8 * size))) != 0;
        }
        else
            for (int p = p0; p < p0 + size; ++p)
                any = any || flags[p] != 0;
        if (any)
            enlist(g);
    }

    const double h = carry.grid().spacing();
    const double gammaS = wires.interiorGain();    // u^{n+1} per unit force density (N/m)
    double* u = wires.uNext.data();

    // Per group: the head node as the ends leave it, W = W0 + cc H (eq. 48-49).
    for (int j = 0; j < numSolve; ++j)
    {
        const int g = solveGroups[(size_t) j];
        const double c = carry.forceGainAt(groupNode[(size_t) g]) / (h * h); // w_c^{n+1} per unit force (N) at the node
        double W0 = carry.nextAt(groupNode[(size_t) g]), cc = c;
        if (groupEndBegin[(size_t) g + 1] > groupEndBegin[(size_t) g])
            eliminateEnds(g, carry, wires, c, W0, cc);
        slotW0[(size_t) j] = W0;
        slotCc[(size_t) j] = cc;
    }

    // Per point: g^n is the slope of psi(xi) = sqrt(2 Phi(xi)) from xi^{n-1} to the prediction
    // xi* = u* - W0 (no contact force), so psi follows sqrt(2 Phi) closely where the prediction
    // is good, and g = 0 (no force, psi stays zero) where both are apart.
    // f = A + B xi^{n+1} with B = g^2/4, A = g psi^{n-1/2} - B xi^{n-1}, and
    // xi^{n+1} = xi* - gammaS f - cc h_s S, S = sum f over the group. Eliminating xi^{n+1}:
    // f = alpha - beta S with alpha = (A + B xi*) / (1 + gammaS B), beta = cc h_s B / (1 + gammaS B).
    if (quarterPower)
        hertzCoefficients(numFlat, flatPoint.data(), flatSlot.data(), pointWireNode.data(), xiPrev.data(), u, psiQ.data(),
                          slotW0.data(), slotCc.data(), hs, gScale, psiScale, gammaS, gq.data(), alphaQ.data(), betaQ.data());
    else
        for (int k = 0; k < numFlat; ++k)
        {
            const int p = flatPoint[(size_t) k], j = flatSlot[(size_t) k];
            const double a = xiPrev[(size_t) p];
            const double predicted = u[pointWireNode[(size_t) p]] - slotW0[(size_t) j];
            const double gp = psiSlope(a, predicted);
            const double B = 0.25 * gp * gp;
            const double d = 1.0 / (1.0 + gammaS * B);
            gq[(size_t) k] = gp;
            alphaQ[(size_t) k] = (gp * psiQ[(size_t) p] + B * (predicted - a)) * d;
            betaQ[(size_t) k] = slotCc[(size_t) j] * hs * B * d;
        }

    // Per group: S = sum alpha / (1 + sum beta), the node and the ends (eq. 32a).
    for (int j = 0, k0 = 0; j < numSolve; k0 = slotEnd[(size_t) j++])
    {
        double sumAlpha = 0.0, sumBeta = 0.0;
        for (int k = k0; k < slotEnd[(size_t) j]; ++k)
        {
            sumAlpha += alphaQ[(size_t) k];
            sumBeta += betaQ[(size_t) k];
        }
        const double S = sumAlpha / (1.0 + sumBeta);
        const double W = slotW0[(size_t) j] + slotCc[(size_t) j] * hs * S;
        const int g = solveGroups[(size_t) j];
        carry.setNextAt(groupNode[(size_t) g], W);
        for (int e = groupEndBegin[(size_t) g]; e < groupEndBegin[(size_t) g + 1]; ++e)
            u[endWireNode[(size_t) groupEnds[(size_t) e]]] = W;
        slotS[(size_t) j] = S;
        slotW[(size_t) j] = W;
    }

    // Per point: the force, the wire, the gap and psi at n+1/2.
    double removed = 0.0, deepest = 0.0;
    int contacts = 0;
    for (int k = 0; k < numFlat; ++k)
    {
        const int p = flatPoint[(size_t) k], j = flatSlot[(size_t) k];
        const double f = alphaQ[(size_t) k] - betaQ[(size_t) k] * slotS[(size_t) j];
        double& ui = u[pointWireNode[(size_t) p]];
        ui -= gammaS * f;
        const double xiNew = ui - slotW[(size_t) j];
        xiNext[(size_t) p] = xiNew;
        const double next = psiQ[(size_t) p] + 0.5 * gq[(size_t) k] * (xiNew - xiPrev[(size_t) p]);
        // psi at n+1/2 stands for the potential of xi^n and xi^{n+1}: on the step a point leaves
        // the head it still holds what xi^n stored, and the next step gives that back as force.
        // Apart at n and n+1, what is left is psi's drift: reset, so the next contact starts
        // from zero.
        const bool touching = xiNew > 0.0;
        const bool keep = touching || xiNow[(size_t) p] > 0.0;
        removed += keep ? 0.0 : next * next;
        psiQ[(size_t) p] = keep ? next : 0.0;
        contacts += touching ? 1 : 0;
        deepest = std::max(deepest, xiNew);
    }
    lastCorrection = 0.5 * hs * removed;

    // Points of groups left alone keep xi^{n+1} = xi* <= 0: only solved groups can touch.
    SnareSolveResult result;
    result.contacts = contacts;
    result.maxPenetration_m = deepest;
    return result;
}

SnareSolveResult SnareContact::stepNewton(Membrane& carry, SnareWires& wires)
{
    SnareSolveResult result;
    const double* u = wires.uNext.data();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int g = 0; g < (int) groupNode.size(); ++g)
    {
        const int p0 = groupPointBegin[(size_t) g], p1 = groupPointBegin[(size_t) g + 1];
        if (groupEndBegin[(size_t) g] == groupEndBegin[(size_t) g + 1])
        {
            // Fast path for a node without wire ends where no point can touch: the free
            // update stands and the gaps follow from it.
            const double W = carry.nextAt(groupNode[(size_t) g]);
            bool touching = false;
            for (int p = p0; p < p1 && ! touching; ++p)
                touching = xiPrev[(size_t) p] > 0.0 || u[pointWireNode[(size_t) p]] - W > 0.0;
            if (! touching)
            {
                for (int p = p0; p < p1; ++p)
                {
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
    const double gammaS = wires.interiorGain();       // u^{n+1} per unit force density (N/m)
    double* u = wires.uNext.data();
    double W0 = 0.0, cc = 0.0;
    const double h = carry.grid().spacing();
    eliminateEnds(g, carry, wires, carry.forceGainAt(node) / (h * h), W0, cc);
    const double coupling = cc * hs; // node response to a contact force density at any of its points

    // Collisions (eq. 50) restricted to this node: r_m + gammaS psi_m + coupling sum psi + b_m = 0,
    // r = xi^{n+1} - xi^{n-1}, a = xi^{n-1}, b = a - (u* - W0). Forces are >= 0 and only lift
    // the node, so points apart at n-1 and apart without forces stay apart.
    const int p0 = groupPointBegin[(size_t) g], p1 = groupPointBegin[(size_t) g + 1];
    int m = 0;
    for (int p = p0; p < p1; ++p)
    {
        const double aPrev = xiPrev[(size_t) p];
        const double xiFree = u[pointWireNode[(size_t) p]] - W0;
        if (aPrev > 0.0 || xiFree > 0.0)
        {
            active[(size_t) m] = p;
            a[(size_t) m] = aPrev;
            phiA[(size_t) m] = law.phi(aPrev);
            b[(size_t) m] = aPrev - xiFree;
            ++m;
        }
    }

    double H = 0.0; // total contact force on the node (N)
    if (m == 1)
    {
        int its = 0;
        r[0] = solveCollision(law, gammaS + coupling, a[0], b[0], its, rLast[(size_t) active[0]]);
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
    for (int p = p0; p < p1; ++p)
        rLast[(size_t) p] = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < m; ++i)
    {
        psi[(size_t) i] = law.psi(r[(size_t) i], a[(size_t) i]); // eq. (30)
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
    for (int p = p0; p < p1; ++p)
    {
        xiNext[(size_t) p] = u[pointWireNode[(size_t) p]] - W;
        if (xiNext[(size_t) p] > 0.0)
            ++result.contacts;
    }
}

bool SnareContact::solveGroupNewton(int m, double gammaS, double coupling, int& iterations)
{
    // Newton on eq. (50) for the node: J = diag(1 + gammaS psi') + coupling 1 psi'^T, solved by
    // Sherman-Morrison in O(m), from the last step's roots (or r = -b, no force).
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
            psi[(size_t) i] = sec.psi;
            dpsi[(size_t) i] = sec.dpsi;
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
        // Converged, or stalled at round-off after quadratic convergence.
        if (stepSize <= tolerance * scale || (stepSize >= lastStep && stepSize <= 1.0e-11 * scale))
            return true;
        lastStep = stepSize;
    }
    return false;
}

bool SnareContact::solveGroupReduced(int m, double gammaS, double coupling, int& iterations)
{
    // Eq. (50) on one node: the points see each other only through S = sum psi, so for a given
    // S each point solves its own scalar equation (bracketed, solveCollision) and
    // the group reduces to the monotone scalar equation g(S) = S - sum psi_m(S) = 0, solved by
    // Newton with g'(S) = 1 + sum coupling psi'_m / (1 + gammaS psi'_m) >= 1, kept in its bracket.
    auto evaluate = [&](double S, double& derivative) {
        double sum = 0.0;
        derivative = 1.0;
        int inner = 0;
        for (int i = 0; i < m; ++i)
        {
            r[(size_t) i] = solveCollision(law, gammaS, a[(size_t) i], b[(size_t) i] + coupling * S, inner);
            const double slope = law.dpsi(r[(size_t) i], a[(size_t) i]);
            sum += law.psi(r[(size_t) i], a[(size_t) i]);
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
    // Bracketed fallback: for a given total S = sum psi every point solves its own scalar
    // equation; sum psi(S) is non-increasing in S, so S = sum psi(S) has one root, found by
    // bisection. Always finite; the iteration count is bounded.
    auto total = [&](double S) {
        double sum = 0.0;
        for (int i = 0; i < m; ++i)
        {
            int its = 0;
            r[(size_t) i] = solveCollision(law, gammaS, a[(size_t) i], b[(size_t) i] + coupling * S, its);
            sum += law.psi(r[(size_t) i], a[(size_t) i]);
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
    const auto& now = head.displacement();
    const auto& prev = head.previousDisplacement();
    auto lay = [&](int wireNode, int headNode) {
        snares.uNow[(size_t) wireNode] = snares.uNext[(size_t) wireNode] = now[(size_t) headNode];
        snares.uPrev[(size_t) wireNode] = prev[(size_t) headNode];
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

double SnareContact::gapAt(int wire, int l) const
{
    return xiNow[(size_t) pointOfWireNode[(size_t) (wire * wireInterior + l - 1)]];
}

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
