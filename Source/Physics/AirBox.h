#pragma once
// The 3D air around and inside the drum: velocity potential Psi (eq. 5), scheme (25)
//   dtt Psi = c^2 D Psi + c sigma dt- D Psi,   D the 7-point Laplacian,
// on a box of cubic cells of side h (eq. 41), nodes at the cell centres, walls half a cell
// beyond the outer nodes. D is a sum over links between neighbouring nodes; a link through
// a wall, through the rigid shell (eq. 6) or through an embedded head is cut (zero normal
// velocity there; a head adds its own flux, HeadEmbedding). Absorbing walls (eq. 51) add
// -(m c / h) dt. Psi at a node with m wall faces. Energy eq. (36) over the links present,
// with the sigma term's share; energy^{n+1/2} + stepLoss() = energy^{n-1/2} to round-off.
// Pressure p = rho_a dt Psi, particle velocity -grad Psi.
//
// The update: Psi^{n+1} = 2 Psi^n - Psi^{n-1} + L v, v = (lambda^2 + s) Psi^n - s Psi^{n-1}
// (s = c sigma k / h^2, L the unscaled 7-point Laplacian), layer by layer: each thread keeps v
// of three layers in cache, so each level streams from memory once; the layers are independent
// of each other, so threads take them in any order with the same numbers.

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace snaresim
{

enum class AirWalls
{
    absorbing,  // first-order Engquist-Majda, eq. (51)
    reflecting, // zero normal derivative (for energy tests)
};

enum class ShellEnds
{
    open,   // the shell's top and bottom let air through (no heads)
    closed, // rigid discs at both ends (where heads are embedded, they replace the discs)
};

struct AirBoxSpec
{
    double soundSpeed_m_per_s = 343.0;              // c_a
    double density_kg_per_m3 = 1.21;                // rho_a
    double sigma_m = 2e-6;                          // sigma_a, viscothermal loss (paper section 5.3)
    double gridSigma_m = -1.0;                      // largest sigma_a the grid allows (negative: sigma_m)
    double gridCoarseness = 1.0;                    // h = coarseness * bound of eq. (41); >= 1
    std::array<double, 3> size_m { 0.6, 0.6, 0.6 }; // box (x, y, z), centred at the origin
    AirWalls walls = AirWalls::absorbing;

    // The drum's rigid cylindrical shell (eq. 6), axis along z through the origin,
    // from z = -depth/2 (carry head) to +depth/2 (batter).
    bool shell = true;
    double shellRadius_m = 0.1778;
    double shellDepth_m = 0.14;
    ShellEnds shellEnds = ShellEnds::open;
};

// One end of a cut link, as a layer's update takes it back (AirBox.cpp).
struct AirCut
{
    int local; // the node's index within its padded layer
    int delta; // its cut neighbour's index offset (+-1, +-sx, +-sx sy)
    int layer; // the neighbour's layer: 0 below, 1 the same, 2 above
    int shift; // its offset within that layer
};

class AirBox
{
public:
    // Throws std::invalid_argument when the time step, the coarseness or the size cannot
    // make a grid, or the drum does not fit inside the box with a cell to spare.
    AirBox(const AirBoxSpec& spec, double timeStep_s);
    ~AirBox();
    AirBox(const AirBox&) = delete;
    AirBox& operator=(const AirBox&) = delete;

    // eq. (41): h = coarseness * sqrt(3 c^2 k^2 + 6 c sigma k).
    static double gridSpacing(const AirBoxSpec& spec, double timeStep_s);

    double spacing() const { return h; }
    double timeStep() const { return k; }
    double soundSpeed() const { return c; }
    double density() const { return rho; }
    int nx() const { return n[0]; }
    int ny() const { return n[1]; }
    int nz() const { return n[2]; }
    long numPoints() const { return (long) n[0] * n[1] * n[2]; }
    int numCutLinks() const { return (int) cutA.size(); }

    // Node coordinates (m) of node index i in 0..n-1 along an axis.
    double coordinate(int axis, int i) const { return (i - 0.5 * (n[(size_t) axis] - 1)) * h; }
    // The layer l such that the plane between layers l and l+1 is nearest z.
    int layerBelow(double z_m) const;
    // z of the plane between layers l and l+1.
    double planeAbove(int layer) const { return coordinate(2, layer) + 0.5 * h; }
    // Flat index of node (ix, iy, iz), each in 0..n-1.
    long index(int ix, int iy, int iz) const { return (long) (ix + 1) + sx * ((long) (iy + 1) + sy * (long) (iz + 1)); }

    // Cut the vertical links between layer l and l+1 at the nodes within radius of the
    // axis (x, y) = (cx, cy): a rigid disc, or where a head is embedded. Cutting twice is harmless.
    // Returns the nodes of layer l whose link was (or already had been) cut there.
    std::vector<long> cutDisc(int layer, double cx_m, double cy_m, double radius_m);

    // Sets Psi at time n and n-1 to f(x, y, z) (at rest), clears n+1.
    void setPotential(const std::function<double(double, double, double)>& f);
    void clear();

    // Psi^{n+1} from Psi^n, Psi^{n-1}: the whole update, walls, shell and cut links included.
    // Couplings then add their terms to the next level (HeadEmbedding).
    // The same as beginNext({}) then finishNext().
    void computeNext();

    // The update in two parts, so that a coupling can work on a few layers while the threads
    // compute the others. beginNext(layers) starts the threads on every layer not listed and
    // computes the listed ones on the calling thread: when it returns, those layers of next()
    // are final (cut links, walls and ghosts included). Until finishNext(), the caller may read
    // and write next() on the listed layers only (and read now() and prev()). finishNext() lends
    // the calling thread to the layers still left, then waits for the threads: next() is then
    // complete. The numbers are those of computeNext(), bit for bit, whatever the split. On one
    // thread beginNext() computes every layer (in one run: cheapest) and finishNext() has nothing
    // left to do. Allocates only when the list differs from the last call's.
    void beginNext(std::span<const int> layers);
    void finishNext();

    void advance(); // rotate time levels (finishes a pending update first)

    // Split the update's layers over this many threads, the calling one included (1: the
    // calling thread only). Between steps the others spin a short while, then sleep.
    void setThreads(int count);
    int threads() const { return threadCount; }

    // The figures below read every layer: call them after finishNext() (or computeNext()).
    // eq. (36) at n+1/2 from Psi^{n+1}, Psi^n (with the sigma term's share, -(rho sigma k / 4c) |grad dt+ Psi|^2).
    double energy() const;
    // Energy removed from n-1/2 to n+1/2 by sigma_a and the absorbing walls (k q^n >= 0).
    double stepLoss() const;

    // p = rho_a (Psi^{n+1} - Psi^n) / k at time n+1/2, trilinear between nodes; 0 outside the grid.
    double pressure(double x_m, double y_m, double z_m) const;

    // Raw levels (padded layout: index()), for couplings and tests. Between beginNext() and
    // finishNext() only the listed layers of next() may be read or written.
    double* next() { return lvl[0]; }
    const double* next() const { return lvl[0]; }
    const double* now() const { return lvl[1]; }
    const double* prev() const { return lvl[2]; }

    // Coefficients couplings need: lambda^2 = (c k / h)^2.
    double lambda2() const { return l2; }

private:
    // A thread's three layers of v = a1 Psi^n + b1 Psi^{n-1} (eq. 25 is Psi^{n+1} = 2 Psi^n -
    // Psi^{n-1} + L v, L the unscaled 7-point Laplacian), kept by padded layer number mod 3.
    struct Ring
    {
        std::vector<double> v;
        long tag[3] { -1, -1, -1 }; // padded layer held in each slot (-1: none)
        void invalidate() { tag[0] = tag[1] = tag[2] = -1; }
    };

    void buildWalls();
    void buildShell();
    void cutLink(long a, long b, int axis);
    void indexCuts();                           // cut links by layer, each from both ends
    void setOrder(std::span<const int> layers); // the listed layers and the rest
    const double* ringLayer(Ring& ring, int pz) const;
    void updateLayer(int iz, Ring& ring); // one layer of next(), complete
    void fillGhosts(double* u);

    AirBoxSpec spec;
    double k, h, c, rho, sigma;
    double l2 = 0, s = 0; // lambda^2, c sigma k / h^2
    double a0 = 0, a1 = 0, b0 = 0, b1 = 0;
    std::array<double, 4> wallGain {}, wallInverse {}; // eq. (51) by number of wall faces m
    std::array<int, 3> n {};
    long sx = 0, sy = 0, total = 0; // padded strides and size

    std::vector<double> store; // three padded levels
    double* lvl[3] {};         // next, now, prev

    // cut links (a, b): the bulk stencil includes them; each layer takes them back
    std::vector<long> cutA, cutB;
    std::vector<std::uint8_t> cutMask; // per node: bit axis set when the link to +axis is cut
    std::vector<AirCut> cuts;          // by layer and row, from both ends: node i loses v_j - v_i
    std::vector<int> cutRow;           // interior row iy of layer iz: [cutRow[iz ny + iy], cutRow[iz ny + iy + 1])

    // absorbing wall nodes by number of wall faces m = 1, 2, 3 (for stepLoss)
    std::array<std::vector<long>, 3> wallNodes;

    // the layers beginNext() computes on the caller, and the others in the threads' order
    std::vector<int> earlyArgs, early, rest;
    bool pending = false;

    int threadCount = 1;
    std::vector<Ring> rings; // one per thread, the caller's first
    struct Pool;
    std::unique_ptr<Pool> pool;
};

} // namespace snaresim
