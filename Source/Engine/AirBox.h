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

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
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
    double soundSpeed_m_per_s = 343.0;  // c_a
    double density_kg_per_m3 = 1.21;    // rho_a
    double sigma_m = 2e-6;              // sigma_a, viscothermal loss (paper section 5.3)
    double gridSigma_m = -1.0;          // largest sigma_a the grid allows (negative: sigma_m)
    double gridCoarseness = 1.0;        // h = coarseness * bound of eq. (41); >= 1
    std::array<double, 3> size_m { 0.6, 0.6, 0.6 }; // box (x, y, z), centred at the origin
    AirWalls walls = AirWalls::absorbing;

    // The drum's rigid cylindrical shell (eq. 6), axis along z through the origin,
    // from z = -depth/2 (carry head) to +depth/2 (batter).
    bool shell = true;
    double shellRadius_m = 0.1778;
    double shellDepth_m = 0.14;
    ShellEnds shellEnds = ShellEnds::open;
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
    double coordinate(int axis, int i) const { return (i - 0.5 * (n[axis] - 1)) * h; }
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
    void computeNext();
    void advance(); // rotate time levels

    // Split the update's z-range over this many threads (1: the calling thread only).
    void setThreads(int count);
    int threads() const { return threadCount; }

    // eq. (36) at n+1/2 from Psi^{n+1}, Psi^n (with the sigma term's share, -(rho sigma k / 4c) |grad dt+ Psi|^2).
    double energy() const;
    // Energy removed from n-1/2 to n+1/2 by sigma_a and the absorbing walls (k q^n >= 0).
    double stepLoss() const;

    // p = rho_a (Psi^{n+1} - Psi^n) / k at time n+1/2, trilinear between nodes; 0 outside the grid.
    double pressure(double x_m, double y_m, double z_m) const;

    // Raw levels (padded layout: index()), for couplings and tests.
    double* next() { return lvl[0]; }
    const double* next() const { return lvl[0]; }
    const double* now() const { return lvl[1]; }
    const double* prev() const { return lvl[2]; }

    // Coefficients couplings need: lambda^2 = (c k / h)^2.
    double lambda2() const { return l2; }

private:
    void buildWalls();
    void buildShell();
    void cutLink(long a, long b, int axis);
    void updateLayers(int zBegin, int zEnd); // bulk stencil over layers [zBegin, zEnd)
    void fillGhosts(double* u);

    AirBoxSpec spec;
    double k, h, c, rho, sigma;
    double l2 = 0, s = 0;               // lambda^2, c sigma k / h^2
    double a0 = 0, a1 = 0, b0 = 0, b1 = 0;
    std::array<int, 3> n {};
    long sx = 0, sy = 0, total = 0;     // padded strides and size

    std::vector<double> store;          // three padded levels
    double* lvl[3] {};                  // next, now, prev

    // cut links (a, b): the bulk stencil included them; corrected afterwards
    std::vector<long> cutA, cutB;
    std::vector<std::uint8_t> cutMask;  // per node: bit axis set when the link to +axis is cut

    // absorbing wall nodes by number of wall faces m = 1, 2, 3
    std::array<std::vector<long>, 3> wallNodes;

    int threadCount = 1;
    struct Pool;
    std::unique_ptr<Pool> pool;
};

} // namespace snaresim
