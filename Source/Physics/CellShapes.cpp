#include "CellShapes.h"

#include "VectorTarget.h"

#include <algorithm>

namespace snaresim
{

namespace
{
#define SNARESIM_KERNELS "CellShapesKernels.inl"
#include "PerVectorTarget.inl"
} // namespace

void combineShapes(int shapes, int cells, const double* weight, const double* shape, double* out)
{
    SNARESIM_ON_VECTOR_TARGET(combine(shapes, cells, weight, shape, out));
}

void combineShapes(int shapes, int cells, const double* weight, const float* shape, double* out)
{
    SNARESIM_ON_VECTOR_TARGET(combine(shapes, cells, weight, shape, out));
}

void projectShapes(int shapes, int cells, const double* shape, const double* v, double scale, double* out)
{
    SNARESIM_ON_VECTOR_TARGET(project(shapes, cells, shape, v, scale, out));
}

void projectShapes(int shapes, int cells, const float* shape, const double* v, double scale, double* out)
{
    SNARESIM_ON_VECTOR_TARGET(project(shapes, cells, shape, v, scale, out));
}

} // namespace snaresim
