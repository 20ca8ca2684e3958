#pragma once
// Shapes on a head's cells (HeadCells), shape-major (shape s's value in cell c at
// shape[s * cells + c]), as the couplings that act through them use them: a pressure field from
// the shapes' weights, and the shapes' projections of the cells' sums (the one the transpose of
// the other). Four shapes at a time, so that the sums are independent chains.

namespace snaresim
{

// out[c] = sum_s weight[s] shape[s][c].
void combineShapes(int shapes, int cells, const double* weight, const double* shape, double* out);
void combineShapes(int shapes, int cells, const double* weight, const float* shape, double* out);
// out[s] = scale sum_c shape[s][c] v[c].
void projectShapes(int shapes, int cells, const double* shape, const double* v, double scale, double* out);
void projectShapes(int shapes, int cells, const float* shape, const double* v, double scale, double* out);

} // namespace snaresim
