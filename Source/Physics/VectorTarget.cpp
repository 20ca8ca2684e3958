#include "VectorTarget.h"

#include <cstdio>
#include <cstdlib>

namespace snaresim
{

std::string_view vectorTargetName(VectorTarget target) noexcept
{
    switch (target)
    {
        case VectorTarget::avx512: return "avx512";
        case VectorTarget::avx2: return "avx2";
        case VectorTarget::baseline: break;
    }
    return "baseline";
}

VectorTarget widestVectorTarget() noexcept
{
#if SNARESIM_VECTOR_TARGETS
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v4"))
        return VectorTarget::avx512;
    if (__builtin_cpu_supports("x86-64-v3"))
        return VectorTarget::avx2;
#endif
    return VectorTarget::baseline;
}

VectorTargetChoice chooseVectorTarget(const char* requested, VectorTarget widest)
{
    if (requested == nullptr || *requested == '\0')
        return { widest, {} };
    const std::string_view name(requested);
    for (const auto target : { VectorTarget::baseline, VectorTarget::avx2, VectorTarget::avx512 })
        if (name == vectorTargetName(target))
        {
            if (target <= widest)
                return { target, {} };
            return
            {
                widest, "SNARESIM_VECTOR_TARGET=" + std::string(name) +
                            ": not available on this "
#if SNARESIM_VECTOR_TARGETS
                            "processor"
#else
                            "build (it has the baseline path only)"
#endif
                            "; using " +
                            std::string(vectorTargetName(widest))
            };
        }
    return { widest, "SNARESIM_VECTOR_TARGET=" + std::string(name) + ": not one of baseline, avx2, avx512; using " +
                         std::string(vectorTargetName(widest)) };
}

namespace detail
{
// Decided when the library is loaded: the line a request that cannot be met prints comes then,
// never from an audio thread.
const VectorTarget vectorTargetInForce = [] {
    const auto choice = chooseVectorTarget(std::getenv("SNARESIM_VECTOR_TARGET"), widestVectorTarget());
    if (! choice.warning.empty())
        std::fprintf(stderr, "%s\n", choice.warning.c_str());
    return choice.target;
}();
} // namespace detail

} // namespace snaresim
