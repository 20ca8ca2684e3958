#pragma once
// A square grid of spacing h clipped to a disc of radius R (eq. 1, 22-24), stored as a
// padded N x N array so that the 5-point stencil needs no bounds checks: nodes outside the
// disc are fixed at zero (the fixed rim).

#include <cstddef>
#include <vector>

namespace snaresim
{

// A grid distribution g over a few nodes, normalised so that h^2 sum(g) = 1 (as g_b in eq. 26).
// Used for the mallet's contact patch g_b.
struct GridDistribution
{
    std::vector<int> index; // flat node indices (interior nodes only)
    std::vector<double> g;  // values of g at those nodes (1/m^2)
    int size = 0;           // used entries (capacity is index.size())

    void reserve(int capacity)
    {
        index.assign((std::size_t) capacity, 0);
        g.assign((std::size_t) capacity, 0.0);
        size = 0;
    }
};

class CircularGrid
{
public:
    CircularGrid(double radius_m, double spacing_m);

    double radius() const { return R; }
    double spacing() const { return h; }
    int width() const { return n; } // N: nodes per row, padding included
    int numNodes() const { return n * n; }
    int numInterior() const { return interiorCount; }
    const std::vector<double>& mask() const { return interior; } // 1 inside, 0 on/after the rim

    int index(int ix, int iy) const { return iy * n + ix; }
    double x(int ix) const { return (ix - centre) * h; }

    // The interior node nearest to (x, y), or -1 when that node is not on the head.
    int nearestInterior(double x_m, double y_m) const;

    // Capacity a distribution of the given radius may need.
    int distributionCapacity(double radius_m) const;

    // Raised-cosine patch of the given radius centred at (x, y), or bilinear interpolation
    // weights when the radius is below h. Writes into d without allocating (d must have
    // distributionCapacity(radius) entries). Returns false when the point has no interior
    // node near it.
    bool makeDistribution(double x_m, double y_m, double radius_m, GridDistribution& d) const;

private:
    double R, h;
    int n;
    double centre;
    int interiorCount = 0;
    std::vector<double> interior;
};

} // namespace snaresim
