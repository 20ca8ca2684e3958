#pragma once
// The batter's modes one by one: its displacement projected on a vacuum mode's shape after a
// strike, and the mode's peak near a frequency. Shared by the air box's and the near field's tests.

#include "Drum.h"
#include "SpectrumPeaks.h"

#include <cmath>
#include <vector>

namespace snaresim::test
{
// The batter's (m,n) vacuum mode shape J_m(j_mn r / R) cos(m theta) on its grid, and its
// coordinate (the shape's sum over the head) per step after a strike at (0.5 R, 0).
struct BatterMode
{
    int m;
    double j; // j_mn, the n-th zero of J_m (Abramowitz and Stegun, table 9.5)
    const char* name;
};

// J_m(j r / R) cos(m theta) at every node of g (zero outside the disc).
inline std::vector<double> vacuumShape(const CircularGrid& g, int m, double j)
{
    std::vector<double> s((size_t) (g.width() * g.width()), 0.0);
    for (int iy = 0; iy < g.width(); ++iy)
        for (int ix = 0; ix < g.width(); ++ix)
        {
            const double x = g.x(ix), y = g.x(iy), r = std::hypot(x, y);
            if (r < g.radius())
                s[(size_t) g.index(ix, iy)] = std::cyl_bessel_j(m, j * r / g.radius()) * std::cos(m * std::atan2(y, x));
        }
    return s;
}

inline std::vector<std::vector<double>> batterModeCoordinates(const DrumConfig& cfg, const std::vector<BatterMode>& modes, int steps)
{
    Drum drum(cfg);
    drum.strike(2.0, 0.5, 0.0);
    const CircularGrid& g = drum.batter().grid();
    const int nodes = g.width() * g.width();
    std::vector<std::vector<double>> shapes, out(modes.size());
    for (const BatterMode& mode : modes)
        shapes.push_back(vacuumShape(g, mode.m, mode.j));
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        for (size_t q = 0; q < modes.size(); ++q)
        {
            double sum = 0.0;
            for (int i = 0; i < nodes; ++i)
                sum += shapes[q][(size_t) i] * drum.batter().nowAt(i);
            out[q].push_back(sum);
        }
    }
    return out;
}

// The strongest peak of x within 15 % below to 5 % above f.
inline double peakNear(const std::vector<double>& x, double sampleRate_Hz, double f)
{
    const size_t pad = 8;
    const auto found = test::peaks(test::hannSpectrum(x, pad), sampleRate_Hz / (double) (pad * x.size()), 0.85 * f, 1.05 * f);
    return found.empty() ? 0.0 : found.front().frequency;
}
} // namespace snaresim::test
