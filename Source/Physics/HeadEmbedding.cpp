#include "HeadEmbedding.h"

#include "AirBox.h"
#include "Membrane.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace snaresim
{

HeadEmbedding::HeadEmbedding(AirBox& a, Membrane& m, double z, double cx, double cy) : air(a), head(m)
{
    if (head.singlePrecision())
        throw std::invalid_argument("head embedding: the air box needs heads in double precision");
    const double R = head.grid().radius(), ha = air.spacing();
    const double halfX = 0.5 * air.nx() * ha, halfY = 0.5 * air.ny() * ha;
    if (std::abs(cx) + R + ha > halfX || std::abs(cy) + R + ha > halfY)
        throw std::invalid_argument("head embedding: a head of radius " + std::to_string(R) + " m does not fit in the air box");
    d = air.layerBelow(z);
    if (d < 1 || d + 2 >= air.nz())
        throw std::invalid_argument("head embedding: the head's plane z = " + std::to_string(z) + " m is not inside the air box");
    up = air.index(0, 0, d + 1) - air.index(0, 0, d);
    below = air.cutDisc(d, cx, cy, R);

    const CircularGrid& g = head.grid();
    const double hm = g.spacing();
    coarserAir = ha >= hm;

    // (x, y) of an air node over the head from its index in the padded layout
    const long layer0 = air.index(0, 0, d), stride = air.index(0, 1, d) - layer0;
    auto airX = [&](long i) { return air.coordinate(0, (int) ((i - layer0) % stride)); };
    auto airY = [&](long i) { return air.coordinate(1, (int) ((i - layer0) / stride)); };

    // the groups: the head nodes and the air nodes each links
    std::vector<std::vector<int>> groupNodes;
    std::vector<std::vector<long>> groupCells;
    if (coarserAir)
    {
        // each interior head node to the nearest air node over the head
        groupNodes.resize(below.size());
        std::vector<int> rowOf((size_t) air.nx() * (size_t) air.ny(), -1);
        for (size_t row = 0; row < below.size(); ++row)
            rowOf[(size_t) ((below[row] - layer0) / stride * air.nx() + (below[row] - layer0) % stride)] = (int) row;
        for (int iy = 0; iy < g.width(); ++iy)
            for (int ix = 0; ix < g.width(); ++ix)
            {
                const int j = g.index(ix, iy);
                if (g.mask()[(size_t) j] == 0.0)
                    continue;
                const double x = cx + g.x(ix), y = cy + g.x(iy);
                const long ax = std::lround(x / ha + 0.5 * (air.nx() - 1)), ay = std::lround(y / ha + 0.5 * (air.ny() - 1));
                int row = -1;
                if (ax >= 0 && ay >= 0 && ax < air.nx() && ay < air.ny())
                    row = rowOf[(size_t) (ay * air.nx() + ax)];
                if (row < 0) // the nearest lies beyond the cut disc (at the rim): the nearest within it
                {
                    double best = std::numeric_limits<double>::infinity();
                    for (size_t r = 0; r < below.size(); ++r)
                    {
                        const double dist = std::hypot(airX(below[r]) - x, airY(below[r]) - y);
                        if (dist < best)
                        {
                            best = dist;
                            row = (int) r;
                        }
                    }
                }
                groupNodes[(size_t) row].push_back(j);
            }
        for (size_t row = 0; row < below.size(); ++row)
            groupCells.push_back({ below[row] });
    }
    else
    {
        // each air node over the head to the nearest head node; rigid when that is on the rim
        std::vector<int> groupOfNode((size_t) g.numNodes(), -1);
        for (long i : below)
        {
            const int j = g.nearestInterior(airX(i) - cx, airY(i) - cy);
            if (j < 0)
                continue;
            int& grp = groupOfNode[(size_t) j];
            if (grp < 0)
            {
                grp = (int) groupNodes.size();
                groupNodes.push_back({ j });
                groupCells.emplace_back();
            }
            groupCells[(size_t) grp].push_back(i);
        }
    }

    // Groups of the same shape next to each other: the loops over a group's nodes and air
    // nodes then run the same number of times from one group to the next.
    std::vector<size_t> order(groupNodes.size());
    std::iota(order.begin(), order.end(), size_t { 0 });
    std::stable_sort(order.begin(), order.end(), [&](size_t p, size_t q) {
        return std::pair(groupNodes[p].size(), groupCells[p].size()) < std::pair(groupNodes[q].size(), groupCells[q].size());
    });
    nodeBegin.push_back(0);
    cellBegin.push_back(0);
    groupOf.assign((size_t) g.numNodes(), -1);
    for (size_t grp : order)
    {
        if (groupNodes[grp].empty()) // an air node with no head node: rigid
            continue;
        for (int j : groupNodes[grp])
            groupOf[(size_t) j] = (int) count.size();
        nodes.insert(nodes.end(), groupNodes[grp].begin(), groupNodes[grp].end());
        cells.insert(cells.end(), groupCells[grp].begin(), groupCells[grp].end());
        nodeBegin.push_back((int) nodes.size());
        cellBegin.push_back((int) cells.size());
        for (size_t q = 0; q < groupCells[grp].size(); ++q)
            cellGroup.push_back((int) count.size());
        if (runs.empty() || runs.back().nodes != (int) groupNodes[grp].size() || runs.back().cells != (int) groupCells[grp].size())
            runs.push_back({ count.size(), count.size(), (int) groupNodes[grp].size(), (int) groupCells[grp].size() });
        runs.back().last = count.size() + 1;
        count.push_back((double) groupNodes[grp].size());
        // J's value on the group: its air nodes together sweep the volume its head nodes do
        const double m = (double) groupCells[grp].size();
        value.push_back(hm * hm / (m * ha * ha));
    }
    const size_t G = count.size(), N = nodes.size();
    for (auto* v : { &gain, &invResponse, &sumPrev, &sumR, &pullFree, &airStep })
        v->assign(G, 0.0);
    for (auto* v : { &rNode, &seenNode, &exactNode, &deltaNode, &seenOld, &exactOld, &deltaOld, &sigma, &warmNode })
        v->assign(N, 0.0);
    response.assign((size_t) g.numNodes(), 1.0);
    start = head.nextDisplacement();
    active.reserve(G);
    warmGroups.reserve(G);
    isActive.assign(G, 0);
    refresh();
    head.setResponse(response.data());
}

HeadEmbedding::~HeadEmbedding()
{
    if (head.responseScale() == response.data())
        head.setResponse(nullptr);
}

double HeadEmbedding::planeZ() const { return air.planeAbove(d); }

double HeadEmbedding::volumeRatio() const
{
    const double ha = air.spacing(), hm = head.grid().spacing();
    double swept = 0.0;
    for (size_t grp = 0; grp < count.size(); ++grp)
        swept += (double) (cellBegin[grp + 1] - cellBegin[grp]) * value[grp] * count[grp];
    return ha * ha * swept / (hm * hm * (double) nodes.size());
}

void HeadEmbedding::refresh()
{
    const double k = air.timeStep(), c = air.soundSpeed(), ha = air.spacing(), hm = head.grid().spacing();
    alpha = c * c * k / ha;                              // Psi_u - Psi_d gains alpha J (w+ - w-)
    beta = air.density() * head.forceGain() / (2.0 * k); // w+ loses beta I (D+ - D-)
    ratio = ha * ha / (hm * hm);                         // I = ratio J^T
    gamma = alpha * beta * ratio;
    for (size_t grp = 0; grp < count.size(); ++grp)
    {
        // J^T J on the group: kappa 1 1^T, kappa = (its air nodes) value^2; A^{-1} = 1 - gain 1 1^T there
        const double kappa = (double) (cellBegin[grp + 1] - cellBegin[grp]) * value[grp] * value[grp];
        gain[grp] = gamma * kappa / (1.0 + gamma * kappa * count[grp]);
        invResponse[grp] = 1.0 / (1.0 - gain[grp]);
        for (int q = nodeBegin[grp]; q < nodeBegin[grp + 1]; ++q)
            response[(size_t) nodes[(size_t) q]] = 1.0 - gain[grp]; // the diagonal of A^{-1}
    }
}

void HeadEmbedding::clear()
{
    forget();
    warmGroups.clear();
    std::fill(sigma.begin(), sigma.end(), 0.0);
}

void HeadEmbedding::forget()
{
    for (int grp : active)
        isActive[(size_t) grp] = 0;
    active.clear();
}

void HeadEmbedding::activate(int grp)
{
    if (isActive[(size_t) grp])
        return;
    isActive[(size_t) grp] = 1;
    active.push_back(grp); // within the capacity reserved: no allocation
    // untouched until now: every trial so far saw the exact pull
    const double p = pullFree[(size_t) grp];
    for (int q = nodeBegin[(size_t) grp]; q < nodeBegin[(size_t) grp + 1]; ++q)
    {
        seenNode[(size_t) q] = exactNode[(size_t) q] = seenOld[(size_t) q] = exactOld[(size_t) q] = p;
        deltaNode[(size_t) q] = deltaOld[(size_t) q] = 0.0;
    }
}

void HeadEmbedding::step()
{
    solveFree(false);
    finish();
}

namespace
{
// solveFree() over a run of groups of one shape: nn head nodes and mm air nodes each (N, M:
// the same known at compile time, 0 when not), their nodes and air nodes consecutive.
struct FreeRun
{
    const double *next, *prev, *wm;
    double* w; // w^{n+1}: w* in, A^{-1} r out
    const int* node;
    const long* cell;
    double* r; // r per node
    const double *value, *gain;
    double *sumPrev, *sumR, *pullFree, *airStep;
    long up;
    double cellGain, alpha; // ratio beta, alpha
};

template <int N, int M>
void solveFreeRun(const FreeRun& f, size_t g0, size_t g1, int nn, int mm)
{
    if constexpr (N > 0)
        nn = N;
    if constexpr (M > 0)
        mm = M;
    const int* nd = f.node;
    const long* cl = f.cell;
    double* rr = f.r;
    for (size_t grp = g0; grp < g1; ++grp, nd += nn, cl += mm, rr += nn)
    {
        double wPrev = 0.0, wStar = 0.0;
        for (int q = 0; q < nn; ++q)
        {
            wPrev += f.wm[nd[q]];
            wStar += f.w[nd[q]];
        }
        // the air side of the right-hand side: y_a = ratio beta (alpha (J w^{n-1})_a - (D*_a - D^{n-1}_a)),
        // D* = Psi_u - Psi_d from the air's own update; each head node of the group gets J^T y
        double dSum = 0.0;
        for (int q = 0; q < mm; ++q)
        {
            const long i = cl[q];
            dSum += (f.next[i + f.up] - f.next[i]) - (f.prev[i + f.up] - f.prev[i]);
        }
        const double v = f.value[grp];
        const double y = f.cellGain * v * ((double) mm * f.alpha * v * wPrev - dSum);
        const double sum = wStar + (double) nn * y; // the sum of r over the group
        const double p = f.gain[grp] * sum;         // (1 + gamma J^T J)^{-1} on the group
        double base = 0.0;
        for (int q = 0; q < nn; ++q)
        {
            const double r = f.w[nd[q]] + y;
            rr[q] = r;
            f.w[nd[q]] = r - p;
            base += r - p;
        }
        f.sumPrev[grp] = wPrev;
        f.sumR[grp] = sum;
        f.pullFree[grp] = p;
        f.airStep[grp] = 0.5 * f.alpha * v * (base - wPrev); // eq. (8) if the coupling leaves the group
    }
}
} // namespace

void HeadEmbedding::solveFree(bool warm)
{
    start = head.nextDisplacement(); // the same size: no allocation
    double* w = start.data();
    double* rr = rNode.data();
    const int* node = nodes.data();
    forget();
    FreeRun f { air.next(),
                air.prev(),
                head.previousDisplacement().data(),
                w,
                nullptr,
                nullptr,
                nullptr,
                value.data(),
                gain.data(),
                sumPrev.data(),
                sumR.data(),
                pullFree.data(),
                airStep.data(),
                up,
                ratio * beta,
                alpha };
    for (const Run& run : runs)
    {
        f.node = nodes.data() + nodeBegin[run.first];
        f.cell = cells.data() + cellBegin[run.first];
        f.r = rNode.data() + nodeBegin[run.first];
        const size_t g0 = run.first, g1 = run.last;
        // the shapes with a loop of their own (a coarse head's node can hold 8 or more air nodes)
        switch (run.nodes < 8 && run.cells < 8 ? run.nodes * 8 + run.cells : -1)
        {
            case 1 * 8 + 1: solveFreeRun<1, 1>(f, g0, g1, 1, 1); break;
            case 1 * 8 + 2: solveFreeRun<1, 2>(f, g0, g1, 1, 2); break;
            case 1 * 8 + 3: solveFreeRun<1, 3>(f, g0, g1, 1, 3); break;
            case 2 * 8 + 1: solveFreeRun<2, 1>(f, g0, g1, 2, 1); break;
            case 3 * 8 + 1: solveFreeRun<3, 1>(f, g0, g1, 3, 1); break;
            case 4 * 8 + 1: solveFreeRun<4, 1>(f, g0, g1, 4, 1); break;
            default: solveFreeRun<0, 0>(f, g0, g1, run.nodes, run.cells); break;
        }
    }
    fresh = true;
    if (warm)
        for (int grp : warmGroups)
        {
            // a group of several head nodes the coupling moved in the last step: each node starts
            // from the pull it ended with then (beyond the free one), not the free pull
            activate(grp);
            for (int q = nodeBegin[(size_t) grp]; q < nodeBegin[(size_t) grp + 1]; ++q)
            {
                const double x = pullFree[(size_t) grp] + warmNode[(size_t) q];
                seenNode[(size_t) q] = seenOld[(size_t) q] = exactOld[(size_t) q] = x;
                w[node[q]] = rr[q] - x;
            }
            fresh = false;
        }
    // the sum of the whole next level (Membrane keeps it for the swept volume)
    double s4[4] = {};
    const size_t n = start.size();
    size_t i = 0;
    for (; i + 4 <= n; i += 4)
        for (int l = 0; l < 4; ++l)
            s4[l] += w[i + (size_t) l];
    for (; i < n; ++i)
        s4[0] += w[i];
    startSum = (s4[0] + s4[1]) + (s4[2] + s4[3]);
    head.restoreNext(start, startSum);
}

double HeadEmbedding::correct()
{
    // The groups the coupling moved (the pull depends on nothing else), and the head's scale.
    const double* wn = head.nextDisplacement().data();
    const double* st = start.data();
    const int* owner = groupOf.data();
    const size_t n = start.size();
    double m4[4] = {};
    size_t i = 0;
    for (; i + 4 <= n; i += 4)
    {
        bool moved = false;
        for (int l = 0; l < 4; ++l)
        {
            moved = moved || wn[i + (size_t) l] != st[i + (size_t) l];
            m4[l] = std::max(m4[l], std::abs(wn[i + (size_t) l]));
        }
        if (moved)
            for (size_t l = i; l < i + 4; ++l)
                if (wn[l] != st[l] && owner[l] >= 0)
                    activate(owner[l]);
    }
    for (; i < n; ++i)
    {
        m4[0] = std::max(m4[0], std::abs(wn[i]));
        if (wn[i] != st[i] && owner[i] >= 0)
            activate(owner[i]);
    }
    wScale = std::max(std::max(m4[0], m4[1]), std::max(m4[2], m4[3]));
    if (fresh && active.empty()) // no force on the head: solveFree's w stands
        return 0.0;
    // The coupling moved node j by response x delta_j, delta its vacuum response: the exact
    // w = r + delta - P with P = gain (S(r) + sum delta), i.e. the node should have seen the pull
    // P - gain delta_j (its own share it saw through its response).
    const int* node = nodes.data();
    double change = 0.0;
    for (int grp : active)
    {
        const size_t g = (size_t) grp;
        const int j0 = nodeBegin[g], j1 = nodeBegin[g + 1];
        const double inv = invResponse[g], gg = gain[g];
        double added = 0.0;
        for (int q = j0; q < j1; ++q)
            added += wn[node[q]] - st[node[q]];
        const double p = gg * (sumR[g] + inv * added);
        for (int q = j0; q < j1; ++q)
        {
            const int j = node[q];
            const double delta = inv * (wn[j] - st[j]);
            const double exact = p - gg * delta;
            const double shift = seenNode[(size_t) q] - exact;
            deltaNode[(size_t) q] = delta;
            exactNode[(size_t) q] = exact;
            change = std::max(change, std::abs(shift)); // what the trial saw against the exact pull
            if (shift != 0.0)
                head.setNextAt(j, wn[j] + shift);
        }
    }
    return change;
}

void HeadEmbedding::retry(double omega, bool pointwise)
{
    fresh = false;
    double* w = start.data();
    const double* rr = rNode.data();
    const int* node = nodes.data();
    double total = startSum;
    for (int grp : active)
    {
        const size_t g = (size_t) grp;
        const int j0 = nodeBegin[g], j1 = nodeBegin[g + 1];
        const double gg = gain[g];
        if (omega < 1.0)
            for (int q = j0; q < j1; ++q) // the pull seen moved by omega of the way to the exact one
            {
                const double x = seenNode[(size_t) q];
                seenNode[(size_t) q] = x + omega * (exactNode[(size_t) q] - x);
            }
        else if (pointwise)
        {
            // The coupling's response at each node, delta_j = c_j + sigma_j x_j with sigma_j the
            // secant through the last two trials (before a second trial, the node's last one),
            // between 0 and 1 / response (a node held where it is); with it the group's pulls
            // x_j = gain (S(r) + sum over the others of delta_i) are one linear solve:
            // T = sum (c_i + sigma_i x_i) = [sum c + sum a (S(r) - c)] / (1 - sum a),
            // a_i = gain sigma_i / (1 + gain sigma_i), x_j = gain (S(r) + T - c_j) / (1 + gain sigma_j).
            const double most = invResponse[g];
            double sumC = 0.0, sumA = 0.0, sumAC = 0.0;
            for (int q = j0; q < j1; ++q)
            {
                const size_t i = (size_t) q;
                const double dx = seenNode[i] - seenOld[i];
                if (dx != 0.0)
                    sigma[i] = std::clamp((deltaNode[i] - deltaOld[i]) / dx, 0.0, most);
                const double c = deltaNode[i] - sigma[i] * seenNode[i], a = gg * sigma[i] / (1.0 + gg * sigma[i]);
                sumC += c;
                sumA += a;
                sumAC += a * c;
            }
            const double T = (sumC + sumA * sumR[g] - sumAC) / (1.0 - sumA);
            for (int q = j0; q < j1; ++q)
            {
                const size_t i = (size_t) q;
                const double c = deltaNode[i] - sigma[i] * seenNode[i];
                seenOld[i] = seenNode[i];
                exactOld[i] = exactNode[i];
                deltaOld[i] = deltaNode[i];
                seenNode[i] = gg * (sumR[g] + T - c) / (1.0 + gg * sigma[i]);
            }
        }
        else
            for (int q = j0; q < j1; ++q)
            {
                // The exact pull against the one seen, node by node, taken linear through the
                // last two trials (the secant): a force spread over several nodes moves them
                // together, so from one trial to the next each node's pull moves along the
                // same direction.
                const size_t i = (size_t) q;
                const double x = seenNode[i], t = exactNode[i];
                const double dx = x - seenOld[i];
                const double m = dx != 0.0 ? std::clamp((t - exactOld[i]) / dx, -0.5, 0.5) : 0.0;
                seenOld[i] = x;
                exactOld[i] = t;
                deltaOld[i] = deltaNode[i];
                seenNode[i] = t + m / (1.0 - m) * (t - x);
            }
        // the head as the trial found it, with the new pull
        for (int q = j0; q < j1; ++q)
        {
            const double v = rr[q] - seenNode[(size_t) q];
            total += v - w[node[q]];
            w[node[q]] = v;
        }
    }
    startSum = total;
    head.restoreNext(start, startSum);
}

void HeadEmbedding::finish()
{
    // where the coupling moved a group of several nodes, the pull they ended with: the next
    // step's start
    warmGroups.clear();
    for (int grp : active)
        if (nodeBegin[(size_t) grp + 1] - nodeBegin[(size_t) grp] > 1)
        {
            warmGroups.push_back(grp);
            for (int q = nodeBegin[(size_t) grp]; q < nodeBegin[(size_t) grp + 1]; ++q)
                warmNode[(size_t) q] = exactNode[(size_t) q] - pullFree[(size_t) grp];
        }
    // eq. (8): the head's velocity is the air's on both sides, D^{n+1} = D* + alpha J (w^{n+1} - w^{n-1})
    const double* wn = head.nextDisplacement().data();
    const int* node = nodes.data();
    for (int grp : active)
    {
        double sum = 0.0;
        for (int q = nodeBegin[(size_t) grp]; q < nodeBegin[(size_t) grp + 1]; ++q)
            sum += wn[node[q]];
        airStep[(size_t) grp] = 0.5 * alpha * value[(size_t) grp] * (sum - sumPrev[(size_t) grp]);
    }
    double* next = air.next();
    const long u = up;
    const size_t nc = cells.size();
    for (size_t q = 0; q < nc; ++q)
    {
        const double t = airStep[(size_t) cellGroup[q]];
        next[cells[q] + u] += t;
        next[cells[q]] -= t;
    }
}

} // namespace snaresim
