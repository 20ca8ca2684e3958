#include "NearFieldCoupling.h"

#include "Bessel.h"
#include "CellShapes.h"

#include <algorithm>
#include <cmath>

namespace snaresim
{

NearFieldCoupling::Face NearFieldCoupling::makeFace(Membrane& head, int which, double cellSize, double coarseSize)
{
    Face f { &head, HeadCells(head.grid(), cellSize), 0, 0, 0, {}, {}, {}, {}, {}, {}, {}, false };
    while (f.first < air.size() && air.shape(f.first).head != which)
        ++f.first;
    while (f.first + f.count < air.size() && air.shape(f.first + f.count).head == which)
        ++f.count;
    if (f.count == 0)
        return f; // nothing to hold
    const CircularGrid& g = head.grid();
    const int n = g.width(), side = f.cells.side, cells = f.cells.cells();
    const size_t blocks = (size_t) (f.cells.blocks * f.cells.blocks);
    const double R = g.radius(), area = g.spacing() * g.spacing();
    // g x g fine cells a coarse one, numbered in order of first use
    const int group = std::max(1, (int) std::lround(coarseSize / (side * g.spacing())));
    const int across = (f.cells.blocks + group - 1) / group;
    std::vector<int> coarseOfSlot((size_t) (across * across), -1), coarseOfBlock(blocks, -1);
    f.coarseOf.assign((size_t) cells, 0);
    for (int c = 0; c < cells; ++c)
    {
        const int b = f.cells.block[(size_t) c], slot = (b / f.cells.blocks / group) * across + (b % f.cells.blocks) / group;
        if (coarseOfSlot[(size_t) slot] < 0)
            coarseOfSlot[(size_t) slot] = f.coarse++;
        f.coarseOf[(size_t) c] = coarseOfBlock[(size_t) b] = coarseOfSlot[(size_t) slot];
    }
    std::vector<int> nodesIn((size_t) f.coarse, 0);
    std::vector<double> mean((size_t) f.coarse, 0.0);
    f.shape.assign((size_t) f.count * (size_t) f.coarse, 0.0f);
    // J_m(j r / R) tabulated on the radius (linear interpolation: parts in 1e4 of the shape,
    // which the force and the coordinate share), so that no node costs a Bessel function
    constexpr int radii = 512;
    std::vector<double> radial(radii + 1), lowest(radii + 1);
    for (int s = 0; s < f.count; ++s)
    {
        const NearFieldShape& shape = air.shape(f.first + s);
        if (s == 0 || shape.m != air.shape(f.first + s - 1).m || shape.n != air.shape(f.first + s - 1).n)
        {
            const double low = shape.m < 2 ? besselZero(shape.m, 1) : 0.0;
            for (int i = 0; i <= radii; ++i)
            {
                radial[(size_t) i] = std::cyl_bessel_j((double) shape.m, shape.zero * i / radii);
                if (shape.m < 2)
                    lowest[(size_t) i] = std::cyl_bessel_j((double) shape.m, low * i / radii);
            }
        }
        std::fill(mean.begin(), mean.end(), 0.0);
        std::fill(nodesIn.begin(), nodesIn.end(), 0);
        double own = 0.0; // the shape squared over the interior nodes
        for (int iy = 0; iy < n; ++iy)
            for (int ix = 0; ix < n; ++ix)
                if (g.mask()[(size_t) g.index(ix, iy)] != 0.0)
                {
                    const double at = std::min(1.0, std::hypot(g.x(ix), g.x(iy)) / R) * radii;
                    const int i = std::min(radii - 1, (int) at);
                    auto at_ = [&](const std::vector<double>& t) { return t[(size_t) i] + (at - i) * (t[(size_t) i + 1] - t[(size_t) i]); };
                    const double v = NearFieldAir::shapeValue(shape, R, g.x(ix), g.x(iy), at_(radial), at_(lowest));
                    const int c = coarseOfBlock[(size_t) ((iy / side) * f.cells.blocks + ix / side)];
                    own += v * v;
                    mean[(size_t) c] += v;
                    ++nodesIn[(size_t) c];
                }
        double sumCells = 0.0; // each coarse cell's mean squared (as kept, in float), once per interior node of it
        float* kept = f.shape.data() + (size_t) s * (size_t) f.coarse;
        for (int c = 0; c < f.coarse; ++c)
        {
            kept[c] = (float) (mean[(size_t) c] / (double) std::max(1, nodesIn[(size_t) c]));
            sumCells += (double) nodesIn[(size_t) c] * (double) kept[c] * (double) kept[c];
        }
        air.setNorms(f.first + s, area * sumCells, area * own);
    }
    // each coarse cell's blocks in a run: its sum without a read-modify-write per fine cell
    f.firstBlock.assign((size_t) f.coarse + 1, 0);
    for (int c = 0; c < cells; ++c)
        ++f.firstBlock[(size_t) f.coarseOf[(size_t) c] + 1];
    for (int c = 0; c < f.coarse; ++c)
        f.firstBlock[(size_t) c + 1] += f.firstBlock[(size_t) c];
    f.fineBlocks.assign((size_t) cells, 0);
    std::vector<int> filled(f.firstBlock.begin(), f.firstBlock.end() - 1);
    for (int c = 0; c < cells; ++c)
        f.fineBlocks[(size_t) filled[(size_t) f.coarseOf[(size_t) c]]++] = f.cells.block[(size_t) c];
    f.blockSum.assign(blocks, 0.0);
    f.blockPressure.assign(blocks, 0.0);
    f.cellValue.assign((size_t) f.coarse, 0.0);
    head.prepareBlocks(side);
    return f;
}

NearFieldCoupling::NearFieldCoupling(Membrane& batter, Membrane& carry, NearFieldAir& nearField, double cellSize, double coarseSize)
    : air(nearField), faces { makeFace(batter, 0, cellSize, coarseSize), makeFace(carry, 1, cellSize, coarseSize) }
{}

void NearFieldCoupling::applyPressures() noexcept
{
    for (Face& f : faces)
    {
        if (f.count == 0)
            continue;
        // P^n per unit of each shape (an upward push on either head: each channel is one head's)
        combineShapes(f.count, f.coarse, air.pressures() + f.first, f.shape.data(), f.cellValue.data());
        for (int c = 0; c < f.cells.cells(); ++c)
            f.blockPressure[(size_t) f.cells.block[(size_t) c]] = f.cellValue[(size_t) f.coarseOf[(size_t) c]];
        f.head->addBlockPressure(f.cells.side, f.blockPressure.data());
    }
}

void NearFieldCoupling::step(std::array<const double*, 2> sums) noexcept
{
    double* q = air.coordinatesNext();
    for (int fi = 0; fi < 2; ++fi)
    {
        Face& f = faces[(size_t) fi];
        f.ownSums = false;
        if (f.count == 0)
            continue;
        const double* blockSum = sums[(size_t) fi];
        if (blockSum == nullptr)
        {
            f.head->blockSumsNext(f.cells.side, f.blockSum.data());
            f.ownSums = true;
            blockSum = f.blockSum.data();
        }
        for (int c = 0; c < f.coarse; ++c)
        {
            double sum = 0.0;
            for (int i = f.firstBlock[(size_t) c]; i < f.firstBlock[(size_t) c + 1]; ++i)
                sum += blockSum[f.fineBlocks[(size_t) i]];
            f.cellValue[(size_t) c] = sum;
        }
        const double area = f.head->grid().spacing() * f.head->grid().spacing();
        projectShapes(f.count, f.coarse, f.shape.data(), f.cellValue.data(), area, q + f.first);
    }
}

} // namespace snaresim
