#pragma once
// Coupling between the heads and the near field's channels (NearFieldAir.h): each head's cells
// (HeadCells; the microphones' and the cavity's modes' cells, whose sums are taken once a step for
// all) are grouped g x g into coarser ones of about OutsideAirSpec::nearFieldCellSize_m, and a
// shape is its mean over each coarse cell's interior nodes. Before the heads' free updates the
// channels' pressures at time n push each coarse cell's nodes (Membrane::addBlockPressure,
// explicit); once every force is in, the cells' volumes give the channels' coordinates
// q^{n+1} = h^2 sum_cells phi_cell sum_cell w.
// Force and coordinate are each other's transposes, so the pressures' work on the heads is
// exactly the channels' energy change: it stores no energy and removes none.

#include "HeadCells.h"
#include "Membrane.h"
#include "NearFieldAir.h"

#include <array>
#include <vector>

namespace snaresim
{

class NearFieldCoupling
{
public:
    // Sets every shape's norms on its head (NearFieldAir::setNorms).
    // cellSize_m: the fine cells' (the microphones'); coarseSize_m: the coarse cells' (at least one fine cell).
    NearFieldCoupling(Membrane& batterHead, Membrane& carryHead, NearFieldAir& air, double cellSize_m, double coarseSize_m);

    // Before the heads' free updates (eq. 22-23): the channels' pressures at n, for them.
    void applyPressures() noexcept;
    // After every force on the heads is in: q^{n+1}. sums: a head's Membrane::blockSumsNext at
    // its cells' side for this step, if a coupling already has them, else nullptr.
    void step(std::array<const double*, 2> sums = {}) noexcept;

    int cellSide(int head) const { return faces[(size_t) head].cells.side; }
    // This step's block sums of a head (0 batter, 1 carry) when taken here at this side, else nullptr.
    const double* blockSums(int head, int side) const
    {
        const Face& f = faces[(size_t) head];
        return f.ownSums && f.cells.side == side ? f.blockSum.data() : nullptr;
    }

    double energy() const { return 0.0; }
    double stepLoss() const { return 0.0; }

private:
    struct Face
    {
        Membrane* head;
        HeadCells cells;
        int first = 0, count = 0;    // the head's shapes in the air's list
        int coarse = 0;              // coarse cells
        std::vector<int> coarseOf;   // fine cell -> coarse cell (the pressures: faster than the runs below)
        std::vector<int> firstBlock; // coarse cell c's blocks: fineBlocks[firstBlock[c] .. firstBlock[c + 1])
        std::vector<int> fineBlocks;
        std::vector<float> shape;          // the shapes' coarse cell means, shape-major (CellShapes.h)
        std::vector<double> blockSum;      // Membrane::blockSumsNext
        std::vector<double> cellValue;     // per coarse cell: its sum, or its pressure
        std::vector<double> blockPressure; // per block (0 where no cell)
        bool ownSums = false;              // blockSum holds this step's sums
    };
    Face makeFace(Membrane& head, int which, double cellSize_m, double coarseSize_m);

    NearFieldAir& air;
    std::array<Face, 2> faces;
};

} // namespace snaresim
