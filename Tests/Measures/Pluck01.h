#pragma once
// A head at rest in its (0,1) shape J0(2.4048 r / R), 0.1 mm at the centre: the start of the
// mode tests with and without air (HeadEmbeddingTests, airbox_figures).

#include "Membrane.h"

#include <cmath>

namespace snaresim::test
{

inline void pluck01(Membrane& head)
{
    const CircularGrid& g = head.grid();
    for (int round = 0; round < 2; ++round) // w^n = w^{n-1}: at rest
    {
        for (int iy = 0; iy < g.width(); ++iy)
            for (int ix = 0; ix < g.width(); ++ix)
            {
                const int i = g.index(ix, iy);
                if (g.mask()[(size_t) i] != 0.0)
                    head.setNextAt(i, 1e-4 * std::cyl_bessel_j(0.0, 2.404825557695773 * std::hypot(g.x(ix), g.x(iy)) / g.radius()));
            }
        head.advance();
    }
}

} // namespace snaresim::test
