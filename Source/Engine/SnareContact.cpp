#include "SnareContact.h"

#include "CollisionSolve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace snaresim
{

SnareContact::SnareContact(const SnareSpec& spec, const SnareWires& wires, const Membrane& carry) : hs(wires.spacing())
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
    size_t largest = 1;
    for (const auto& [node, members] : byNode)
    {
        groupNode.push_back(node);
        groupPointBegin.push_back((int) groupPoints.size());
        groupEndBegin.push_back((int) groupEnds.size());
        groupPoints.insert(groupPoints.end(), members.first.begin(), members.first.end());
        groupEnds.insert(groupEnds.end(), members.second.begin(), members.second.end());
        largest = std::max(largest, members.first.size());
    }
    groupPointBegin.push_back((int) groupPoints.size());
    groupEndBegin.push_back((int) groupEnds.size());
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
}

SnareSolveResult SnareContact::step(Membrane& carry, SnareWires& wires)
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
            {
                const int id = groupPoints[(size_t) p];
                touching = xiPrev[(size_t) id] > 0.0 || u[pointWireNode[(size_t) id]] - W > 0.0;
            }
            if (! touching)
            {
                for (int p = p0; p < p1; ++p)
                {
                    const int id = groupPoints[(size_t) p];
                    xiNext[(size_t) id] = u[pointWireNode[(size_t) id]] - W;
                    rLast[(size_t) id] = nan;
                }
                continue;
            }
        }
        solveGroup(g, carry, wires, result);
    }
    return result;
}

void SnareContact::solveGroup(int g, Membrane& carry, SnareWires& wires, SnareSolveResult& result)
{
    const int node = groupNode[(size_t) g];
    const double h2 = carry.grid().spacing() * carry.grid().spacing();
    const double c = carry.forceGain() / h2;          // w_c[j]^{n+1} per unit force (N) at the node
    const double gammaS = wires.interiorGain();       // u^{n+1} per unit force density (N/m)
    const double gammaE = wires.endGain();            // end node u^{n+1} per unit force (N)
    double* u = wires.uNext.data();

    // Attached ends (eq. 32a, 48-49): u_e^{n+1} = W. With W = W* + c (H - sum lambda) and
    // u_e^{n+1} = u_e* + gammaE lambda_e, the ends act on the node as W = W0 + c' H.
    const double Wfree = carry.nextAt(node);
    double G = 0.0, D = 0.0;
    for (int e = groupEndBegin[(size_t) g]; e < groupEndBegin[(size_t) g + 1]; ++e)
    {
        G += 1.0 / gammaE;
        D += (Wfree - u[endWireNode[(size_t) groupEnds[(size_t) e]]]) / gammaE;
    }
    const double W0 = Wfree - c * D / (1.0 + c * G);
    const double cc = c / (1.0 + c * G);
    const double coupling = cc * hs; // node response to a contact force density at any of its points

    // Collisions (eq. 50) restricted to this node: r_m + gammaS psi_m + coupling sum psi + b_m = 0,
    // r = xi^{n+1} - xi^{n-1}, a = xi^{n-1}, b = a - (u* - W0). Forces are >= 0 and only lift
    // the node, so points apart at n-1 and apart without forces stay apart.
    const int p0 = groupPointBegin[(size_t) g], p1 = groupPointBegin[(size_t) g + 1];
    int m = 0;
    for (int p = p0; p < p1; ++p)
    {
        const int id = groupPoints[(size_t) p];
        const double aPrev = xiPrev[(size_t) id];
        const double xiFree = u[pointWireNode[(size_t) id]] - W0;
        if (aPrev > 0.0 || xiFree > 0.0)
        {
            active[(size_t) m] = id;
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
        rLast[(size_t) groupPoints[(size_t) p]] = std::numeric_limits<double>::quiet_NaN();
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
        const int id = groupPoints[(size_t) p];
        xiNext[(size_t) id] = u[pointWireNode[(size_t) id]] - W;
        if (xiNext[(size_t) id] > 0.0)
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

double SnareContact::potentialEnergy() const
{
    double e = 0.0;
    for (size_t i = 0; i < xiNext.size(); ++i)
        e += law.phi(xiNext[i]) + law.phi(xiNow[i]);
    return 0.5 * hs * e;
}

double SnareContact::potentialEnergyBeforeStep() const
{
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

void SnareContact::layOnHead(const Membrane& carry, SnareWires& wires)
{
    const auto& now = carry.displacement();
    const auto& prev = carry.previousDisplacement();
    auto lay = [&](int wireNode, int headNode) {
        wires.uNow[(size_t) wireNode] = wires.uNext[(size_t) wireNode] = now[(size_t) headNode];
        wires.uPrev[(size_t) wireNode] = prev[(size_t) headNode];
    };
    for (size_t p = 0; p < pointWireNode.size(); ++p)
        lay(pointWireNode[p], pointHeadNode[p]);
    for (size_t e = 0; e < endWireNode.size(); ++e)
        lay(endWireNode[e], endHeadNode[e]);
    clear();
}

void SnareContact::clear()
{
    std::fill(rLast.begin(), rLast.end(), std::numeric_limits<double>::quiet_NaN());
    std::fill(xiNext.begin(), xiNext.end(), 0.0);
    std::fill(xiNow.begin(), xiNow.end(), 0.0);
    std::fill(xiPrev.begin(), xiPrev.end(), 0.0);
}

} // namespace snaresim
