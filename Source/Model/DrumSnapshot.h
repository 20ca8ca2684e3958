#pragma once
// A picture of the drum's state for display: both heads' displacement resampled on a fixed
// square raster and the snare wires at a fixed number of points, with where they touch the
// carry head. Fixed size, so it is filled on the audio thread without allocating and handed
// to the editor through a lock-free buffer.

#include <array>

namespace snaresim
{

struct DrumSnapshot
{
    static constexpr int raster = 48; // head pixels per side, covering [-R, R]^2
    static constexpr int maxWires = 64;
    static constexpr int wirePoints = 48; // samples along each wire

    std::array<float, raster * raster> batter {}; // displacement (m); 0 outside the head
    std::array<float, raster * raster> carry {};
    std::array<unsigned char, raster * raster> onHead {}; // 1 where the raster point is on the head

    int numWires = 0;
    float wireLength_frac = 0.0f;                                 // wire length over the head diameter
    std::array<float, maxWires> wireY_frac {};                    // wire position across, fraction of R
    std::array<float, maxWires * wirePoints> wire {};             // displacement (m)
    std::array<unsigned char, maxWires * wirePoints> touching {}; // 1 where the wire presses on the head

    bool snaresEngaged = true;
    float peakDisplacement = 0.0f; // largest |w| over both heads (m), for colour scaling
    long long samplesRendered = 0; // host samples since the drum was built or reset
};

} // namespace snaresim
