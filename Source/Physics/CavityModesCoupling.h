#pragma once
// Coupling between the heads and the cavity's modes (CavityModes.h): each head is cut into
// square cells (HeadCells; the microphones' cells, whose sums are taken once a step for both);
// a mode's shape is its mean over each cell's nodes. After the heads'
// free updates the modes' pressures at time n push each cell's nodes (explicit, like the uniform
// pressure of CavityCoupling); once every force is in, the cells' volumes give the modes'
// coordinates q^{n+1} = sum_cells Phi_b V_b - sum_cells Phi_c V_c. Force and coordinate are each
// other's transposes, so the pressures' work on the heads is exactly the modes' energy change:
// it stores no energy and removes none.

#include "CavityModes.h"
#include "HeadCells.h"
#include "Membrane.h"

#include <array>
#include <vector>

namespace snaresim
{

class CavityModesCoupling
{
public:
    CavityModesCoupling(Membrane& batterHead, Membrane& carryHead, CavityModes& modes, double cellSize_m);

    // Before the heads' free updates (eq. 22-23): the modes' pressures at n, for them.
    void applyPressures() noexcept;
    // After every force on the heads is in: q^{n+1}.
    void step() noexcept;

    // This step's Membrane::blockSumsNext of a head (0 batter, 1 carry) when taken at this side
    // (the microphones' cells are the same), else nullptr.
    const double* blockSums(int head, int side) const
    {
        return air.active() && faces[(size_t) head].cells.side == side ? faces[(size_t) head].blockSum.data() : nullptr;
    }

    double energy() const { return 0.0; }
    double stepLoss() const { return 0.0; }

private:
    struct Face
    {
        Membrane* head;
        HeadCells cells;
        double sign;                  // +1 batter; -1 carry head (the force's sense, times (-1)^p per mode)
        std::vector<double> shape;    // the face shapes' cell means per block (0 where no cell), shape-major
        std::vector<double> blockSum; // Membrane::blockSumsNext
        std::vector<double> perShape; // per shape: its modes' pressures summed, or its projection
        std::vector<double> pressure; // per block (0 where no cell)
    };
    Face makeFace(Membrane& head, double sign, double cellSize_m) const;

    CavityModes& air;
    std::array<Face, 2> faces;
};

} // namespace snaresim
