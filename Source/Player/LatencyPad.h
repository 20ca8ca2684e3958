#pragma once
// A pure delay of whole samples after a drum's output, so that every drum a player plays lags
// its strikes by the same time (BuildOptions::constantLatency): the drums simulated at the
// host's rate wait as long as the ones whose signals are interpolated to it
// (longestLatencySamples, HostRateInterpolator.h). Allocates only in resize().

#include <algorithm>
#include <utility>
#include <vector>

namespace snaresim
{

class LatencyPad
{
public:
    void resize(int samples)
    {
        ring.assign((std::size_t) std::max(0, samples), 0.0f);
        pos = 0;
    }
    int length() const noexcept { return (int) ring.size(); }

    // x[i] leaves as the sample length() later; silence comes out first
    void process(float* x, int n) noexcept
    {
        if (ring.empty())
            return;
        for (int i = 0; i < n; ++i)
        {
            std::swap(x[i], ring[pos]);
            if (++pos == ring.size())
                pos = 0;
        }
    }

    void clear() noexcept
    {
        std::fill(ring.begin(), ring.end(), 0.0f);
        pos = 0;
    }

private:
    std::vector<float> ring;
    std::size_t pos = 0;
};

} // namespace snaresim
