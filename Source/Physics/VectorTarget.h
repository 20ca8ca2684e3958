#pragma once
// The vector target: which build of the hot loops (the *Kernels.inl files, compiled once per
// target by PerVectorTarget.inl) this process runs. Chosen once, at start: the widest the
// processor has, or the one SNARESIM_VECTOR_TARGET names (baseline | avx2 | avx512).
//
//   baseline  x86-64 (SSE2): no FMA, two doubles a vector. Every x86-64 processor computes
//             the same bits on it, so the golden renders are made and compared on it.
//   avx2      x86-64-v3 (AVX2 and FMA): a * b + c contracted into FMAs, four doubles a vector.
//   avx512    x86-64-v4 (AVX-512): eight doubles a vector.
//
// Each target sums in its own lane width and rounds its FMAs once, so their outputs differ in
// the last bits, and the snares' collisions lift that to an audible difference within a
// fraction of a second: a different strike of the same drum, not a different drum
// (docs/VECTOR_TARGETS.md gives the measured bounds). A name the processor lacks gets one line
// on stderr and the widest it has. Builds other than GCC on x86-64 (clang, arm64) have the
// baseline path only.

#include <string>
#include <string_view>

// 1 where the hot loops are built for each target (GCC on x86-64), 0 where only the baseline is.
#if defined(__x86_64__) && defined(__GNUC__) && ! defined(__clang__)
#define SNARESIM_VECTOR_TARGETS 1
#else
#define SNARESIM_VECTOR_TARGETS 0
#endif

namespace snaresim
{

enum class VectorTarget
{
    baseline,
    avx2,
    avx512,
};

namespace detail
{
// Set when the engine library is loaded (before it, zero: the baseline).
extern const VectorTarget vectorTargetInForce;
} // namespace detail

// The target in force, the same for the process's whole life.
inline VectorTarget vectorTarget() noexcept { return detail::vectorTargetInForce; }

// "baseline", "avx2", "avx512".
std::string_view vectorTargetName(VectorTarget target) noexcept;

// The widest target this build and this processor run.
VectorTarget widestVectorTarget() noexcept;

// What SNARESIM_VECTOR_TARGET=`requested` selects on a processor whose widest target is
// `widest` (nullptr or empty: `widest`), and, where it cannot be had, the one line to print.
struct VectorTargetChoice
{
    VectorTarget target;
    std::string warning; // empty when the request is met
};
VectorTargetChoice chooseVectorTarget(const char* requested, VectorTarget widest);

} // namespace snaresim

// SNARESIM_ON_VECTOR_TARGET(f<...>): the build of kernel f (a function of a *Kernels.inl
// included through PerVectorTarget.inl) for the target in force; SNARESIM_ON_VECTOR_TARGET(f(x))
// calls it.
#if SNARESIM_VECTOR_TARGETS
#define SNARESIM_ON_VECTOR_TARGET(...)                                                                                                     \
    (::snaresim::vectorTarget() == ::snaresim::VectorTarget::avx512 ? isa_avx512::__VA_ARGS__                                              \
     : ::snaresim::vectorTarget() == ::snaresim::VectorTarget::avx2 ? isa_avx2::__VA_ARGS__                                                \
                                                                    : isa_baseline::__VA_ARGS__)
#else
#define SNARESIM_ON_VECTOR_TARGET(...) (isa_baseline::__VA_ARGS__)
#endif
