#include "CavityModesCoupling.h"

#include "CellShapes.h"

#include <algorithm>

namespace snaresim
{

CavityModesCoupling::Face CavityModesCoupling::makeFace(Membrane& head, double sign, double cellSize) const
{
    Face f { &head, HeadCells(head.grid(), cellSize), sign, {}, {}, {}, {} };
    if (! air.active())
        return f; // nothing to hold
    const double R = head.grid().radius();
    const size_t blocks = (size_t) (f.cells.blocks * f.cells.blocks);
    f.shape.assign((size_t) air.shapes() * blocks, 0.0);
    for (int s = 0; s < air.shapes(); ++s)
    {
        int i = 0;
        while (air.mode(i).shape != s)
            ++i;
        const CavityMode mode = air.mode(i);
        const std::vector<double> mean = f.cells.meanOver([&](double x, double y) { return CavityModes::faceShape(mode, R, x, y); });
        for (int c = 0; c < f.cells.cells(); ++c)
            f.shape[(size_t) s * blocks + (size_t) f.cells.block[(size_t) c]] = mean[(size_t) c];
    }
    f.blockSum.assign(blocks, 0.0);
    f.perShape.assign((size_t) air.shapes(), 0.0);
    f.pressure = f.blockSum;
    head.prepareBlocks(f.cells.side);
    return f;
}

CavityModesCoupling::CavityModesCoupling(Membrane& batter, Membrane& carry, CavityModes& modes, double cellSize)
    : air(modes), faces { makeFace(batter, 1.0, cellSize), makeFace(carry, -1.0, cellSize) }
{}

void CavityModesCoupling::applyPressures() noexcept
{
    if (! air.active())
        return;
    for (int fi = 0; fi < 2; ++fi)
    {
        Face& f = faces[(size_t) fi];
        std::fill(f.perShape.begin(), f.perShape.end(), 0.0);
        for (int i = 0; i < air.size(); ++i) // on the carry head, Phi is (-1)^p times the face shape
            f.perShape[(size_t) air.mode(i).shape] += (fi == 1 && (air.mode(i).p & 1) ? -f.sign : f.sign) * air.pressure(i);
        combineShapes(air.shapes(), (int) f.pressure.size(), f.perShape.data(), f.shape.data(), f.pressure.data());
        f.head->addBlockPressure(f.cells.side, f.pressure.data());
    }
}

void CavityModesCoupling::step() noexcept
{
    if (! air.active())
        return;
    for (Face& f : faces)
    {
        f.head->blockSumsNext(f.cells.side, f.blockSum.data());
        const double area = f.head->grid().spacing() * f.head->grid().spacing();
        projectShapes(air.shapes(), (int) f.blockSum.size(), f.shape.data(), f.blockSum.data(), area, f.perShape.data());
    }
    double* q = air.coordinatesNext();
    for (int i = 0; i < air.size(); ++i)
    {
        const size_t s = (size_t) air.mode(i).shape;
        q[i] = faces[0].perShape[s] - (air.mode(i).p & 1 ? -1.0 : 1.0) * faces[1].perShape[s];
    }
}

} // namespace snaresim
