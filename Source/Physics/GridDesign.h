#pragma once
// How the heads' and the wires' grids are spaced against their stability bounds (eq. 39, 40).

namespace snaresim
{

// The step a grid is designed at when simulated at step k: gridTimeStep_s where k is longer
// (0: k itself).
inline double designStep(double k, double gridTimeStep_s) { return gridTimeStep_s > 0.0 && gridTimeStep_s < k ? gridTimeStep_s : k; }

// The spacing a grid of this coarseness is built with at step k, bound(step) being its
// stability bound (eq. 39 or 40) at a step: coarseness times the bound at the design step
// (designStep), never finer than the bound at k.
template <class Bound>
double designedSpacing(double coarseness, double k, double gridTimeStep_s, Bound bound)
{
    const double design = designStep(k, gridTimeStep_s);
    const double asked = coarseness * bound(design), least = bound(k);
    return asked > least ? asked : least;
}

} // namespace snaresim
