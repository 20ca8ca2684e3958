#include "PressureMicrophones.h"

#include "HeadCells.h"
#include "Membrane.h"
#include "VectorTarget.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

namespace snaresim
{

namespace
{
double distance(double x, double y, double z, const AirPoint& p)
{
    return std::sqrt((p.x_m - x) * (p.x_m - x) + (p.y_m - y) * (p.y_m - y) + (p.z_m - z) * (p.z_m - z));
}

// The mean of 1/R over a square cell of side w centred at (x, y, z), R to p: 1/r from the
// centre when the cell is small beside r, else over a 6 x 6 raster.
double meanInverseOver(double x, double y, double z, double w, double r, const AirPoint& p)
{
    if (r >= 2.0 * w)
        return 1.0 / r;
    double sum = 0.0;
    for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b)
            sum += 1.0 / std::max(1e-4, distance(x + w * ((a + 0.5) / 6.0 - 0.5), y + w * ((b + 0.5) / 6.0 - 0.5), z, p));
    return sum / 36.0;
}

#define SNARESIM_KERNELS "PressureMicrophonesKernels.inl"
#include "PerVectorTarget.inl"

// Kirchhoff's obliquity (1 + cos theta) / 2 blended in by `far` (0 near the head: 1).
double obliquityAt(double r, double far, double z, const AirPoint& p) { return 1.0 - far * 0.5 * (1.0 - std::abs(p.z_m - z) / r); }
} // namespace

PressureMicrophones::PressureMicrophones(const MicSpec& spec, const CavitySpec& air, double sampleRate_Hz, const Membrane& batter,
                                         const Membrane& carry)
    : k(1.0 / sampleRate_Hz), radius(batter.grid().radius()), depth(air.shellDepth_m), nearWidths(2.0), rho(air.airDensity_kg_per_m3),
      c(air.soundSpeed_m_per_s), alpha(1.0 - std::exp(-c / radius / sampleRate_Hz))
{
    const double H = air.shellDepth_m;
    const Membrane* membranes[2] = { &batter, &carry };
    for (int hi = 0; hi < 2; ++hi)
    {
        Head& h = heads[(size_t) hi];
        const CircularGrid& g = membranes[hi]->grid();
        h.z = hi == 0 ? 0.5 * H : -0.5 * H;
        h.grid = &g;
        h.sign = hi == 0 ? 1.0 : -1.0;
        const HeadCells cells(g, spec.cellSize_m);
        h.side = cells.side;
        const int blocks = cells.blocks;
        h.width_m = h.side * g.spacing();
        h.nodeArea = g.spacing() * g.spacing();
        h.blockSum.assign((size_t) (blocks * blocks), 0.0);
        h.block.assign(cells.block.begin(), cells.block.end());
        h.cx.assign(cells.cx.begin(), cells.cx.end());
        h.cy.assign(cells.cy.begin(), cells.cy.end());
        h.cells = (int) h.block.size();
        h.blocks = blocks;
        h.fine = std::clamp((int) std::lround(spec.fineCellSize_m / g.spacing()), 1, h.side);
        h.vNow.assign((size_t) h.cells, 0.0);
        h.vPrev = h.vNow;
        h.rowBegin = hi == 0 ? 0 : heads[0].cells;
    }
    constexpr double deepest = 1.0; // the deepest shell a drum is built with (DrumConfig::validate), for a depth changed later
    const double farthest = spec.reach_m + std::hypot(radius, 0.5 * deepest) + deepest;
    const int longest = (int) std::ceil(farthest / (c * k)) + 2;
    rows = 1;
    while (rows < longest)
        rows *= 2;
    const size_t most = (size_t) std::max(heads[0].cells, heads[1].cells);
    // the most fine cells a microphone can hear: a square of 2 nearWidths + 2 coarse cells
    size_t nearMost = 0;
    for (const Head& h : heads)
    {
        const int span = ((int) (2.0 * nearWidths) + 2) * h.side / h.fine + 1;
        nearMost = std::max(nearMost, (size_t) span * (size_t) span);
    }
    size_t sources = (size_t) (heads[0].cells + heads[1].cells);
    for (Listener& l : mics)
    {
        l.fineBegin = (int) sources;
        sources += nearMost;
        l.fineCapacity = (int) nearMost;
        l.cell.resize(most + nearMost);
        l.now.resize(most + nearMost);
        l.next.resize(most + nearMost);
        l.taps.resize(most + nearMost);
        l.tapCell.resize(most + nearMost);
        l.runEnd.resize((size_t) rows);
        l.count.resize((size_t) rows);
        l.direct.assign((size_t) rows * kLanes, 0.0f);
        l.directNear = l.direct;
        l.around.assign((size_t) rows, 0.0);
    }
    sourceRows.assign(sources * kLanes, 0.0f);
    // A microphone's whole delays to its facing head's cells span at most the head's diameter
    // (two cells' distances to it differ by no more than the cells' distance) and two more.
    const int widest = std::min(rows, (int) std::ceil(2.0 * radius / (c * k)) + 2);
    tileNow.assign((size_t) widest * kLanes * kLanes, 0.0f);
    tileNext = tileNow;
    setPositions(spec, H);
}

PressureMicrophones::Tap PressureMicrophones::tapAt(double r, double gain) const noexcept
{
    const double t = std::clamp(r / (c * k), 0.0, rows - 2.0);
    const int d = (int) t;
    return Tap { d, t - d, gain };
}

void PressureMicrophones::place(Listener& l, const AirPoint& p) noexcept
{
    l.facing = p.z_m >= 0.0 ? 0 : 1;
    const Head& f = heads[(size_t) l.facing];
    const double w = f.width_m;
    // Near the head (closer to its centre than its radius) the head is its own baffle; far from
    // it the drum is a finite body, whose faces radiate with Kirchhoff's obliquity (1 + cos)/2.
    const double far = std::clamp(distance(0.0, 0.0, f.z, p) / radius - 1.0, 0.0, 1.0);
    // The near rectangle: the coarse blocks within nearWidths of the foot, when the microphone is
    // within three cells of the head's plane.
    const CircularGrid& g = *f.grid;
    const double h = g.spacing();
    int bx0 = 1, bx1 = 0, by0 = 1, by1 = 0; // empty
    if (std::abs(p.z_m - f.z) < 3.0 * w)
    {
        const double fx = p.x_m / h - g.x(0) / h, fy = p.y_m / h - g.x(0) / h; // the foot in node units
        const double reach = nearWidths * f.side;
        bx0 = std::max(0, (int) std::floor((fx - reach) / f.side));
        bx1 = std::min(f.blocks - 1, (int) std::floor((fx + reach) / f.side));
        by0 = std::max(0, (int) std::floor((fy - reach) / f.side));
        by1 = std::min(f.blocks - 1, (int) std::floor((fy + reach) / f.side));
    }
    l.nearX = bx0 * f.side;
    l.nearY = by0 * f.side;
    l.nearColumns = bx1 >= bx0 ? std::min(g.width(), (bx1 + 1) * f.side) - l.nearX : 0;
    l.nearRows = by1 >= by0 ? std::min(g.width(), (by1 + 1) * f.side) - l.nearY : 0;
    const int fineColumns = (l.nearColumns + f.fine - 1) / f.fine, fineRows = (l.nearRows + f.fine - 1) / f.fine;
    l.nearCells = fineColumns * fineRows;
    if (l.nearCells > l.fineCapacity) // cannot happen (the capacity is the largest square)
        l.nearCells = 0, l.nearColumns = l.nearRows = 0, bx1 = bx0 - 1;
    int lo = rows, hi = 0;
    int cellTaps = 0;
    auto add = [&](const Tap& t, int source) {
        l.taps[(size_t) cellTaps] = t;
        l.tapCell[(size_t) cellTaps] = source;
        ++cellTaps;
        lo = std::min(lo, t.delay);
        hi = std::max(hi, t.delay);
    };
    const double fw = f.fine * h;
    for (int cy = 0; cy < fineRows; ++cy)
        for (int cx = 0; cx < fineColumns; ++cx)
        {
            double x = 0.0, y = 0.0;
            if (! interiorCentre(g, l.nearX + cx * f.fine, std::min(l.nearX + l.nearColumns, l.nearX + (cx + 1) * f.fine),
                                 l.nearY + cy * f.fine, std::min(l.nearY + l.nearRows, l.nearY + (cy + 1) * f.fine), x, y))
                continue;
            const double r = std::max(1e-3, distance(x, y, f.z, p));
            add(tapAt(r, rho / (2.0 * std::numbers::pi) * meanInverseOver(x, y, f.z, fw, r, p) * obliquityAt(r, far, f.z, p) * f.sign),
                l.fineBegin + cy * fineColumns + cx);
        }

    for (int j = 0; j < f.cells; ++j)
    {
        const int bx = f.block[(size_t) j] % f.blocks, by = f.block[(size_t) j] / f.blocks;
        if (bx >= bx0 && bx <= bx1 && by >= by0 && by <= by1)
            continue; // heard in fine cells
        const double cx = f.cx[(size_t) j], cy = f.cy[(size_t) j];
        const double r = std::max(1e-3, distance(cx, cy, f.z, p));
        add(tapAt(r, rho / (2.0 * std::numbers::pi) * meanInverseOver(cx, cy, f.z, w, r, p) * obliquityAt(r, far, f.z, p)), f.rowBegin + j);
    }
    // counting sort of the taps by their whole delays
    l.firstDelay = cellTaps > 0 ? lo : 0;
    l.delays = cellTaps > 0 ? hi - lo + 1 : 0;
    std::fill(l.count.begin(), l.count.begin() + l.delays, 0);
    for (int j = 0; j < cellTaps; ++j)
        ++l.count[(size_t) (l.taps[(size_t) j].delay - lo)];
    int end = 0;
    for (int d = 0; d < l.delays; ++d)
    {
        const int begin = end;
        end += l.count[(size_t) d];
        l.runEnd[(size_t) d] = end;
        l.count[(size_t) d] = begin; // the run's next free slot
    }
    l.delays = std::min(l.delays, (int) (tileNow.size() / (kLanes * kLanes))); // cannot bind (the tiles' length, above)
    l.nearRuns = std::clamp(kFar - l.firstDelay, 0, l.delays);
    for (int j = 0; j < cellTaps; ++j)
    {
        const Tap& t = l.taps[(size_t) j];
        const int slot = l.count[(size_t) (t.delay - lo)]++;
        l.cell[(size_t) slot] = l.tapCell[(size_t) j];
        l.now[(size_t) slot] = (float) (t.gain * (1.0 - t.frac));
        l.next[(size_t) slot] = (float) (t.gain * t.frac);
    }

    // The whole-head terms come from the rim (the edge the baffle lacks): the mean of 1/d over
    // its points, d from the facing head's rim to the microphone, plus the shell's depth for the
    // other head's sound, which comes round the shell.
    constexpr int rimPoints = 32;
    double inverse = 0.0, inverseAround = 0.0, mean = 0.0;
    for (int j = 0; j < rimPoints; ++j)
    {
        const double phi = 2.0 * std::numbers::pi * (j + 0.5) / rimPoints;
        const double d = std::max(1e-3, distance(radius * std::cos(phi), radius * std::sin(phi), f.z, p));
        inverse += 1.0 / d;
        inverseAround += 1.0 / (d + depth);
        mean += d;
    }
    inverse /= rimPoints;
    inverseAround /= rimPoints;
    mean /= rimPoints;
    l.facingWhole = tapAt(mean, -rho / (4.0 * std::numbers::pi) * inverse);
    l.otherWhole = tapAt(mean + depth, rho / (4.0 * std::numbers::pi) * inverseAround);
}

void PressureMicrophones::setPositions(const MicSpec& m, double shellDepth) noexcept
{
    sumBlock(); // the steps heard so far with the taps they were heard with
    depth = shellDepth;
    heads[0].z = 0.5 * shellDepth;
    heads[1].z = -0.5 * shellDepth;
    place(mics[top], m.top);
    place(mics[bottom], m.bottom);
    place(mics[room], m.room);
    beginBlocks();
}

void PressureMicrophones::setLongestBlock(int steps) noexcept
{
    sumBlock();
    longestBlock = std::clamp(steps, 1, kLanes);
    beginBlocks();
}

void PressureMicrophones::beginBlocks() noexcept
{
    int shortestNear = kFar, shortestFar = rows;
    for (const Listener& l : mics)
    {
        if (l.nearRuns > 0)
            shortestNear = std::min(shortestNear, l.firstDelay);
        if (l.delays > l.nearRuns)
            shortestFar = std::min(shortestFar, l.firstDelay + l.nearRuns);
    }
    span = std::clamp(shortestFar + 1, 1, longestBlock);
    nearSpan = std::clamp(shortestNear + 1, 1, span);
    filled = 0;
    nearDone = 0;
}

void PressureMicrophones::addRuns(Listener& l, int first, int last, int from, AlignedVector<float>& ring) noexcept
{
    SNARESIM_ON_VECTOR_TARGET(sumTapBlock<kLanes>)
    (first, last, l.runEnd.data(), l.cell.data(), l.now.data(), l.next.data(), sourceRows.data(), tileNow.data(), tileNext.data());
    SNARESIM_ON_VECTOR_TARGET(addTapTiles<kLanes>)
    (last - first, from, filled, tileNow.data(), tileNext.data(), ring.data(), (size_t) blockSlot + (size_t) (l.firstDelay + first),
     (size_t) rows - 1);
}

void PressureMicrophones::sumNear() noexcept
{
    if (filled > nearDone)
        for (Listener& l : mics)
            if (l.nearRuns > 0)
                addRuns(l, 0, l.nearRuns, nearDone, l.directNear);
    nearDone = filled;
}

void PressureMicrophones::sumBlock() noexcept
{
    sumNear();
    if (filled > 0)
        for (Listener& l : mics) // the rows' steps from `filled` on are not added
            if (l.delays > l.nearRuns)
                addRuns(l, l.nearRuns, l.delays, 0, l.direct);
    filled = 0;
    nearDone = 0;
}

void PressureMicrophones::push(AlignedVector<double>& ring, const Tap& t, double value) const noexcept
{
    const size_t mask = (size_t) rows - 1;
    ring[((size_t) pos + (size_t) t.delay) & mask] += t.gain * (1.0 - t.frac) * value;
    ring[((size_t) pos + (size_t) t.delay + 1) & mask] += t.gain * t.frac * value;
}

void PressureMicrophones::listen(const Membrane& batter, const Membrane& carry, std::array<const double*, 2> sums) noexcept
{
    // this step's column of the sources' rows: the heads' cells, then the fine cells near the
    // microphones
    if (filled == 0)
        blockSlot = pos;
    float* column = sourceRows.data() + filled;
    const Membrane* membranes[2] = { &batter, &carry };
    const double inverseKk = 1.0 / (k * k);
    for (int hi = 0; hi < 2; ++hi)
    {
        Head& h = heads[(size_t) hi];
        const double* blockSum = sums[(size_t) hi] != nullptr ? sums[(size_t) hi] : membranes[hi]->takenBlockSums(h.side);
        if (blockSum == nullptr)
        {
            membranes[hi]->blockSumsNext(h.side, h.blockSum.data()); // volumes / h^2
            blockSum = h.blockSum.data();
        }
        h.whole =
            SNARESIM_ON_VECTOR_TARGET(cellAccelerations<kLanes>)(h.cells, h.block.data(), blockSum, h.sign * h.nodeArea, inverseKk,
                                                                 h.vNow.data(), h.vPrev.data(), column + (size_t) h.rowBegin * kLanes);
    }
    for (Listener& l : mics)
        if (l.nearCells > 0)
        {
            const Head& f = heads[(size_t) l.facing];
            membranes[l.facing]->blockAccelerationsIn(f.fine, l.nearX, l.nearY, l.nearColumns, l.nearRows, inverseKk,
                                                      column + (size_t) l.fineBegin * kLanes, kLanes);
        }
    if (++filled == span)
        sumBlock();
    else if (filled - nearDone == nearSpan)
        sumNear();
    const size_t mask = (size_t) rows - 1;
    for (int m = 0; m < numMics; ++m)
    {
        Listener& l = mics[(size_t) m];
        push(l.around, l.facingWhole, heads[(size_t) l.facing].whole);
        push(l.around, l.otherWhole, heads[(size_t) (1 - l.facing)].whole);
        const size_t here = (size_t) pos & mask;
        float* lanes = l.direct.data() + here * kLanes;
        float* nearLanes = l.directNear.data() + here * kLanes;
        double p = 0.0;
        for (int j = 0; j < kLanes; ++j)
            p += (double) lanes[j];
        for (int j = 0; j < kLanes; ++j)
            p += (double) nearLanes[j];
        std::fill(lanes, lanes + kLanes, 0.0f);
        std::fill(nearLanes, nearLanes + kLanes, 0.0f);
        const double x = l.around[here];
        l.around[here] = 0.0;
        l.lowPass += alpha * (x - l.lowPass);
        out[(size_t) m] = p + l.lowPass;
    }
    pos = (pos + 1) & (rows - 1);
}

void PressureMicrophones::clear() noexcept
{
    for (Head& h : heads)
    {
        std::fill(h.vNow.begin(), h.vNow.end(), 0.0);
        std::fill(h.vPrev.begin(), h.vPrev.end(), 0.0);
        h.whole = 0.0;
    }
    for (Listener& l : mics)
    {
        std::fill(l.direct.begin(), l.direct.end(), 0.0f);
        std::fill(l.directNear.begin(), l.directNear.end(), 0.0f);
        std::fill(l.around.begin(), l.around.end(), 0.0);
        l.lowPass = 0.0;
    }
    filled = 0;
    nearDone = 0;
    out.fill(0.0);
}

} // namespace snaresim
