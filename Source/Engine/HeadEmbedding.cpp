#include "HeadEmbedding.h"

#include "AirBox.h"
#include "Membrane.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace snaresim
{

HeadEmbedding::HeadEmbedding(AirBox& a, Membrane& m, double z, double cx, double cy) : air(a), head(m)
{
    const double R = head.grid().radius(), ha = air.spacing();
    const double halfX = 0.5 * air.nx() * ha, halfY = 0.5 * air.ny() * ha;
    if (std::abs(cx) + R + ha > halfX || std::abs(cy) + R + ha > halfY)
        throw std::invalid_argument("head embedding: a head of radius " + std::to_string(R) + " m does not fit in the air box");
    d = air.layerBelow(z);
    if (d < 1 || d + 2 >= air.nz())
        throw std::invalid_argument("head embedding: the head's plane z = " + std::to_string(z) + " m is not inside the air box");
    up = air.index(0, 0, d + 1) - air.index(0, 0, d);
    below = air.cutDisc(d, cx, cy, R);

    // J: bilinear interpolation of the head's interior nodes at each air node over the head
    const CircularGrid& g = head.grid();
    const double hm = g.spacing(), centre = 0.5 * (g.width() - 1);
    std::vector<int> column((size_t) g.numNodes(), -1);
    std::vector<Eigen::Triplet<double>> t;
    for (size_t row = 0; row < below.size(); ++row)
    {
        // the node's (x, y) from its index in the padded layout
        const long i = below[row] - air.index(0, 0, d);
        const int ix = (int) (i % (air.nx() + 2)), iy = (int) (i / (air.nx() + 2));
        const double fx = (air.coordinate(0, ix) - cx) / hm + centre, fy = (air.coordinate(1, iy) - cy) / hm + centre;
        const int jx = (int) std::floor(fx), jy = (int) std::floor(fy);
        const double ax = fx - jx, ay = fy - jy;
        const int nodes[4] = { g.index(jx, jy), g.index(jx + 1, jy), g.index(jx, jy + 1), g.index(jx + 1, jy + 1) };
        const double w[4] = { (1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay };
        for (int q = 0; q < 4; ++q)
        {
            if (w[q] == 0.0 || g.mask()[(size_t) nodes[q]] == 0.0) // the rim does not move
                continue;
            int& col = column[(size_t) nodes[q]];
            if (col < 0)
            {
                col = (int) support.size();
                support.push_back(nodes[q]);
            }
            t.emplace_back((int) row, col, w[q]);
        }
    }
    J.resize((Eigen::Index) below.size(), (Eigen::Index) support.size());
    J.setFromTriplets(t.begin(), t.end());
    Jt = J.transpose();
    const auto na = (Eigen::Index) below.size(), nm = (Eigen::Index) support.size();
    for (auto* v : { &wFree, &wPrev, &r, &pull, &base, &w, &jts, &seen })
        v->setZero(nm);
    for (auto* v : { &y, &dv, &s, &sNew, &jr })
        v->setZero(na);
    refresh();
}

double HeadEmbedding::planeZ() const
{
    return air.planeAbove(d);
}

void HeadEmbedding::refresh()
{
    const double k = air.timeStep(), c = air.soundSpeed(), ha = air.spacing(), hm = head.grid().spacing();
    alpha = c * c * k / ha;                          // Psi_u - Psi_d gains alpha J (w+ - w-)
    beta = air.density() * head.forceGain() / (2.0 * k); // w+ loses beta I (D+ - D-)
    ratio = ha * ha / (hm * hm);                     // I = ratio J^T
    gamma = alpha * beta * ratio;
    Eigen::SparseMatrix<double> B = gamma * (J * Jt);
    Eigen::SparseMatrix<double> id((Eigen::Index) below.size(), (Eigen::Index) below.size());
    id.setIdentity();
    B += id;
    solver.compute(B);
    if (solver.info() != Eigen::Success)
        throw std::runtime_error("head embedding: the coupling matrix could not be factored");
}

void HeadEmbedding::step()
{
    solveFree();
    finish();
}

void HeadEmbedding::solveFree()
{
    const size_t na = below.size(), nm = support.size();
    const double* next = air.next();
    const double* prev = air.prev();
    const auto& wm = head.previousDisplacement();
    for (size_t j = 0; j < nm; ++j)
    {
        wFree[(Eigen::Index) j] = head.nextAt(support[j]);
        wPrev[(Eigen::Index) j] = wm[(size_t) support[j]];
    }
    // air side of the right-hand side: ratio beta (-(D* - D^{n-1}) + alpha J w^{n-1}),
    // D* = Psi_u - Psi_d from the air's own update
    y.noalias() = J * wPrev;
    for (size_t a = 0; a < na; ++a)
    {
        const long i = below[a];
        const double dStar = next[i + up] - next[i], dPrev = prev[i + up] - prev[i];
        y[(Eigen::Index) a] = ratio * beta * (alpha * y[(Eigen::Index) a] - (dStar - dPrev));
    }
    r = wFree;
    r.noalias() += Jt * y;
    // (1 + gamma J^T J)^{-1} = 1 - gamma J^T (1 + gamma J J^T)^{-1} J  (Woodbury)
    jr.noalias() = J * r;
    s = solver.solve(jr);
    pull.noalias() = Jt * s;
    pull *= gamma;
    w.noalias() = r - pull;
    base = w;
    seen = pull;
    fresh = true;
    wScale = 0.0;
    for (size_t j = 0; j < nm; ++j)
    {
        head.setNextAt(support[j], w[(Eigen::Index) j]);
        wScale = std::max(wScale, std::abs(w[(Eigen::Index) j]));
    }
}

double HeadEmbedding::correct()
{
    // delta: what the coupling added over J's support since solveFree() / retry()
    const size_t nm = support.size();
    bool moved = false;
    for (size_t j = 0; j < nm; ++j)
    {
        const double wj = head.nextAt(support[j]);
        wFree[(Eigen::Index) j] = wj - base[(Eigen::Index) j]; // delta
        moved = moved || wj != base[(Eigen::Index) j];
    }
    if (! moved && fresh) // no force on the head: solveFree's w stands
    {
        w = base;
        return 0.0;
    }
    wFree += r; // r + delta
    jr.noalias() = J * wFree;
    sNew = solver.solve(jr);
    jts.noalias() = Jt * sNew;
    double change = 0.0;
    for (size_t j = 0; j < nm; ++j)
    {
        const double p = gamma * jts[(Eigen::Index) j];
        change = std::max(change, std::abs(p - seen[(Eigen::Index) j])); // what the trial saw against the exact pull
        pull[(Eigen::Index) j] = p;
        const double wj = wFree[(Eigen::Index) j] - p;
        w[(Eigen::Index) j] = wj;
        wScale = std::max(wScale, std::abs(wj));
        head.setNextAt(support[j], wj);
    }
    s.swap(sNew);
    return change;
}

void HeadEmbedding::retry(double omega)
{
    fresh = false;
    seen += omega * (pull - seen);
    base.noalias() = r - seen;
    for (size_t j = 0; j < support.size(); ++j)
        head.setNextAt(support[j], base[(Eigen::Index) j]);
}

void HeadEmbedding::finish()
{
    // eq. (8): the head's velocity is the air's on both sides
    const size_t na = below.size();
    double* next = air.next();
    for (size_t j = 0; j < support.size(); ++j)
        w[(Eigen::Index) j] = head.nextAt(support[j]);
    wFree = w - wPrev;
    dv.noalias() = J * wFree;
    for (size_t a = 0; a < na; ++a)
    {
        const double t = 0.5 * alpha * dv[(Eigen::Index) a];
        next[below[a] + up] += t;
        next[below[a]] -= t;
    }
}

} // namespace snaresim
