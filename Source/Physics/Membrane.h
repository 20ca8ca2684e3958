#pragma once
// A head: the lossy 2D wave equation (eq. 2-4) on a clipped square grid, scheme (22)/(24):
//   rho dtt w = T D w - 2 rho sigma0 dt. w + 2 rho sigma1 dt- D w + forces.
// Its numerical energy (eq. 35) gains the term -(rho sigma1 k / 2) |grad dt+ w|^2 from the
// backward-difference loss; with it, h^{n+1/2} - h^{n-1/2} = -k q^n exactly, q^n >= 0.
// A component: its state, free update (computeFree), energy() and stepLoss(); the couplings'
// forces come in through applyForce / setNextAt, the cavity's pressure through computeFree.
// The state is double, or float (MembraneSpec::precision): the free update then runs twice
// as many nodes per vector and the energy identity holds to float round-off; everything read
// out (nextAt, samples, energy) is double either way.

#include "CacheAligned.h"
#include "CircularGrid.h"
#include "MembraneSpec.h"

#include <array>
#include <vector>

namespace snaresim
{

class Membrane
{
public:
    // kineticReserve: share of the kinetic energy kept for an explicit coupling (the cavity) at
    // this step; designReserve: that share at the grid's design step (MembraneSpec::
    // gridTimeStep_s), negative: the same.
    Membrane(const MembraneSpec& spec, double timeStep_s, double kineticReserve = 0.0, double designReserve = -1.0);

    // Grid spacing from the stability bound eq. (39), for the design tension and sigma1,
    // widened by 1/sqrt(1 - kineticReserve), times the coarseness factor: the bound at the
    // design step with its reserve, or at this step where that is wider (GridDesign.h).
    static double gridSpacing(const MembraneSpec& spec, double timeStep_s, double kineticReserve = 0.0, double designReserve = -1.0);

    const CircularGrid& grid() const { return g; }
    double density() const { return rho; }
    double tension() const { return T; }
    double timeStep() const { return k; }

    // Change tension and losses without a new grid (values above the grid's design are clamped).
    void setCoefficients(double tension_N_per_m, double sigma0_per_s, double sigma1_m2_per_s);

    // w^{n+1} from w^n, w^{n-1} with no contact force (eq. 22), with a uniform pressure p
    // (Pa, pushing up) from the cavity acting at time n (and addBlockPressure's, if any).
    void computeFree(double pressure_Pa = 0.0);
    // The same with a pressure p0 + px x + py y (Pa; px, py in Pa/m, x and y from the head's
    // centre): the cavity's and the outside air's (OutsideAirCoupling.h).
    void computeFree(double p0_Pa, double px_Pa_per_m, double py_Pa_per_m);
    // h^2 sum(x w), h^2 sum(y w) at n+1: the head's first moments (m^4); a pass over the grid
    // unless they are kept.
    std::array<double, 2> tiltNext() const;
    // Keep the first moments as the sum is kept: summed in computeFree, moved by every force
    // update; for a coupling that reads them every step (OutsideAirCoupling).
    void keepMoments() { momentsKept = true; }
    // The sum and first moments at n+1 not kept by computeFree and the force updates but taken in
    // one pass once the step's forces are in (the first read of the volume, the moments or the
    // block sums of this side after a change), a double sum of the state as it is, with the
    // blocks' sums of this side on the way (takenBlockSums).
    void takeSumsWithBlocks(int side);
    // Take those sums now, once every force of the step is in (while the state is in cache).
    void takeSumsNow() const
    {
        if (sumsStale)
            takeSums();
    }
    // blockSumsNext's sums at this side when they come with the taken sums, else nullptr.
    const double* takenBlockSums(int side) const
    {
        if (side != sumSide)
            return nullptr;
        takeSumsNow();
        return sideSums.data();
    }
    // sum(w^{n+1}) over square blocks of side x side nodes (block (bx, by) holds the nodes with
    // ix / side == bx, iy / side == by) into out[by * blocks + bx], blocks = ceil(N / side), in
    // double: h^2 times it is a block's volume. A pass over the grid: the pressure microphones'
    // cells.
    void blockSumsNext(int side, double* out) const;
    // h^2 sum(w^{n+1} - 2 w^n + w^{n-1}) over the blocks of side x side nodes of the rectangle
    // of columns x rows nodes from node (ix0, iy0) (inside the grid), times scale, in float into
    // every stride-th float of out, block row by block row (a microphone's rows of sources).
    void blockAccelerationsIn(int side, int ix0, int iy0, int columns, int rows, double scale, float* out, int stride) const;
    // A pressure (Pa, pushing up) uniform over each block of side x side nodes (as blockSumsNext's
    // blocks; perBlock[by * blocks + bx]) for the next computeFree only, at every interior node
    // (eq. 22's pressure term, node by node): the cavity's modes and the near field
    // (CavityModesCoupling, NearFieldCoupling); the pressures added before a computeFree sum.
    // prepareBlocks(side) first (it allocates; addBlockPressure does not); one side per head.
    void prepareBlocks(int side);
    void addBlockPressure(int side, const double* perBlock);
    // Add an external force f (N, positive up) spread by g to w^{n+1}: w += k^2/(rho q) g f,
    // times the node's response (below).
    void applyForce(const GridDistribution& d, double force_N);
    // k^2 / (rho q): how far w^{n+1} moves per unit force density (in vacuum).
    double forceGain() const { return kk / (rho * q); }
    // How far w^{n+1} at a node moves per unit force density there: forceGain() times the
    // node's response, 1 unless a coupling solved with the head's update sets it (the air of
    // HeadEmbedding: the diagonal of (1 + gamma J^T J)^{-1}). Contacts solve with it.
    double forceGainAt(int node) const { return response ? forceGain() * response[node] : forceGain(); }
    // Per node of the padded grid (the owner keeps it alive and in place), nullptr: 1 everywhere.
    void setResponse(const double* perNode) { response = perNode; }
    const double* responseScale() const { return response; }

    // h^2 g^T w at time n+1, n or n-1.
    double sampleNext(const GridDistribution& d) const { return sample(d, 0); }
    double sampleNow(const GridDistribution& d) const { return sample(d, 1); }
    double samplePrev(const GridDistribution& d) const { return sample(d, 2); }

    // Energy h^{n+1/2} of eq. (35) (with the sigma1 term) from w^{n+1}, w^n.
    double energy() const;
    // k q^n: energy removed by the losses over the step from n-1/2 to n+1/2.
    double stepLoss() const;

    bool singlePrecision() const { return single; }

    // w at one node at n+1, n or n-1, for couplings that act node by node.
    double nextAt(int node) const { return single ? (double) fNext[(size_t) node] : wNext[(size_t) node]; }
    double nowAt(int node) const { return single ? (double) fNow[(size_t) node] : wNow[(size_t) node]; }
    double prevAt(int node) const { return single ? (double) fPrev[(size_t) node] : wPrev[(size_t) node]; }
    void setNextAt(int node, double value)
    {
        if (single)
        {
            const float v = (float) value;
            moved(node, (double) v - (double) fNext[(size_t) node]);
            fNext[(size_t) node] = v;
            return;
        }
        moved(node, value - wNext[(size_t) node]);
        wNext[(size_t) node] = value;
    }
    // The same for count entries: values[j] at nodes[index[j]] (index null: nodes[j]; the
    // indices distinct and increasing), the running sums' changes summed by index: left out,
    // an entry whose value is its node's own changes nothing, to the last bit.
    void setNextAt(const int* nodes, const double* values, const int* index, int count);
    // w^{n+1} at count nodes, into out.
    void nextAt(const int* nodes, double* out, int count) const;
    // w^{n+1} copied out and back (w sized by the first call), for a step's coupling solved
    // more than once (DrumAir). Double precision only (the air box's heads).
    void saveNext(std::vector<double>& w, double& sum) const
    {
        w = wNext;
        sum = sumNext;
    }
    void restoreNext(const std::vector<double>& w, double sum)
    {
        wNext = w;
        sumNext = sum;
        sumsStale = sumSide > 0; // taken sums: taken again from w
    }
    // h^2 sum(w) at n+1: the volume swept by the head (summed in computeFree, kept by the
    // force updates; or taken once the forces are in: takeSumsWithBlocks).
    double sweptVolumeNext() const
    {
        takeSumsNow();
        return h * h * sumNext;
    }

    // Rotate time levels after a completed step.
    void advance();
    void clear();

    // The state arrays themselves, double precision only (empty otherwise): for the air box's
    // embedding (HeadEmbedding), which updates w^{n+1} with the air.
    const std::vector<double>& nextDisplacement() const { return wNext; }     // w^{n+1}
    const std::vector<double>& previousDisplacement() const { return wPrev; } // w^{n-1}
    bool isFinite() const;

private:
    // f(next, now, prev) on the state arrays in their precision.
    template <class F>
    decltype(auto) withState(F&& f) const
    {
        return single ? f(fNext, fNow, fPrev) : f(wNext, wNow, wPrev);
    }
    double sample(const GridDistribution& d, int level) const;
    void expandBlockPressure(); // blockPressure into the push per node
    template <class Real>
    double energyOf(const Real* wNext, const Real* wNow) const;
    template <class Real>
    double stepLossOf(const Real* wNext, const Real* wPrev) const;

    CircularGrid g;
    double k, kk, h;
    double rho, T = 0, sigma0 = 0, sigma1 = 0;
    double maxT, maxSigma1;
    double q = 1;
    double a0 = 0, a1 = 0, b0 = 0, b1 = 0;         // stencil coefficients
    float r = 0, cl = 0, cs = 0;                   // the same as an increment, for the float state (computeFree)
    std::vector<int> rowBegin, rowEnd;             // columns holding interior nodes, per row
    std::vector<double> rowY;                      // y of each row (m)
    mutable double sumNext = 0.0;                  // sum(w^{n+1})
    bool momentsKept = false;                      // keepMoments
    mutable double xSumNext = 0.0, ySumNext = 0.0; // sum(x w^{n+1}), sum(y w^{n+1}), when kept
    // takeSumsWithBlocks: the side of the blocks summed with them (0: the sums are kept), whether
    // w^{n+1} changed since they were taken, and the blocks' sums
    int sumSide = 0;
    mutable bool sumsStale = false;
    mutable std::vector<double> sideSums;
    // the grid's coordinates as the state's xs, ys hold them (x of a column, y of a row: the same
    // values; in float for the float state), for the sums pass
    std::vector<double> axis;
    void takeSums() const;
    // w^{n+1} at a node moved by dw: the sums kept follow
    void moved(int node, double dw)
    {
        if (sumSide > 0)
        {
            sumsStale = true;
            return;
        }
        sumNext += dw;
        if (momentsKept)
        {
            xSumNext += (single ? (double) fX[(size_t) node] : dX[(size_t) node]) * dw;
            ySumNext += (single ? (double) fY[(size_t) node] : dY[(size_t) node]) * dw;
        }
    }
    const double* response = nullptr; // per-node response to a force (setResponse), or 1
    bool single = false;
    std::vector<double> wNext, wNow, wPrev;   // double precision, else empty
    RowAlignedGrid<float> fNext, fNow, fPrev; // single precision, else empty
    RowAlignedGrid<float> fMask;              // single precision: the grid's mask
    RowAlignedGrid<float> fX, fY;             // single precision: x and y times the mask
    std::vector<float> fAxis;                 // single precision: x by column (y by row alike)
    std::vector<double> dX, dY;               // double precision: the same
    mutable std::vector<double> dRowScratch;  // the bands of rows summed, for blockSumsNext
    mutable std::vector<double> accScratch;   // the bands' rows, for blockAccelerationsIn
    int blockSide = 0;                        // prepareBlocks: the side of addBlockPressure's blocks
    std::vector<double> blockPressure;        // the pressures added since the last computeFree, per block
    std::vector<int> columnBlock;             // and each column's block
    std::vector<double> dField;               // the blocks' push per node (double state)
    RowAlignedGrid<float> fField;             // (float state)
    bool fieldSet = false;                    // a block pressure for the next computeFree
};

} // namespace snaresim
