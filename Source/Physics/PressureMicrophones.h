#pragma once
// The microphones: the sound pressure at three points in the air outside the drum (top, bottom,
// room; MicSpec), radiated by the heads' motion. A listener, not a component: it stores no
// energy and exerts no force.
//
// Each head is cut into square cells (MicSpec::cellSize_m). A cell's outward volume
// acceleration A = d^2/dt^2 (h^2 sum w) (the second difference of its volume) radiates to a
// microphone on the head's side as in Rayleigh's integral for a baffled plane,
//   p(t) = rho_a / (2 pi) sum_cells g A(t - R / c) / R,     R: cell centre to microphone,
// (1/R averaged over a cell the microphone is close to), each cell's share pushed ahead into a
// ring of the microphone's future samples (linear interpolation between the two samples around
// its delay; the taps of one whole delay summed together). g = 1 near the head, where the head
// is its own baffle; far from it (beyond a radius from its centre, blended over the next) the
// drum is a finite body and its face radiates with Kirchhoff's obliquity g = (1 + cos theta) / 2.
// A drum is no baffle: below its baffle step (ka ~ 1, a the radius) a compact closed body
// radiates as the free-field monopole rho_a / (4 pi r) d^2(V_out)/dt^2. The sound the baffle
// would have held comes from the rim instead: the facing head's whole-head term, with half its
// baffled strength, negative, and the other head's, round the shell, both from the rim and
// through a one-pole low-pass at c / a (Olson's baffle step):
//   p = Rayleigh(facing) + LP[ -rho_a/(4 pi) <1/d> A_f(t - <d>/c) + rho_a/(4 pi) <1/(d + H)> A_o(t - (<d> + H)/c) ],
// <.> the mean over the facing rim's points, d from a rim point to the microphone, H the shell's
// depth, A_f, A_o the heads' whole outward volume accelerations (the batter's outward normal up,
// the carry head's down). The air box checks it (Tests/Engine/PressureMicrophoneTests.cpp).
// Cost per step: a pass over each head (Membrane::blockSumsNext; the float head's comes with its
// taken sums, Membrane::takeSumsWithBlocks), a store per cell, and two
// multiply-adds per cell per microphone, summed a block of steps at a time. Real-time safe
// after construction: setPositions and listen allocate nothing.

#include "CacheAligned.h"
#include "CavitySpec.h"
#include "CircularGrid.h"
#include "MicSpec.h"

#include <array>
#include <vector>

namespace snaresim
{

class Membrane;

class PressureMicrophones
{
public:
    enum Position
    {
        top,
        bottom,
        room,
        numMics
    };

    // The heads' cells from their grids, the delay lines long enough for any microphone within
    // MicSpec::reach_m of the drum's centre; the air's density and sound speed and the shell's
    // depth from the cavity's spec, the steps at this rate.
    PressureMicrophones(const MicSpec& mics, const CavitySpec& air, double sampleRate_Hz, const Membrane& batter, const Membrane& carry);

    // Move the microphones (each within reach_m, outside the drum: DrumConfig::validate), on a
    // shell of this depth (the heads at +-depth/2).
    void setPositions(const MicSpec& mics, double shellDepth_m) noexcept;

    // Once the heads' w^{n+1} is final: the cells' volumes at n+1, their accelerations at n,
    // and the pressures at the microphones.
    // sums: each head's Membrane::blockSumsNext at its cells' side for this step, if a coupling
    // already has them (CavityModesCoupling), else nullptr (then the head's taken sums at that
    // side, Membrane::takenBlockSums, or a pass of its own).
    void listen(const Membrane& batter, const Membrane& carry, std::array<const double*, 2> sums = {}) noexcept;
    int cellSide(int head) const { return heads[(size_t) head].side; }
    double pressure(Position p) const { return out[(size_t) p]; }

    void clear() noexcept;
    // At most this many steps a block (1 .. kLanes; kLanes unless a test sets it): the sound
    // is the same to the last bit.
    void setLongestBlock(int steps) noexcept;

private:
    struct Head
    {
        double z = 0.0;               // plane of the head
        double sign = 1.0;            // outward normal: +1 batter (up), -1 carry (down)
        int side = 1;                 // cell side in grid nodes
        double width_m = 0.0;         // and in metres
        double nodeArea = 0.0;        // h^2 of the head's grid (a block sum times it is a volume)
        int cells = 0;                // blocks holding interior nodes
        AlignedVector<int> block;     // cell -> block
        AlignedVector<double> cx, cy; // cell centres (m)
        const CircularGrid* grid = nullptr;
        int blocks = 0;                    // blocks per row of the grid
        int fine = 1;                      // side of the cells near a microphone, in grid nodes
        AlignedVector<double> blockSum;    // the blocks' sums of w^{n+1} (Membrane::blockSumsNext)
        AlignedVector<double> vNow, vPrev; // cell volumes at n, n-1 (m^3)
        int rowBegin = 0;                  // its first cell's row of A (sourceRows)
        double whole = 0.0;                // the whole head's A^n
    };
    // One source's share of a microphone: gain at a delay of whole samples plus a fraction.
    struct Tap
    {
        int delay = 0;
        double frac = 0.0;
        double gain = 0.0;
    };
    // A microphone's taps on its facing head's cells, sorted by their whole delays: a run per
    // delay. The taps are summed a block of steps at a time: each source (a head's cell, a
    // microphone's fine cell) keeps a row of kLanes floats, its A at the block's steps, and a
    // run's rows are summed at once, whole rows, no gathers, kept lane by lane (a tap's place
    // in its run modulo kLanes) and added to a ring of the direct sound ahead (a ring of `rows`
    // samples, kLanes floats a sample, added across the lanes when the sample is heard) in the
    // order summing step by step would add them: the sound is the same to the last bit wherever
    // the blocks fall. A block holds at most one step more than the shortest whole delay of the
    // taps it sums, so every sample is complete when it is heard: the samples it reaches lie at
    // least that far ahead of its first step. The far taps (whole delays of kFar and more) are
    // summed in blocks of kLanes steps, into a ring of their own; the near ones (a close
    // microphone's) in the blocks their shortest delay allows, within those, into theirs. In
    // single precision: the taps' rounding is about 1e-7 of the sound, far below anything heard
    // or measured.
    static constexpr int kLanes = 8;
    static constexpr int kFar = kLanes - 1;
    struct Listener
    {
        int facing = 0;
        AlignedVector<int> cell;        // taps: their sources' rows, by delay
        AlignedVector<float> now, next; // gain (1 - frac), gain frac: to the delay and the one after
        AlignedVector<int> runEnd;      // per delay from firstDelay: end of its run of taps
        int firstDelay = 0, delays = 0;
        int nearRuns = 0; // the runs of whole delays under kFar
        // The cells close to the microphone, heard in fine cells (a coarse cell's sum would alias
        // the head's short waves into ones that radiate): a rectangle of the grid from node
        // (nearX, nearY), nearColumns x nearRows nodes, in fine cells.
        int nearX = 0, nearY = 0, nearColumns = 0, nearRows = 0, nearCells = 0;
        int fineBegin = 0;                 // the first fine cell's row of A (sourceRows)
        int fineCapacity = 0;              // the most fine cells its rows of A hold
        Tap facingWhole {}, otherWhole {}; // the low-passed whole-head terms
        AlignedVector<float> direct;       // ring: the far taps' direct sound ahead, kLanes partial sums a sample
        AlignedVector<float> directNear;   // ring: the near taps' alike
        AlignedVector<double> around;      // ring: the low-pass's input, ahead
        double lowPass = 0.0;
        // scratch of place() (no allocation there)
        std::vector<Tap> taps;
        std::vector<int> tapCell, count;
    };

    void place(Listener& l, const AirPoint& p) noexcept;
    // the taps of the block's steps so far into the rings, a new block begun at the next step
    void sumBlock() noexcept;
    void sumNear() noexcept; // the near taps of the block's steps from nearDone
    // runs first .. last - 1 of l over the block's steps from .. filled - 1, into ring
    void addRuns(Listener& l, int first, int last, int from, AlignedVector<float>& ring) noexcept;
    void beginBlocks() noexcept; // the span from the microphones' delays, a new block
    Tap tapAt(double distance_m, double gain) const noexcept;
    void push(AlignedVector<double>& ring, const Tap& t, double value) const noexcept;

    double k, radius, depth; // time step, the heads' radius, the shell's depth
    double nearWidths;       // cells within this many widths of a microphone's foot are heard in fine cells
    double rho, c, alpha;    // air density, sound speed, low-pass coefficient
    int rows = 0;            // the rings' length (a power of two), longer than every delay
    int pos = 0;             // ring slot of step n
    int longestBlock = kLanes;
    int span = 1;                           // steps a block holds (1 .. longestBlock): the far taps' shortest whole delay plus one
    int nearSpan = 1;                       // steps a near taps' block holds (1 .. span), within the block
    int filled = 0;                         // steps of the block so far
    int nearDone = 0;                       // of them, summed into the near taps' ring
    int blockSlot = 0;                      // ring slot of the block's first step
    AlignedVector<float> sourceRows;        // kLanes floats a source: the heads' cells, then each microphone's fine cells
    AlignedVector<float> tileNow, tileNext; // a microphone's runs' sums in a block, per delay, step and lane (sumTapBlock)
    std::array<Head, 2> heads;
    std::array<Listener, numMics> mics;
    std::array<double, numMics> out {};
};

} // namespace snaresim
