#include "Membrane.h"

#include "GridDesign.h"
#include "VectorTarget.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#if SNARESIM_VECTOR_TARGETS
#include <immintrin.h>
#endif

namespace snaresim
{
namespace
{
// The block sums' scratch for an n x n grid: every band's row (ceil(n / side) bands of
// ceil(n / side) side values), the most any side up to n needs.
size_t blockSumsScratch(int n)
{
    size_t most = 0;
    for (int side = 1; side <= n; ++side)
    {
        const size_t blocks = (size_t) ((n + side - 1) / side);
        most = std::max(most, blocks * blocks * (size_t) side);
    }
    return most;
}
} // namespace

double Membrane::gridSpacing(const MembraneSpec& s, double k, double reserve, double designReserve)
{
    const double T = s.gridTension_N_per_m > 0.0 ? s.gridTension_N_per_m : s.tension_N_per_m;
    const double sigma1 = s.gridSigma1_m2_per_s >= 0.0 ? s.gridSigma1_m2_per_s : s.sigma1_m2_per_s;
    // eq. (39): h^2 >= 2 k^2 T / rho + 8 sigma1 k
    return designedSpacing(s.gridCoarseness, k, s.gridTimeStep_s, [&](double step) {
        const double r = step != k && designReserve >= 0.0 ? designReserve : reserve;
        return std::sqrt((2.0 * step * step * T / s.density_kg_per_m2 + 8.0 * sigma1 * step) / (1.0 - r));
    });
}

Membrane::Membrane(const MembraneSpec& s, double timeStep, double reserve, double designReserve)
    : g(s.radius_m, gridSpacing(s, timeStep, reserve, designReserve)), k(timeStep), kk(timeStep * timeStep), h(g.spacing()),
      rho(s.density_kg_per_m2), maxT(s.gridTension_N_per_m > 0.0 ? s.gridTension_N_per_m : s.tension_N_per_m),
      maxSigma1(s.gridSigma1_m2_per_s >= 0.0 ? s.gridSigma1_m2_per_s : s.sigma1_m2_per_s)
{
    const int n = g.width();
    rowBegin.assign((size_t) n, 1);
    rowEnd.assign((size_t) n, 1); // empty rows: begin == end
    rowY.resize((size_t) n);
    for (int iy = 0; iy < n; ++iy)
        rowY[(size_t) iy] = g.x(iy);
    for (int iy = 1; iy < n - 1; ++iy)
    {
        int first = -1, last = -1;
        for (int ix = 1; ix < n - 1; ++ix)
            if (g.mask()[(size_t) g.index(ix, iy)] != 0.0)
            {
                if (first < 0)
                    first = ix;
                last = ix;
            }
        // a disc's row is one run of interior nodes
        if (first >= 0)
        {
            rowBegin[(size_t) iy] = first;
            rowEnd[(size_t) iy] = last + 1;
        }
    }
    single = s.precision == HeadPrecision::single_precision;
    if (single)
    {
        fNext.assign((size_t) g.numNodes(), n, 0.0f);
        fNow = fNext;
        fPrev = fNext;
        fMask.assign(g.mask().begin(), g.mask().end(), n);
    }
    else
    {
        wNext.assign((size_t) g.numNodes(), 0.0);
        wNow = wNext;
        wPrev = wNext;
    }
    // x and y times the mask, for the first moments (tiltNext) and a tilting pressure
    std::vector<double> xs((size_t) g.numNodes(), 0.0), ys = xs;
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix)
        {
            const size_t i = (size_t) g.index(ix, iy);
            xs[i] = g.mask()[i] * g.x(ix);
            ys[i] = g.mask()[i] * g.x(iy);
        }
    dRowScratch.assign(blockSumsScratch(n), 0.0);
    accScratch.assign((size_t) n * (size_t) n, 0.0); // up to n bands of n columns
    if (single)
    {
        fX.assign(xs.begin(), xs.end(), n);
        fY.assign(ys.begin(), ys.end(), n);
        fAxis.resize((size_t) n);
        for (int i = 0; i < n; ++i)
            fAxis[(size_t) i] = (float) g.x(i);
    }
    else
    {
        dX = std::move(xs);
        dY = std::move(ys);
    }
    axis.resize((size_t) n);
    for (int i = 0; i < n; ++i)
        axis[(size_t) i] = single ? (double) (float) g.x(i) : g.x(i); // x by column and y by row as fX, fY (dX, dY) hold them
    setCoefficients(s.tension_N_per_m, s.sigma0_per_s, s.sigma1_m2_per_s);
}

void Membrane::setCoefficients(double tension, double s0, double s1)
{
    T = std::clamp(tension, 0.0, maxT);
    sigma0 = std::max(0.0, s0);
    sigma1 = std::clamp(s1, 0.0, maxSigma1);
    q = 1.0 + sigma0 * k;
    const double lambda2 = kk * T / (rho * h * h);
    const double s = 2.0 * sigma1 * k / (h * h);
    // w+ = [2w - (1 - sigma0 k) w- + lambda^2 L w + s (L w - L w-)] / q, L = unscaled 5-point Laplacian
    a0 = (2.0 - 4.0 * lambda2 - 4.0 * s) / q;
    a1 = (lambda2 + s) / q;
    b0 = -(1.0 - sigma0 * k - 4.0 * s) / q;
    b1 = -s / q;
    // the float state's increment form: w+ = w + r (w - w-) + cl L w + cs L (w - w-)
    r = (float) ((1.0 - sigma0 * k) / q);
    cl = (float) (lambda2 / q);
    cs = (float) (s / q);
}

namespace
{
#define SNARESIM_KERNELS "MembraneKernels.inl"
#include "PerVectorTarget.inl"

// blockSumsAndMoments on the state in its precision, with the first moments or without.
template <class Real>
void sumsOf(bool moments, const Real* w, int n, int side, const double* xs, const double* ys, double* acc, double* out, double& sum,
            double& sx, double& sy)
{
    const auto pass =
        moments ? SNARESIM_ON_VECTOR_TARGET(blockSumsAndMoments<true, Real>) : SNARESIM_ON_VECTOR_TARGET(blockSumsAndMoments<false, Real>);
    pass(w, n, side, xs, ys, acc, out, sum, sx, sy);
}
// updateRows for a head's sums kept (Sums) or taken later, with the tilt and the block field or
// without.
template <bool Sums>
auto rowsUpdate(bool tilt, bool field)
{
    return tilt ? (field ? SNARESIM_ON_VECTOR_TARGET(updateRows<Sums, true, true>)
                         : SNARESIM_ON_VECTOR_TARGET(updateRows<Sums, true, false>))
                : (field ? SNARESIM_ON_VECTOR_TARGET(updateRows<Sums, false, true>)
                         : SNARESIM_ON_VECTOR_TARGET(updateRows<Sums, false, false>));
}
// scatterNodesKeyed on the state in its precision, with the moments' changes or without.
template <class Real>
double scatterKeyed(bool moments, Real* w, const Real* xs, const Real* ys, const int* nodes, const double* values, const int* index,
                    int count, double& dx, double& dy)
{
    const auto scatter =
        moments ? SNARESIM_ON_VECTOR_TARGET(scatterNodesKeyed<true, Real>) : SNARESIM_ON_VECTOR_TARGET(scatterNodesKeyed<false, Real>);
    return scatter(w, xs, ys, nodes, values, index, count, dx, dy);
}
} // namespace

void Membrane::setNextAt(const int* nodes, const double* values, const int* index, int count)
{
    // the running sums follow, unless they are taken later (takeSumsWithBlocks)
    const bool kept = sumSide == 0;
    double dx = 0.0, dy = 0.0;
    const double change = single
                              ? scatterKeyed(kept && momentsKept, fNext.data(), fX.data(), fY.data(), nodes, values, index, count, dx, dy)
                              : scatterKeyed(kept && momentsKept, wNext.data(), dX.data(), dY.data(), nodes, values, index, count, dx, dy);
    if (kept)
    {
        sumNext += change;
        xSumNext += dx;
        ySumNext += dy;
    }
    sumsStale = ! kept;
}

void Membrane::nextAt(const int* nodes, double* out, int count) const
{
    if (single)
        SNARESIM_ON_VECTOR_TARGET(gatherNodes(fNext.data(), nodes, out, count));
    else
        SNARESIM_ON_VECTOR_TARGET(gatherNodes(wNext.data(), nodes, out, count));
}

// Row by row over the disc's runs of interior nodes (nodes outside stay zero, the fixed rim),
// the sums taken later (takeSumsWithBlocks); or, single, the whole grid at once (updateGridFloat),
// double, the rows: both summing w^{n+1} for the cavity on the way (and its first moments, when
// kept). Built for each vector target (VectorTarget.h).
void Membrane::computeFree(double pressure) { computeFree(pressure, 0.0, 0.0); }

void Membrane::computeFree(double p0, double px, double py)
{
    const int n = g.width();
    const double gain = forceGain();
    const double push = gain * p0;                           // eq. (22) with the pressure term, force density p
    const bool tilt = momentsKept || px != 0.0 || py != 0.0; // the moments come with the tilt's variant
    const bool field = fieldSet;
    fieldSet = false; // a block pressure acts on one step
    if (field)
        expandBlockPressure();
    if (single)
    {
        sumsStale = sumSide > 0;
        if (sumsStale) // the sums taken later (takeSumsWithBlocks): the disc's rows only
        {
            const auto rows = tilt ? (field ? SNARESIM_ON_VECTOR_TARGET(updateRowsFloat<true, true>)
                                            : SNARESIM_ON_VECTOR_TARGET(updateRowsFloat<true, false>))
                                   : (field ? SNARESIM_ON_VECTOR_TARGET(updateRowsFloat<false, true>)
                                            : SNARESIM_ON_VECTOR_TARGET(updateRowsFloat<false, false>));
            rows(fNext.data(), fNow.data(), fPrev.data(), fAxis.data(), fAxis.data(), field ? fField.data() : nullptr, rowBegin.data(),
                 rowEnd.data(), n, r, cl, cs, (float) push, (float) (gain * px), (float) (gain * py));
            return;
        }
        // rows 1 .. n-2, whole: every neighbour read stays inside the padded grid, the sums on
        // the way
        const auto update = tilt ? (field ? SNARESIM_ON_VECTOR_TARGET(updateGridFloat<true, true>)
                                          : SNARESIM_ON_VECTOR_TARGET(updateGridFloat<true, false>))
                                 : (field ? SNARESIM_ON_VECTOR_TARGET(updateGridFloat<false, true>)
                                          : SNARESIM_ON_VECTOR_TARGET(updateGridFloat<false, false>));
        sumNext = update(fNext.data() + n, fNow.data() + n, fPrev.data() + n, fMask.data() + n, fX.data() + n, fY.data() + n,
                         field ? fField.data() + n : nullptr, n, n * (n - 2), r, cl, cs, (float) push, (float) (gain * px),
                         (float) (gain * py), xSumNext, ySumNext);
        return;
    }
    sumsStale = sumSide > 0; // the sums taken later (takeSumsWithBlocks)
    const auto update = sumsStale ? rowsUpdate<false>(tilt, field) : rowsUpdate<true>(tilt, field);
    double sx = 0.0, sy = 0.0;
    const double sum = update(wNext.data(), wNow.data(), wPrev.data(), field ? dField.data() : nullptr, dX.data(), rowY.data(),
                              rowBegin.data(), rowEnd.data(), n, a0, a1, b0, b1, push, gain * px, gain * py, sx, sy);
    sumNext = sum;
    xSumNext = sx;
    ySumNext = sy;
}

std::array<double, 2> Membrane::tiltNext() const
{
    takeSumsNow();
    if (momentsKept)
        return { h * h * xSumNext, h * h * ySumNext };
    const int n = g.width();
    double sx = 0.0, sy = 0.0;
    if (single)
        SNARESIM_ON_VECTOR_TARGET(firstMoments(fNext.data(), fX.data(), fY.data(), n * n, sx, sy));
    else
        SNARESIM_ON_VECTOR_TARGET(firstMoments(wNext.data(), dX.data(), dY.data(), n * n, sx, sy));
    return { h * h * sx, h * h * sy };
}

void Membrane::takeSumsWithBlocks(int side)
{
    if (side < 1)
        return;
    const int n = g.width(), blocks = (n + side - 1) / side;
    sumSide = side;
    sideSums.assign((size_t) blocks * (size_t) blocks, 0.0);
    sumsStale = true;
}

void Membrane::takeSums() const
{
    const int n = g.width();
    if (single)
        sumsOf(momentsKept, fNext.data(), n, sumSide, axis.data(), axis.data(), dRowScratch.data(), sideSums.data(), sumNext, xSumNext,
               ySumNext);
    else
        sumsOf(momentsKept, wNext.data(), n, sumSide, axis.data(), axis.data(), dRowScratch.data(), sideSums.data(), sumNext, xSumNext,
               ySumNext);
    sumsStale = false;
}

void Membrane::blockSumsNext(int side, double* out) const
{
    const int n = g.width();
    if (const double* taken = takenBlockSums(side))
    {
        std::copy(taken, taken + sideSums.size(), out);
        return;
    }
    double sum = 0.0, sx = 0.0, sy = 0.0; // the blocks' sums only
    if (single)
        sumsOf(false, fNext.data(), n, side, axis.data(), axis.data(), dRowScratch.data(), out, sum, sx, sy);
    else
        sumsOf(false, wNext.data(), n, side, axis.data(), axis.data(), dRowScratch.data(), out, sum, sx, sy);
}

void Membrane::blockAccelerationsIn(int side, int ix0, int iy0, int columns, int rows, double scale, float* out, int stride) const
{
    const int n = g.width();
    if (single)
    {
        const auto kernel = SNARESIM_ON_VECTOR_TARGET(blockSecondDifferences<float>);
        kernel(fNext.data(), fNow.data(), fPrev.data(), n, ix0, iy0, columns, rows, side, h * h, scale, accScratch.data(), out, stride);
    }
    else
    {
        const auto kernel = SNARESIM_ON_VECTOR_TARGET(blockSecondDifferences<double>);
        kernel(wNext.data(), wNow.data(), wPrev.data(), n, ix0, iy0, columns, rows, side, h * h, scale, accScratch.data(), out, stride);
    }
}

void Membrane::prepareBlocks(int side)
{
    const int n = g.width(), blocks = (n + side - 1) / side;
    if (side == blockSide)
        return;
    blockSide = side;
    columnBlock.resize((size_t) n);
    for (int ix = 0; ix < n; ++ix)
        columnBlock[(size_t) ix] = ix / side;
    blockPressure.assign((size_t) (blocks * blocks), 0.0);
    if (single)
        fField.assign((size_t) g.numNodes(), n, 0.0f);
    else
        dField.assign((size_t) g.numNodes(), 0.0);
}

void Membrane::addBlockPressure(int side, const double* perBlock)
{
    if (side != blockSide)
        return; // prepareBlocks(side) first: no allocation here
    const size_t count = blockPressure.size();
    if (fieldSet)
        for (size_t b = 0; b < count; ++b)
            blockPressure[b] += perBlock[b];
    else
        std::copy(perBlock, perBlock + count, blockPressure.begin());
    fieldSet = true;
}

void Membrane::expandBlockPressure()
{
    const int n = g.width(), side = blockSide, blocks = (n + side - 1) / side;
    const double gain = forceGain();
    const double* perBlock = blockPressure.data();
    for (int by = 0; by < blocks; ++by)
    {
        const int first = by * side, rows = std::min(n, first + side) - first;
        const size_t o = (size_t) first * (size_t) n;
        if (single)
        {
            SNARESIM_ON_VECTOR_TARGET(expandRow<float>)
            (n, columnBlock.data(), perBlock + (size_t) by * (size_t) blocks, gain, fField.data() + o);
            SNARESIM_ON_VECTOR_TARGET(copyRows(fField.data() + o, n, rows));
        }
        else
        {
            SNARESIM_ON_VECTOR_TARGET(expandRow<double>)
            (n, columnBlock.data(), perBlock + (size_t) by * (size_t) blocks, gain, dField.data() + o);
            SNARESIM_ON_VECTOR_TARGET(copyRows(dField.data() + o, n, rows));
        }
    }
}

void Membrane::applyForce(const GridDistribution& d, double force)
{
    const double c = forceGain() * force;
    for (int j = 0; j < d.size; ++j)
    {
        const int i = d.index[(size_t) j];
        const double dw = response ? c * d.g[(size_t) j] * response[i] : c * d.g[(size_t) j];
        if (single)
        {
            const float before = fNext[(size_t) i];
            fNext[(size_t) i] = (float) ((double) before + dw);
            moved(i, (double) fNext[(size_t) i] - (double) before);
        }
        else
        {
            wNext[(size_t) i] += dw;
            moved(i, dw);
        }
    }
}

double Membrane::sample(const GridDistribution& d, int level) const
{
    return withState([&](const auto& next, const auto& now, const auto& prev) {
        const auto& w = level == 0 ? next : level == 1 ? now : prev;
        double s = 0.0;
        for (int j = 0; j < d.size; ++j)
            s += d.g[(size_t) j] * (double) w[(size_t) d.index[(size_t) j]];
        return h * h * s;
    });
}

double Membrane::energy() const
{
    return withState([this](const auto& next, const auto& now, const auto&) { return energyOf(next.data(), now.data()); });
}

template <class Real>
double Membrane::energyOf(const Real* wNext, const Real* wNow) const
{
    const int n = g.width();
    double kinetic = 0.0, potential = 0.0, sigma1Term = 0.0;
    for (int iy = 0; iy < n - 1; ++iy)
        for (int ix = 0; ix < n - 1; ++ix)
        {
            const size_t i = (size_t) (iy * n + ix);
            const double now = wNow[i], next = wNext[i];
            const double v = next - now;
            kinetic += v * v;
            const double dxNow = (double) wNow[i + 1] - now, dxNext = (double) wNext[i + 1] - next;
            const double dyNow = (double) wNow[i + (size_t) n] - now, dyNext = (double) wNext[i + (size_t) n] - next;
            potential += dxNow * dxNext + dyNow * dyNext;
            const double dvx = dxNext - dxNow, dvy = dyNext - dyNow;
            sigma1Term += dvx * dvx + dvy * dvy;
        }
    // eq. (35): h^2 [rho/2 |dt+ w|^2 + T/2 (Dx+ w)(et+ Dx+ w) + ...]; the gradient sums carry
    // 1/h^2, which cancels the h^2.
    return 0.5 * rho * h * h * kinetic / kk + 0.5 * T * potential - 0.5 * rho * sigma1 * sigma1Term / k;
}

double Membrane::stepLoss() const
{
    if (sigma0 == 0.0 && sigma1 == 0.0)
        return 0.0;
    return withState([this](const auto& next, const auto&, const auto& prev) { return stepLossOf(next.data(), prev.data()); });
}

template <class Real>
double Membrane::stepLossOf(const Real* wNext, const Real* wPrev) const
{
    const int n = g.width();
    double v2 = 0.0, grad2 = 0.0;
    for (int iy = 0; iy < n - 1; ++iy)
        for (int ix = 0; ix < n - 1; ++ix)
        {
            const size_t i = (size_t) (iy * n + ix);
            const double d = (double) wNext[i] - (double) wPrev[i];
            v2 += d * d;
            const double dx = ((double) wNext[i + 1] - (double) wPrev[i + 1]) - d;
            const double dy = ((double) wNext[i + (size_t) n] - (double) wPrev[i + (size_t) n]) - d;
            grad2 += dx * dx + dy * dy;
        }
    // k q^n = k [2 rho sigma0 h^2 |dt. w|^2 + 2 rho sigma1 |grad dt. w|^2], dt. w = (w+ - w-) / 2k
    return k * (2.0 * rho * sigma0 * h * h * v2 + 2.0 * rho * sigma1 * grad2) / (4.0 * kk);
}

void Membrane::advance()
{
    std::swap(wPrev, wNow);
    std::swap(wNow, wNext);
    std::swap(fPrev, fNow);
    std::swap(fNow, fNext);
}

void Membrane::clear()
{
    sumNext = xSumNext = ySumNext = 0.0;
    sumsStale = sumSide > 0; // the blocks' sums too: taken again, of zeros
    for (auto* w : { &wNext, &wNow, &wPrev })
        std::fill(w->begin(), w->end(), 0.0);
    for (auto* w : { &fNext, &fNow, &fPrev })
        std::fill(w->begin(), w->end(), 0.0f);
}

bool Membrane::isFinite() const
{
    return withState([](const auto&, const auto& now, const auto&) {
        for (auto v : now)
            if (! std::isfinite(v))
                return false;
        return true;
    });
}

} // namespace snaresim
