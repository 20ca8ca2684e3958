#include "MalletContact.h"

#include "CollisionSolve.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace snaresim
{

namespace
{
// h^2 g_i^T R g_j for two patches, R the head's response node by node (Membrane::forceGainAt
// over forceGain; 1 in vacuum). Index lists are short; no allocation.
double overlap(const GridDistribution& p, const GridDistribution& q, double h2, const double* response)
{
    double s = 0.0;
    for (int i = 0; i < p.size; ++i)
        for (int j = 0; j < q.size; ++j)
            if (p.index[(size_t) i] == q.index[(size_t) j])
                s += p.g[(size_t) i] * q.g[(size_t) j] * (response ? response[p.index[(size_t) i]] : 1.0);
    return h2 * s;
}
} // namespace

MalletContact::MalletContact(Membrane& batterHead, std::span<Mallet> mallets) : batter(batterHead), malletSet(mallets) {}

ContactSolveResult MalletContact::step()
{
    ContactSolveResult result;
    const double h2 = batter.grid().spacing() * batter.grid().spacing();
    const double kk = batter.timeStep() * batter.timeStep();

    // Free predictions (z* = 2 z^n - z^{n-1} from Mallet::computeFree, eq. 43): eta* = h^2 g^T w* - z*.
    int m = 0;
    for (int i = 0; i < (int) malletSet.size(); ++i)
    {
        Mallet& ml = malletSet[(size_t) i];
        if (! ml.inPlay())
            continue;
        ml.etaNext = batter.sampleNext(ml.patch()) - ml.zNext;
        // Forces are >= 0 and Gamma >= 0 elementwise, so a mallet that is apart at n-1 and
        // stays apart without forces stays apart with them.
        if ((ml.etaPrev > 0.0 || ml.etaNext > 0.0) && m < maxMallets)
            members[m++] = i;
    }
    if (m == 0)
        return result;

    // eq. (45): Gamma_ij = k^2/(rho q) h^2 g_i^T R g_j + delta_ij k^2/M_i (R: the head's response, 1 in vacuum),
    // a = eta^{n-1}, b = eta^{n-1} - eta*  (eq. 44: r + Gamma psi(r) + b = 0).
    gamma.resize(m, m);
    a.resize(m);
    b.resize(m);
    r.resize(m);
    f.resize(m);
    for (int i = 0; i < m; ++i)
    {
        const Mallet& mi = malletSet[(size_t) members[i]];
        a(i) = mi.etaPrev;
        b(i) = mi.etaPrev - mi.etaNext;
        for (int j = i; j < m; ++j)
            gamma(i, j) = gamma(j, i) =
                batter.forceGain() * overlap(mi.patch(), malletSet[(size_t) members[j]].patch(), h2, batter.responseScale());
        gamma(i, i) += kk / mi.mass();
    }

    bool coupled = false;
    for (int i = 0; i < m && ! coupled; ++i)
        for (int j = i + 1; j < m; ++j)
            coupled = coupled || gamma(i, j) != 0.0;

    if (! coupled)
    {
        for (int i = 0; i < m; ++i)
        {
            const Mallet& mi = malletSet[(size_t) members[i]];
            r(i) = solveCollision(mi.potential(), gamma(i, i), a(i), b(i), result.iterations);
        }
    }
    else if (! solveJoint(malletSet, m, result.iterations))
    {
        result.fallback = true;
        solveGaussSeidel(malletSet, m, result.iterations);
    }

    // Forces from the converged r (eq. 27), applied to the head (eq. 26: -g f) and mallet (eq. 43).
    for (int i = 0; i < m; ++i)
    {
        Mallet& mi = malletSet[(size_t) members[i]];
        const double force = mi.potential().psi(r(i), a(i));
        f(i) = std::isfinite(force) ? force : 0.0;
        batter.applyForce(mi.patch(), -f(i));
        mi.zNext += kk * f(i) / mi.mass();
    }
    for (int i = 0; i < m; ++i)
    {
        Mallet& mi = malletSet[(size_t) members[i]];
        mi.etaNext = batter.sampleNext(mi.patch()) - mi.zNext;
    }
    return result;
}

bool MalletContact::solveJoint(std::span<Mallet> mallets, int m, int& iterations)
{
    // Newton on F(r) = r + Gamma psi(r) + b, J = I + Gamma diag(psi'(r)), from r = -b.
    Vec psi(m), dpsi(m), F(m), delta(m);
    Mat J(m, m);
    r = -b;
    for (int it = 0; it < maxNewtonIterations; ++it)
    {
        ++iterations;
        for (int i = 0; i < m; ++i)
        {
            const auto& law = mallets[(size_t) members[i]].potential();
            psi(i) = law.psi(r(i), a(i));
            dpsi(i) = law.dpsi(r(i), a(i));
        }
        F = r + gamma * psi + b;
        J = gamma * dpsi.asDiagonal();
        J.diagonal().array() += 1.0;
        delta = J.partialPivLu().solve(F);
        if (! delta.allFinite())
            return false;
        r -= delta;
        const double scale = r.cwiseAbs().maxCoeff() + a.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff();
        if (delta.cwiseAbs().maxCoeff() <= tolerance * scale)
            return true;
    }
    return false;
}

void MalletContact::solveGaussSeidel(std::span<Mallet> mallets, int m, int& iterations)
{
    // Nonlinear Gauss-Seidel: each mallet's scalar equation solved in its bracket with the
    // others' forces fixed. It is coordinate descent on a strictly convex function, so it
    // converges; the sweep cap bounds the work and every iterate is finite.
    r = -b;
    for (int sweep = 0; sweep < maxFallbackSweeps; ++sweep)
    {
        double change = 0.0, scale = 0.0;
        for (int i = 0; i < m; ++i)
        {
            double bi = b(i);
            for (int j = 0; j < m; ++j)
                if (j != i)
                    bi += gamma(i, j) * mallets[(size_t) members[j]].potential().psi(r(j), a(j));
            const double ri = solveCollision(mallets[(size_t) members[i]].potential(), gamma(i, i), a(i), bi, iterations);
            change = std::max(change, std::abs(ri - r(i)));
            scale = std::max(scale, std::abs(ri) + std::abs(a(i)) + std::abs(bi));
            r(i) = ri;
        }
        if (change <= tolerance * scale)
            return;
    }
}

double MalletContact::potentialEnergy(const Mallet& ml)
{
    return ml.inPlay() ? 0.5 * (ml.potential().phi(ml.etaNext) + ml.potential().phi(ml.etaNow)) : 0.0; // eq. (37)
}

double MalletContact::potentialEnergyBeforeStep(const Mallet& ml)
{
    return ml.inPlay() ? 0.5 * (ml.potential().phi(ml.etaNow) + ml.potential().phi(ml.etaPrev)) : 0.0;
}

double MalletContact::energy() const
{
    double e = 0.0;
    for (const auto& ml : malletSet)
        e += potentialEnergy(ml);
    return e;
}

} // namespace snaresim
