#pragma once
// What the golden tests share: whether the references are being regenerated, and the
// difference of a render from its reference.

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace golden
{

// SNARESIM_UPDATE_GOLDENS=1: the references are written, not compared.
inline bool updating()
{
    const char* v = std::getenv("SNARESIM_UPDATE_GOLDENS");
    return v != nullptr && std::string(v) == "1";
}

struct Difference
{
    long differing = 0;
    double maxAbs = 0.0;
    double dbBelowSignal = INFINITY; // of the RMS difference, relative to the reference's RMS
};

inline Difference compare(const std::vector<std::vector<float>>& reference, const std::vector<std::vector<float>>& now)
{
    Difference d;
    double signal = 0.0, error = 0.0;
    for (size_t ch = 0; ch < reference.size(); ++ch)
        for (size_t i = 0; i < reference[ch].size(); ++i)
        {
            const double r = reference[ch][i], x = now[ch][i];
            signal += r * r;
            error += (x - r) * (x - r);
            if (x != r)
                ++d.differing;
            d.maxAbs = std::max(d.maxAbs, std::abs(x - r));
        }
    if (error > 0.0)
        d.dbBelowSignal = 10.0 * std::log10(signal / error);
    return d;
}

} // namespace golden
