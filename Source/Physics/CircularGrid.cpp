#include "CircularGrid.h"

#include <algorithm>
#include <cmath>

namespace snaresim
{

CircularGrid::CircularGrid(double radius_m, double spacing_m) : R(radius_m), h(spacing_m)
{
    const int m = (int) std::ceil(R / h) + 1; // nodes from the centre to beyond the rim
    n = 2 * m + 1;
    centre = m;
    interior.assign((size_t) n * (size_t) n, 0.0);
    // A node belongs to the head when it lies within R - h/2 of the centre: the Dirichlet
    // condition then acts on nodes whose mean distance from the centre is about R, so the
    // staircase rim encloses the head's real area rather than one half-cell more.
    const double rIn = R - 0.5 * h;
    for (int iy = 1; iy < n - 1; ++iy)
        for (int ix = 1; ix < n - 1; ++ix)
            if (std::hypot(x(ix), x(iy)) < rIn)
            {
                interior[(size_t) index(ix, iy)] = 1.0;
                ++interiorCount;
            }
}

int CircularGrid::nearestInterior(double px, double py) const
{
    const int ix = (int) std::lround(px / h + centre), iy = (int) std::lround(py / h + centre);
    if (ix < 1 || iy < 1 || ix > n - 2 || iy > n - 2)
        return -1;
    const int i = index(ix, iy);
    return interior[(size_t) i] != 0.0 ? i : -1;
}

int CircularGrid::distributionCapacity(double radius_m) const
{
    const int span = 2 * (int) std::ceil(radius_m / h) + 3;
    return std::max(4, span * span);
}

bool CircularGrid::makeDistribution(double px, double py, double radius_m, GridDistribution& d) const
{
    d.size = 0;
    const int cap = (int) d.index.size();
    double sum = 0.0;
    auto add = [&](int idx, double w) {
        if (w <= 0.0 || interior[(size_t) idx] == 0.0 || d.size >= cap)
            return;
        d.index[(size_t) d.size] = idx;
        d.g[(size_t) d.size] = w;
        sum += w;
        ++d.size;
    };

    if (radius_m >= h)
    {
        const int r = (int) std::ceil(radius_m / h) + 1;
        const int cx = (int) std::lround(px / h + centre), cy = (int) std::lround(py / h + centre);
        for (int iy = std::max(1, cy - r); iy <= std::min(n - 2, cy + r); ++iy)
            for (int ix = std::max(1, cx - r); ix <= std::min(n - 2, cx + r); ++ix)
            {
                const double dist = std::hypot(x(ix) - px, x(iy) - py);
                if (dist < radius_m)
                    add(index(ix, iy), 0.5 * (1.0 + std::cos(M_PI * dist / radius_m)));
            }
    }
    if (sum <= 0.0) // bilinear interpolation
    {
        d.size = 0;
        const double fx = px / h + centre, fy = py / h + centre;
        const int ix = (int) std::floor(fx), iy = (int) std::floor(fy);
        if (ix < 1 || iy < 1 || ix + 1 > n - 2 || iy + 1 > n - 2)
            return false;
        const double ax = fx - ix, ay = fy - iy;
        add(index(ix, iy), (1 - ax) * (1 - ay));
        add(index(ix + 1, iy), ax * (1 - ay));
        add(index(ix, iy + 1), (1 - ax) * ay);
        add(index(ix + 1, iy + 1), ax * ay);
    }
    if (sum <= 0.0)
        return false;
    const double norm = 1.0 / (sum * h * h); // h^2 1^T g = 1
    for (int i = 0; i < d.size; ++i)
        d.g[(size_t) i] *= norm;
    return true;
}

} // namespace snaresim
