#include "AirBox.h"

#include "VectorTarget.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

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

// What the layer's nodes need after the stencil, row by row while they are cached: the cut
// links taken back (shell eq. 6, closed ends, embedded heads), the absorbing walls (eq. 51), the
// ghost columns.
struct LayerFixes
{
    const AirCut* cuts;    // the layer's cut-link ends, by row
    const int* rowStart;   // interior row iy's (1..ny) are [rowStart[iy - 1], rowStart[iy])
    const double* gain;    // eq. (51) by number of wall faces m: m lambda / 2
    const double* inverse; // 1 / (1 + m lambda / 2)
    int layerFaces;        // wall faces of the layer itself (0, or 1 at the top or bottom); -1: reflecting walls
};

#define SNARESIM_KERNELS "AirBoxKernels.inl"
#include "PerVectorTarget.inl"

inline void relax()
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Spin-then-block: spins a bounded number of times on the atomic, then sleeps in
// std::atomic::wait (a futex), until done(value) holds. A busy machine is not starved by a
// thread that waits long; a short wait costs no system call.
constexpr int spinLimit = 2048; // about 40 us of pause instructions on the build machine

template <class T, class Done>
T awaitValue(const std::atomic<T>& a, Done done)
{
    T x = a.load(std::memory_order_acquire);
    for (int i = 0; i < spinLimit && ! done(x); ++i)
    {
        relax();
        x = a.load(std::memory_order_acquire);
    }
    while (! done(x))
    {
        a.wait(x, std::memory_order_acquire);
        x = a.load(std::memory_order_acquire);
    }
    return x;
}

// A range of positions in the threads' order, [front, back), claimed one layer at a time from
// the front (its owner) or the back (a thread that has finished its own): one atomic word.
struct alignas(64) Range
{
    std::atomic<std::uint64_t> word { 0 };
    static std::uint64_t pack(std::uint32_t front, std::uint32_t back) { return (std::uint64_t) back << 32 | front; }
    void set(std::uint32_t front, std::uint32_t back) { word.store(pack(front, back), std::memory_order_relaxed); }
    std::uint32_t left() const
    {
        const std::uint64_t w = word.load(std::memory_order_relaxed);
        return (std::uint32_t)(w >> 32) - (std::uint32_t) w;
    }
    // the position claimed, or -1 when the range is empty
    long claim(bool fromFront)
    {
        std::uint64_t w = word.load(std::memory_order_relaxed);
        for (;;)
        {
            const auto front = (std::uint32_t) w, back = (std::uint32_t)(w >> 32);
            if (front >= back)
                return -1;
            const std::uint64_t next = fromFront ? pack(front + 1, back) : pack(front, back - 1);
            if (word.compare_exchange_weak(w, next, std::memory_order_relaxed))
                return fromFront ? (long) front : (long) back - 1;
        }
    }
};
} // namespace

// Workers 1..count-1. Each step (beginNext) hands worker t a contiguous range of the layers
// not computed on the caller, which it works through from the front; a thread whose range is
// done (the caller in finishNext included) takes layers from the back of the fullest range.
struct AirBox::Pool
{
    Pool(AirBox& b, int count) : box(b), ranges((size_t) count - 1)
    {
        for (int t = 1; t < count; ++t)
            workers.emplace_back([this, t] { run(t); });
    }
    ~Pool()
    {
        stop.store(true, std::memory_order_relaxed);
        generation.fetch_add(1, std::memory_order_release);
        generation.notify_all();
        for (auto& w : workers)
            w.join();
    }

    // Splits the positions 0..count-1 over the workers and wakes them.
    void start(int count)
    {
        const auto w = (std::uint32_t) ranges.size();
        for (std::uint32_t t = 0; t < w; ++t)
            ranges[t].set((std::uint32_t)((std::uint64_t) count * t / w), (std::uint32_t)((std::uint64_t) count * (t + 1) / w));
        finished.store(0, std::memory_order_relaxed);
        generation.fetch_add(1, std::memory_order_release);
        generation.notify_all(); // no system call unless a worker sleeps
    }

    // Layers from the back of the fullest range until none is left.
    void help(Ring& ring)
    {
        for (;;)
        {
            Range* fullest = nullptr;
            std::uint32_t most = 0;
            for (auto& r : ranges)
                if (const auto left = r.left(); left > most)
                {
                    most = left;
                    fullest = &r;
                }
            if (fullest == nullptr)
                return;
            const long p = fullest->claim(false);
            if (p >= 0)
                box.updateLayer(box.rest[(size_t) p], ring);
        }
    }

    void join()
    {
        const auto w = (int) ranges.size();
        awaitValue(finished, [w](int f) { return f == w; });
    }

    void run(int t)
    {
        std::uint32_t seen = 0;
        Ring& ring = box.rings[(size_t) t];
        for (;;)
        {
            seen = awaitValue(generation, [seen](std::uint32_t g) { return g != seen; });
            if (stop.load(std::memory_order_relaxed))
                return;
            ring.invalidate(); // new levels
            Range& own = ranges[(size_t) t - 1];
            for (long p; (p = own.claim(true)) >= 0;)
                box.updateLayer(box.rest[(size_t) p], ring);
            help(ring);
            finished.fetch_add(1, std::memory_order_release);
            finished.notify_one();
        }
    }

    AirBox& box;
    std::vector<Range> ranges; // worker t's is ranges[t - 1]
    std::atomic<std::uint32_t> generation { 0 };
    std::atomic<int> finished { 0 };
    std::atomic<bool> stop { false };
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
        throw std::invalid_argument("air box: grid coarseness " + fmt(sp.gridCoarseness) +
                                    " is below the stability bound of eq. 41 (it must be at least 1)");
    h = gridSpacing(sp, k);
    for (int a = 0; a < 3; ++a)
    {
        const double L = sp.size_m[(size_t) a];
        if (! (L > 0.0) || ! std::isfinite(L))
            throw std::invalid_argument("air box: the box size must be positive (axis " + std::to_string(a) + ": " + fmt(L) + " m)");
        const double cells = std::ceil(L / h - 1e-9);
        if (cells < 3.0)
            throw std::invalid_argument("air box: a " + fmt(L) + " m side holds fewer than 3 points at h = " + fmt(h) +
                                        " m (eq. 41 at this sample rate); make the box larger or the sample rate higher");
        if (cells > 1e5)
            throw std::invalid_argument("air box: " + fmt(cells) + " points along one side is too many");
        n[(size_t) a] = (int) cells;
    }
    if ((double) n[0] * n[1] * n[2] > (double) maxPoints)
        throw std::invalid_argument("air box: " + fmt((double) n[0] * n[1] * n[2]) + " points at h = " + fmt(h) +
                                    " m is more than the limit of " + fmt((double) maxPoints) + "; lower the sample rate or the box size");
    if (sp.shell)
    {
        const double R = sp.shellRadius_m, H = sp.shellDepth_m;
        if (! (R > 0.0) || ! (H > 0.0))
            throw std::invalid_argument("air box: the shell's radius and depth must be positive");
        const double halfX = 0.5 * n[0] * h, halfY = 0.5 * n[1] * h, halfZ = 0.5 * n[2] * h;
        if (R + h > std::min(halfX, halfY) || 0.5 * H + h > halfZ)
            throw std::invalid_argument("air box: the drum (radius " + fmt(R) + " m, depth " + fmt(H) + " m) does not fit in the " +
                                        fmt(sp.size_m[0]) + " x " + fmt(sp.size_m[1]) + " x " + fmt(sp.size_m[2]) +
                                        " m box with a cell to spare");
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
    const double lambda = c * k / h;
    for (int m = 1; m <= 3; ++m)
    {
        wallGain[(size_t) m] = 0.5 * m * lambda;
        wallInverse[(size_t) m] = 1.0 / (1.0 + wallGain[(size_t) m]);
    }

    buildWalls();
    if (sp.shell)
        buildShell();
    indexCuts();
    early.reserve((size_t) n[2]);
    rest.reserve((size_t) n[2]);
    setOrder({});
    rings.resize(1);
    rings[0].v.assign((size_t) (3 * sx * sy), 0.0);
}

AirBox::~AirBox()
{
    finishNext(); // then the pool (declared last) stops and joins its threads
}

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
    const auto bit = (std::uint8_t)(1u << axis);
    if (cutMask[(size_t) a] & bit)
        return;
    cutMask[(size_t) a] |= bit;
    cutA.push_back(a);
    cutB.push_back(b);
}

int AirBox::layerBelow(double z) const { return (int) std::lround((z - coordinate(2, 0) - 0.5 * h) / h); }

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
        throw std::invalid_argument("air box: a disc between layers " + std::to_string(layer) + " and " + std::to_string(layer + 1) +
                                    " is outside the box");
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
    indexCuts();
    return nodes;
}

// Each cut link (a, b) from both ends, by layer and row: node a loses v_b - v_a, node b v_a - v_b.
void AirBox::indexCuts()
{
    finishNext();
    const long sxy = sx * sy;
    const auto key = [&](long i) { return (size_t) (i / sxy - 1) * (size_t) n[1] + (size_t) ((i % sxy) / sx - 1); };
    const size_t rows = (size_t) n[2] * (size_t) n[1];
    cutRow.assign(rows + 1, 0);
    for (size_t j = 0; j < cutA.size(); ++j)
    {
        ++cutRow[key(cutA[j]) + 1];
        ++cutRow[key(cutB[j]) + 1];
    }
    for (size_t k = 0; k < rows; ++k)
        cutRow[k + 1] += cutRow[k];
    cuts.assign(2 * cutA.size(), AirCut {});
    std::vector<int> fill(cutRow.begin(), cutRow.end() - 1);
    for (size_t j = 0; j < cutA.size(); ++j)
        for (const auto& [i, other] : { std::pair { cutA[j], cutB[j] }, std::pair { cutB[j], cutA[j] } })
        {
            const long d = other - i;
            const int layer = d == sxy ? 2 : d == -sxy ? 0 : 1;
            cuts[(size_t) fill[key(i)]++] = { (int) (i % sxy), (int) d, layer, (int) (layer == 1 ? d : 0) };
        }
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
    finishNext();
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

// v of padded layer pz in the ring, computed unless the ring holds it already.
const double* AirBox::ringLayer(Ring& ring, int pz) const
{
    const long sxy = sx * sy;
    const int slot = pz % 3;
    double* v = ring.v.data() + slot * sxy;
    if (ring.tag[slot] != pz)
    {
        SNARESIM_ON_VECTOR_TARGET(layerV)(v, lvl[1] + pz * sxy, lvl[2] + pz * sxy, sxy, a1, b1);
        ring.tag[slot] = pz;
    }
    return v;
}

// Layer iz of Psi^{n+1}, complete: eq. (25) with every link, then row by row the cut links
// taken back (shell eq. 6, closed ends, embedded heads), the absorbing walls (eq. 51) and the
// ghosts that mirror the layer (links through the walls carry nothing), while it is cached. Reads Psi^n and Psi^{n-1}
// only, so the layers can be computed in any order, by any thread, with the same numbers
// (v is a1 Psi^n + b1 Psi^{n-1} however it is reached: the file is built without contraction).
void AirBox::updateLayer(int iz, Ring& ring)
{
    const long sxy = sx * sy;
    const int pz = iz + 1;
    const long base = pz * sxy;
    double* out = lvl[0] + base;
    const double* u = lvl[1] + base;
    const double* up = lvl[2] + base;
    const LayerFixes fixes { cuts.data(), cutRow.data() + (size_t) iz * (size_t) n[1], wallGain.data(), wallInverse.data(),
                             spec.walls == AirWalls::absorbing ? (iz == 0) + (iz == n[2] - 1) : -1 };
    // Rows 1..ny as one range, ghost columns included (no row ends in the loops), then fixed.
    const long first = sx, end = (n[1] + 1) * sx;
    if (s != 0.0)
    {
        // v of this layer and both neighbours: from the ring, or computed; a run of layers
        // upwards (or downwards) computes the next layer's v with the layer itself
        const double* side[3] { nullptr, ringLayer(ring, pz), nullptr };
        const auto held = [&](int q) { return ring.tag[q % 3] == q; };
        if (held(pz - 1) && held(pz + 1))
        {
            side[0] = ring.v.data() + ((pz - 1) % 3) * sxy;
            side[2] = ring.v.data() + ((pz + 1) % 3) * sxy;
            SNARESIM_ON_VECTOR_TARGET(layerLossy)(out, u, up, side[1], side[0], side[2], first, end, sx, a0, b0);
        }
        else
        {
            const bool down = held(pz + 1);
            const int q = down ? pz - 1 : pz + 1; // the layer whose v is computed here
            const double* vo = ringLayer(ring, down ? pz + 1 : pz - 1);
            double* vn = ring.v.data() + (q % 3) * sxy;
            SNARESIM_ON_VECTOR_TARGET(layerLossyAhead)
            (out, u, up, side[1], vo, vn, lvl[1] + q * sxy, lvl[2] + q * sxy, first, end, sx, a0, b0, a1, b1);
            std::copy(vn + sx, vn + 2 * sx, vn); // vn's ghost rows
            std::copy(vn + n[1] * sx, vn + (n[1] + 1) * sx, vn + (n[1] + 1) * sx);
            ring.tag[q % 3] = q;
            side[0] = down ? vn : vo;
            side[2] = down ? vo : vn;
        }
        SNARESIM_ON_VECTOR_TARGET(fixLayer)(out, up, side, nullptr, 0.0, n[0], n[1], sx, fixes);
    }
    else
    {
        const double* none[3] { nullptr, nullptr, nullptr };
        SNARESIM_ON_VECTOR_TARGET(layerLossless)(out, u, up, first, end, sx, sxy, a0, a1);
        SNARESIM_ON_VECTOR_TARGET(fixLayer)(out, up, none, u, a1, n[0], n[1], sx, fixes);
    }

    // the ghost rows, and the ghost layers beyond the top and bottom ones
    std::copy(out + sx, out + 2 * sx, out);
    std::copy(out + n[1] * sx, out + (n[1] + 1) * sx, out + (n[1] + 1) * sx);
    if (iz == 0)
        std::copy(out, out + sxy, out - sxy);
    if (iz == n[2] - 1)
        std::copy(out, out + sxy, out + sxy);
}

void AirBox::setThreads(int count)
{
    finishNext();
    count = std::max(1, count);
    if (count == threadCount)
        return;
    pool.reset();
    threadCount = std::min(count, std::max(1, n[2]));
    rings.resize((size_t) threadCount);
    for (auto& r : rings)
    {
        r.v.assign((size_t) (3 * sx * sy), 0.0);
        r.invalidate();
    }
    if (threadCount > 1)
        pool = std::make_unique<Pool>(*this, threadCount);
}

// The listed layers (sorted, each once), and the others in the threads' order: those below the
// highest listed layer upwards, then those above it downwards. The workers start at the front;
// the caller, done with the listed layers, takes from the back, right above the last layer it
// computed, whose v it still holds (each thread's run of layers computes two layers' v to start).
void AirBox::setOrder(std::span<const int> layers)
{
    earlyArgs.assign(layers.begin(), layers.end());
    std::vector<std::uint8_t> listed((size_t) n[2], 0);
    for (int l : layers)
    {
        if (l < 0 || l >= n[2])
            throw std::invalid_argument("air box: layer " + std::to_string(l) + " is outside the box");
        listed[(size_t) l] = 1;
    }
    early.clear();
    rest.clear();
    for (int iz = 0; iz < n[2]; ++iz)
        if (listed[(size_t) iz])
            early.push_back(iz);
    const int top = early.empty() ? n[2] : early.back();
    for (int iz = 0; iz < top; ++iz)
        if (! listed[(size_t) iz])
            rest.push_back(iz);
    for (int iz = n[2] - 1; iz > top; --iz)
        rest.push_back(iz);
}

void AirBox::beginNext(std::span<const int> layers)
{
    finishNext();
    if (! std::equal(layers.begin(), layers.end(), earlyArgs.begin(), earlyArgs.end()))
        setOrder(layers);
    Ring& ring = rings[0];
    ring.invalidate(); // new levels
    if (! pool)
    {
        // one thread: every layer now, in one run upwards (the listed ones are final, as asked)
        for (int iz = 0; iz < n[2]; ++iz)
            updateLayer(iz, ring);
        return;
    }
    pending = true;
    pool->start((int) rest.size());
    for (int iz : early)
        updateLayer(iz, ring);
}

void AirBox::finishNext()
{
    if (! pending)
        return;
    pending = false;
    pool->help(rings[0]);
    pool->join();
}

void AirBox::computeNext()
{
    beginNext({});
    finishNext();
}

void AirBox::advance()
{
    finishNext();
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
