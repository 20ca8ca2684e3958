#pragma once
// A head's grid cut into square cells of side x side nodes (block (bx, by) holds the nodes with
// ix / side == bx, iy / side == by, as Membrane::blockSumsNext sums them): the blocks that hold
// interior nodes, their centres and the mean of a function over each one's interior nodes. The
// pressure microphones hear the heads through these cells, and the cavity's modes act on them.

#include "CircularGrid.h"

#include <functional>
#include <vector>

namespace snaresim
{

// The centre of the interior nodes of columns [ix0, ix1) and rows [iy0, iy1) of g; false if none.
bool interiorCentre(const CircularGrid& g, int ix0, int ix1, int iy0, int iy1, double& x, double& y);

struct HeadCells
{
    // Cells of about cellSize_m (a whole number of nodes, at least one) on grid g.
    HeadCells(const CircularGrid& g, double cellSize_m);

    // The mean of f(x, y) over each cell's interior nodes, in cell order.
    std::vector<double> meanOver(const std::function<double(double, double)>& f) const;

    const CircularGrid* grid;
    int side = 1;               // cell side in grid nodes
    int blocks = 0;             // blocks per row of the grid
    std::vector<int> block;     // cell -> block
    std::vector<double> cx, cy; // cell centres: the mean of their interior nodes (m)
    int cells() const { return (int) block.size(); }
};

} // namespace snaresim
