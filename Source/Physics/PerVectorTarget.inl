// Compiles the kernels of SNARESIM_KERNELS (a file name) once per vector target, in the
// namespaces isa_avx512, isa_avx2 and isa_baseline of the including scope; the calls pick one
// with SNARESIM_ON_VECTOR_TARGET (VectorTarget.h). Include it where the kernels' own includes
// are already in, once per kernels file:
//
//   #define SNARESIM_KERNELS "MembraneKernels.inl"
//   #include "PerVectorTarget.inl"
//
// The baseline build is the one every x86-64 processor rounds the same (SSE2: no FMA to
// contract into); the others are built for x86-64-v4 and x86-64-v3, as -march would, and
// contract a * b + c into FMAs. SNARESIM_VECTOR_BYTES is the target's vector width in the
// kernels (64, 32, 16), for kernels written with explicit vectors.

#ifndef SNARESIM_KERNELS
#error "define SNARESIM_KERNELS as the kernels' file before including PerVectorTarget.inl"
#endif

#if SNARESIM_VECTOR_TARGETS
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#define SNARESIM_VECTOR_BYTES 64
namespace isa_avx512
{
#include SNARESIM_KERNELS
} // namespace isa_avx512
#undef SNARESIM_VECTOR_BYTES
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
#define SNARESIM_VECTOR_BYTES 32
namespace isa_avx2
{
#include SNARESIM_KERNELS
} // namespace isa_avx2
#undef SNARESIM_VECTOR_BYTES
#pragma GCC pop_options
#endif

#define SNARESIM_VECTOR_BYTES 16
namespace isa_baseline
{
#include SNARESIM_KERNELS
} // namespace isa_baseline
#undef SNARESIM_VECTOR_BYTES

#undef SNARESIM_KERNELS
