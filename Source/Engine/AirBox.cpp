#include "AirBox.h"

#include "VectorClones.h"

#include <algorithm>
#include <barrier>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace snaresim
{

namespace
{
constexpr long maxPoints = 60'000'000; // about 1.4 GB for the three levels

std::string fmt(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return b;
}

// One row of eq. (25), lossy: out = a0 u + a1 (6 neighbours of u) + b0 up + b1 (6 neighbours of up).
SNARESIM_VECTOR_CLONES void rowLossy(double* __restrict out, const double* __restrict u, const double* __restrict up, int count,
                                     long sx, long sxy, double a0, double a1, double b0, double b1)
{
    for (int m = 0; m < count; ++m)
    {
        const double nb = (u[m - 1] + u[m + 1]) + (u[m - sx] + u[m + sx]) + (u[m - sxy] + u[m + sxy]);
        const double nbp = (up[m - 1] + up[m + 1]) + (up[m - sx] + up[m + sx]) + (up[m - sxy] + up[m + sxy]);
        out[m] = a0 * u[m] + a1 * nb + b0 * up[m] + b1 * nbp;
    }
}

// The same without sigma_a: out = a0 u + a1 (6 neighbours of u) - up.
SNARESIM_VECTOR_CLONES void rowLossless(double* __restrict out, const double* __restrict u, const double* __restrict up, int count,
                                        long sx, long sxy, double a0, double a1)
{
    for (int m = 0; m < count; ++m)
    {
        const double nb = (u[m - 1] + u[m + 1]) + (u[m - sx] + u[m + sx]) + (u[m - sxy] + u[m + sxy]);
        out[m] = a0 * u[m] + a1 * nb - up[m];
    }
}
} // namespace

// Workers that each run a slice of the layers, started and joined by two barriers per step.
struct AirBox::Pool
{
    Pool(AirBox& box, int count) : start(count), done(count)
    {
        for (int t = 1; t < count; ++t)
            workers.emplace_back([this, &box, t, count] {
                for (;;)
                {
                    start.arrive_and_wait();
                    if (stop)
                        return;
                    const auto [b, e] = slice(box, t, count);
                    box.updateLayers(b, e);
                    done.arrive_and_wait();
                }
            });
    }
    ~Pool()
    {
        stop = true;
        start.arrive_and_wait();
        for (auto& w : workers)
            w.join();
    }
    static std::pair<int, int> slice(const AirBox& box, int t, int count)
    {
        const int nz = box.n[2];
        return { nz * t / count, nz * (t + 1) / count };
    }
    std::barrier<> start, done;
    bool stop = false;
    std::vector<std::thread> workers;
};

double AirBox::gridSpacing(const AirBoxSpec& sp, double k)
{
    const double sig = sp.gridSigma_m >= 0.0 ? std::max(sp.gridSigma_m, sp.sigma_m) : sp.sigma_m;
    const double ca = sp.soundSpeed_m_per_s;
    // eq. (41): h^2 >= 3 c^2 k^2 + 6 c sigma k
    return sp.gridCoarseness * std::sqrt(3.0 * ca * ca * k * k + 6.0 * ca * sig * k);
}

AirBox::AirBox(const AirBoxSpec& sp, double timeStep)
    : spec(sp), k(timeStep), c(sp.soundSpeed_m_per_s), rho(sp.density_kg_per_m3), sigma(sp.sigma_m)
{
    if (! (k > 0.0) || ! std::isfinite(k) || ! std::isfinite(1.0 / k))
        throw std::invalid_argument("air box: the sample rate must be a positive finite number (time step " + fmt(k) + " s)");
    if (! (c > 0.0) || ! (rho > 0.0) || ! (sigma >= 0.0) || ! std::isfinite(c + rho + sigma))
        throw std::invalid_argument("air box: sound speed and density must be positive and sigma_a not negative");
    if (! (sp.gridCoarseness >= 1.0) || ! std::isfinite(sp.gridCoarseness))
        throw std::invalid_argument("air box: grid coarseness " + fmt(sp.gridCoarseness)
                                    + " is below the stability bound of eq. 41 (it must be at least 1)");
    h = gridSpacing(sp, k);
    for (int a = 0; a < 3; ++a)
    {
        const double L = sp.size_m[(size_t) a];
        if (! (L > 0.0) || ! std::isfinite(L))
            throw std::invalid_argument("air box: the box size must be positive (axis " + std::to_string(a) + ": " + fmt(L) + " m)");
        const double cells = std::ceil(L / h - 1e-9);
        if (cells < 3.0)
            throw std::invalid_argument("air box: a " + fmt(L) + " m side holds fewer than 3 points at h = " + fmt(h)
                                        + " m (eq. 41 at this sample rate); make the box larger or the sample rate higher");
        if (cells > 1e5)
            throw std::invalid_argument("air box: " + fmt(cells) + " points along one side is too many");
        n[(size_t) a] = (int) cells;
    }
    if ((double) n[0] * n[1] * n[2] > (double) maxPoints)
        throw std::invalid_argument("air box: " + fmt((double) n[0] * n[1] * n[2]) + " points at h = " + fmt(h)
                                    + " m is more than the limit of " + fmt((double) maxPoints) + "; lower the sample rate or the box size");
    if (sp.shell)
    {
        const double R = sp.shellRadius_m, H = sp.shellDepth_m;
        if (! (R > 0.0) || ! (H > 0.0))
            throw std::invalid_argument("air box: the shell's radius and depth must be positive");
        const double halfX = 0.5 * n[0] * h, halfY = 0.5 * n[1] * h, halfZ = 0.5 * n[2] * h;
        if (R + h > std::min(halfX, halfY) || 0.5 * H + h > halfZ)
            throw std::invalid_argument("air box: the drum (radius " + fmt(R) + " m, depth " + fmt(H) + " m) does not fit in the "
                                        + fmt(sp.size_m[0]) + " x " + fmt(sp.size_m[1]) + " x " + fmt(sp.size_m[2])
                                        + " m box with a cell to spare");
        if (H < 2.0 * h)
            throw std::invalid_argument("air box: the shell depth " + fmt(H) + " m is less than two cells (h = " + fmt(h) + " m)");
    }

    sx = n[0] + 2;
    sy = n[1] + 2;
    total = sx * sy * (n[2] + 2);
    store.assign((size_t) (3 * total), 0.0);
    for (int i = 0; i < 3; ++i)
        lvl[i] = store.data() + i * total;
    cutMask.assign((size_t) total, 0);

    l2 = (c * k / h) * (c * k / h);
    s = c * sigma * k / (h * h);
    // Psi+ = 2 Psi - Psi- + l2 L Psi + s (L Psi - L Psi-), L the unscaled 7-point Laplacian
    a0 = 2.0 - 6.0 * (l2 + s);
    a1 = l2 + s;
    b0 = -(1.0 - 6.0 * s);
    b1 = -s;

    buildWalls();
    if (sp.shell)
        buildShell();
}

AirBox::~AirBox() = default;

void AirBox::buildWalls()
{
    if (spec.walls != AirWalls::absorbing)
        return;
    for (int iz = 0; iz < n[2]; ++iz)
        for (int iy = 0; iy < n[1]; ++iy)
            for (int ix = 0; ix < n[0]; ++ix)
            {
                const int m = (ix == 0) + (ix == n[0] - 1) + (iy == 0) + (iy == n[1] - 1) + (iz == 0) + (iz == n[2] - 1);
                if (m > 0)
                    wallNodes[(size_t) std::min(m, 3) - 1].push_back(index(ix, iy, iz));
            }
}

void AirBox::cutLink(long a, long b, int axis)
{
    const auto bit = (std::uint8_t) (1u << axis);
    if (cutMask[(size_t) a] & bit)
        return;
    cutMask[(size_t) a] |= bit;
    cutA.push_back(a);
    cutB.push_back(b);
}

int AirBox::layerBelow(double z) const
{
    return (int) std::lround((z - coordinate(2, 0) - 0.5 * h) / h);
}

// eq. (6): the shell is the staircase between nodes within R of the axis and nodes beyond;
// the horizontal links across it are cut on every layer between the two heads' planes.
void AirBox::buildShell()
{
    const double R = spec.shellRadius_m;
    const int lc = layerBelow(-0.5 * spec.shellDepth_m), lb = layerBelow(0.5 * spec.shellDepth_m);
    auto inside = [&](int ix, int iy) {
        const double x = coordinate(0, ix), y = coordinate(1, iy);
        return x * x + y * y < R * R;
    };
    for (int iz = lc + 1; iz <= lb; ++iz)
        for (int iy = 0; iy < n[1]; ++iy)
            for (int ix = 0; ix < n[0]; ++ix)
            {
                const bool in = inside(ix, iy);
                if (ix + 1 < n[0] && inside(ix + 1, iy) != in)
                    cutLink(index(ix, iy, iz), index(ix + 1, iy, iz), 0);
                if (iy + 1 < n[1] && inside(ix, iy + 1) != in)
                    cutLink(index(ix, iy, iz), index(ix, iy + 1, iz), 1);
            }
    if (spec.shellEnds == ShellEnds::closed)
    {
        cutDisc(lc, 0.0, 0.0, R);
        cutDisc(lb, 0.0, 0.0, R);
    }
}

std::vector<long> AirBox::cutDisc(int layer, double cx, double cy, double radius)
{
    if (layer < 0 || layer + 1 >= n[2])
        throw std::invalid_argument("air box: a disc between layers " + std::to_string(layer) + " and " + std::to_string(layer + 1)
                                    + " is outside the box");
    std::vector<long> nodes;
    for (int iy = 0; iy < n[1]; ++iy)
        for (int ix = 0; ix < n[0]; ++ix)
        {
            const double x = coordinate(0, ix) - cx, y = coordinate(1, iy) - cy;
            if (x * x + y * y < radius * radius)
            {
                cutLink(index(ix, iy, layer), index(ix, iy, layer + 1), 2);
                nodes.push_back(index(ix, iy, layer));
            }
        }
    return nodes;
}

void AirBox::setPotential(const std::function<double(double, double, double)>& f)
{
    clear();
    for (int iz = 0; iz < n[2]; ++iz)
        for (int iy = 0; iy < n[1]; ++iy)
            for (int ix = 0; ix < n[0]; ++ix)
            {
                const long i = index(ix, iy, iz);
                lvl[1][i] = lvl[2][i] = f(coordinate(0, ix), coordinate(1, iy), coordinate(2, iz));
            }
    fillGhosts(lvl[1]);
    fillGhosts(lvl[2]);
}

void AirBox::clear()
{
    std::fill(store.begin(), store.end(), 0.0);
}

// Ghost nodes copy the node inside each face, so links through the walls carry nothing.
void AirBox::fillGhosts(double* u)
{
    const long sxy = sx * sy;
    for (int iz = 1; iz <= n[2]; ++iz)
    {
        double* layer = u + iz * sxy;
        for (int iy = 1; iy <= n[1]; ++iy)
        {
            double* row = layer + iy * sx;
            row[0] = row[1];
            row[n[0] + 1] = row[n[0]];
        }
        std::copy(layer + sx + 1, layer + sx + 1 + n[0], layer + 1);
        std::copy(layer + n[1] * sx + 1, layer + n[1] * sx + 1 + n[0], layer + (n[1] + 1) * sx + 1);
    }
    std::copy(u + sxy, u + 2 * sxy, u);
    std::copy(u + n[2] * sxy, u + (n[2] + 1) * sxy, u + (n[2] + 1) * sxy);
}

void AirBox::updateLayers(int zBegin, int zEnd)
{
    const long sxy = sx * sy;
    double* out = lvl[0];
    const double* u = lvl[1];
    const double* up = lvl[2];
    for (int iz = zBegin + 1; iz <= zEnd; ++iz)
        for (int iy = 1; iy <= n[1]; ++iy)
        {
            const long r = iz * sxy + iy * sx + 1;
            if (s != 0.0)
                rowLossy(out + r, u + r, up + r, n[0], sx, sxy, a0, a1, b0, b1);
            else
                rowLossless(out + r, u + r, up + r, n[0], sx, sxy, a0, a1);
        }
}

void AirBox::setThreads(int count)
{
    count = std::max(1, count);
    if (count == threadCount)
        return;
    pool.reset();
    threadCount = std::min(count, std::max(1, n[2]));
    if (threadCount > 1)
        pool = std::make_unique<Pool>(*this, threadCount);
}

void AirBox::computeNext()
{
    // eq. (25) everywhere, every link present (walls through the mirrored ghosts)
    if (pool)
    {
        pool->start.arrive_and_wait();
        const auto [b, e] = Pool::slice(*this, 0, threadCount);
        updateLayers(b, e);
        pool->done.arrive_and_wait();
    }
    else
        updateLayers(0, n[2]);

    // take back the cut links' terms (shell eq. 6, closed ends, embedded heads)
    double* out = lvl[0];
    const double* u = lvl[1];
    const double* up = lvl[2];
    for (size_t j = 0; j < cutA.size(); ++j)
    {
        const long a = cutA[j], b = cutB[j];
        const double t = a1 * (u[b] - u[a]) + b1 * (up[b] - up[a]);
        out[a] -= t;
        out[b] += t;
    }

    // eq. (51): (1 + m lambda/2) Psi+ = [the update above] + (m lambda/2) Psi-
    if (spec.walls == AirWalls::absorbing)
    {
        const double lambda = c * k / h;
        for (int m = 1; m <= 3; ++m)
        {
            const double g = 0.5 * m * lambda, inv = 1.0 / (1.0 + g);
            for (long i : wallNodes[(size_t) m - 1])
                out[i] = (out[i] + g * up[i]) * inv;
        }
    }
    fillGhosts(out);
}

void AirBox::advance()
{
    double* t = lvl[2];
    lvl[2] = lvl[1];
    lvl[1] = lvl[0];
    lvl[0] = t;
}

double AirBox::energy() const
{
    const long sxy = sx * sy;
    const double* up = lvl[0];
    const double* u = lvl[1];
    double kin = 0.0, pot = 0.0, vis = 0.0;
    for (int iz = 1; iz <= n[2]; ++iz)
        for (int iy = 1; iy <= n[1]; ++iy)
        {
            const long r = iz * sxy + iy * sx;
            double kr = 0.0, pr = 0.0, vr = 0.0;
            for (long i = r + 1; i <= r + n[0]; ++i)
            {
                const double v = up[i] - u[i];
                kr += v * v;
                for (long d : { 1L, sx, sxy })
                {
                    const double gn = up[i + d] - up[i], g = u[i + d] - u[i];
                    pr += gn * g;
                    vr += (gn - g) * (gn - g);
                }
            }
            kin += kr;
            pot += pr;
            vis += vr;
        }
    for (size_t j = 0; j < cutA.size(); ++j)
    {
        const long a = cutA[j], b = cutB[j];
        const double gn = up[b] - up[a], g = u[b] - u[a];
        pot -= gn * g;
        vis -= (gn - g) * (gn - g);
    }
    // eq. (36), h^3 [rho/(2c^2) |dt+ Psi|^2 + rho/2 (D+ Psi)(et+ D+ Psi)] - h^3 (rho sigma k / 4c) |D+ dt+ Psi|^2
    return 0.5 * rho * h * (h * h / (c * c * k * k) * kin + pot - sigma / (2.0 * c * k) * vis);
}

double AirBox::stepLoss() const
{
    const long sxy = sx * sy;
    const double* up = lvl[0];
    const double* um = lvl[2];
    double grad = 0.0, wall = 0.0;
    if (sigma > 0.0)
    {
        for (int iz = 1; iz <= n[2]; ++iz)
            for (int iy = 1; iy <= n[1]; ++iy)
            {
                const long r = iz * sxy + iy * sx;
                double gr = 0.0;
                for (long i = r + 1; i <= r + n[0]; ++i)
                    for (long d : { 1L, sx, sxy })
                    {
                        const double t = (up[i + d] - um[i + d]) - (up[i] - um[i]);
                        gr += t * t;
                    }
                grad += gr;
            }
        for (size_t j = 0; j < cutA.size(); ++j)
        {
            const long a = cutA[j], b = cutB[j];
            const double t = (up[b] - um[b]) - (up[a] - um[a]);
            grad -= t * t;
        }
    }
    if (spec.walls == AirWalls::absorbing)
        for (int m = 1; m <= 3; ++m)
        {
            double w = 0.0;
            for (long i : wallNodes[(size_t) m - 1])
                w += (up[i] - um[i]) * (up[i] - um[i]);
            wall += m * w;
        }
    // k q^n: sigma term k (rho sigma / c) h^3 |D+ dt. Psi|^2, walls k (m rho h^2 / c) (dt. Psi)^2
    return rho * h / (4.0 * c * k) * (sigma * grad + h * wall);
}

double AirBox::pressure(double x, double y, double z) const
{
    const double f[3] = { x / h + 0.5 * (n[0] - 1), y / h + 0.5 * (n[1] - 1), z / h + 0.5 * (n[2] - 1) };
    int i0[3];
    double w[3];
    for (int a = 0; a < 3; ++a)
    {
        if (! (f[a] >= 0.0 && f[a] <= n[(size_t) a] - 1))
            return 0.0;
        i0[a] = std::min((int) std::floor(f[a]), n[(size_t) a] - 2);
        w[a] = f[a] - i0[a];
    }
    double p = 0.0;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
            {
                const long i = index(i0[0] + dx, i0[1] + dy, i0[2] + dz);
                const double wt = (dx ? w[0] : 1 - w[0]) * (dy ? w[1] : 1 - w[1]) * (dz ? w[2] : 1 - w[2]);
                p += wt * (lvl[0][i] - lvl[1][i]);
            }
    return rho * p / k;
}

} // namespace snaresim
