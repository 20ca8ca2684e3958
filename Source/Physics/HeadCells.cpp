#include "HeadCells.h"

#include <algorithm>
#include <cmath>

namespace snaresim
{

bool interiorCentre(const CircularGrid& g, int ix0, int ix1, int iy0, int iy1, double& x, double& y)
{
    double sx = 0.0, sy = 0.0;
    int count = 0;
    for (int iy = iy0; iy < iy1; ++iy)
        for (int ix = ix0; ix < ix1; ++ix)
            if (g.mask()[(size_t) g.index(ix, iy)] > 0.5)
            {
                sx += g.x(ix);
                sy += g.x(iy);
                ++count;
            }
    if (count == 0)
        return false;
    x = sx / count;
    y = sy / count;
    return true;
}

HeadCells::HeadCells(const CircularGrid& g, double cellSize) : grid(&g), side(std::max(1, (int) std::lround(cellSize / g.spacing())))
{
    const int n = g.width();
    blocks = (n + side - 1) / side;
    for (int b = 0; b < blocks * blocks; ++b)
    {
        const int bx = b % blocks, by = b / blocks;
        double x = 0.0, y = 0.0;
        if (! interiorCentre(g, bx * side, std::min(n, (bx + 1) * side), by * side, std::min(n, (by + 1) * side), x, y))
            continue;
        block.push_back(b);
        cx.push_back(x);
        cy.push_back(y);
    }
}

std::vector<double> HeadCells::meanOver(const std::function<double(double, double)>& f) const
{
    const CircularGrid& g = *grid;
    const int n = g.width();
    std::vector<double> out;
    out.reserve(block.size());
    for (const int b : block)
    {
        const int bx = b % blocks, by = b / blocks;
        double sum = 0.0;
        int count = 0;
        for (int iy = by * side; iy < std::min(n, (by + 1) * side); ++iy)
            for (int ix = bx * side; ix < std::min(n, (bx + 1) * side); ++ix)
                if (g.mask()[(size_t) g.index(ix, iy)] > 0.5)
                {
                    sum += f(g.x(ix), g.x(iy));
                    ++count;
                }
        out.push_back(sum / count);
    }
    return out;
}

} // namespace snaresim
