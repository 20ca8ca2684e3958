#pragma once
// The drum's signals at the host's rate when the physics runs at a fraction M / L of it
// (simulatedRateFor): each signal interpolated L times by a linear-phase low-pass FIR in
// polyphase form, then every M-th sample of that kept (M < L, so each host sample needs at most
// one new simulated sample). Its band: flat to 0.45 of the simulated rate (14.4 kHz at 32 kHz,
// 21.6 at 48), everything from 0.5 of it (the images of the simulated band, and what would
// alias in the keeping of every M-th) at least 100 dB down (Kaiser window, beta 10.06); its
// delay (taps - 1) / 2 samples at L times the simulated rate (2.0 ms at 32 kHz, 1.34 ms at 48).
// The grids' cost grows with the rate squared and more, the interpolation's with the rate.
// Not a component: it stores no energy and exerts no force. Real-time safe after construction.

#include "CacheAligned.h"

#include <array>
#include <vector>

namespace snaresim
{

class HostRateInterpolator
{
public:
    static constexpr int numChannels = 4;

    // up L, down M (L = 1: the signals pass as they are)
    explicit HostRateInterpolator(int up, int down = 1);

    int factor() const { return L; }
    int down() const { return M; }
    // the filter's delay in samples at L times the simulated rate (0 for L = 1)
    int delay() const { return delayFor(L); }
    int length() const { return taps; }
    // the same for an interpolation by `up`, without building it
    static int delayFor(int up) noexcept { return (tapsFor(up) - 1) / 2; }

    // a new simulated sample of each channel (before the phase at which it is due: below M)
    void push(const std::array<double, numChannels>& x) noexcept;
    // channel c at phase p (0 .. L - 1) of L times the simulated rate after the last push; host
    // sample n stands at phase n M mod L, and a simulated sample is due before the phases below M
    double value(int c, int phase) const noexcept;
    void clear() noexcept;

private:
    static int perPhaseFor(int up) noexcept;
    static int tapsFor(int up) noexcept;

    int L, M;
    int perPhase = 1;           // taps of each phase (P)
    int taps = 1;               // P L - 1 or one less, odd: a whole delay
    AlignedVector<double> h;    // phase-major: phase p's taps h[p + m L] at [p P + m]
    AlignedVector<double> ring; // per channel, 2 P samples, the newest at pos and pos + P
    int pos = 0;
};

// The rate the drum is simulated at, as the host's rate times down / up.
struct SimulatedRate
{
    double rate_Hz;
    int up = 1, down = 1;
};

// Grids this coarse or coarser (in multiples of their stability bound at the 48 kHz step:
// bandwidths to 8.1 kHz, the default's 7.84 kHz among them) are simulated at kReducedRate_Hz or
// a little above: stable there from a coarseness of 1.5 (1.45 at 33.075 kHz).
constexpr double kReducedRateCoarseness = 1.9;
constexpr double kReducedRate_Hz = 32000.0;

// The rate the drum is simulated at for a host rate and the grids' coarseness: the host's rate
// halved while it stays at 44.1 kHz or above (88.2 and 96 kHz: 44.1 and 48; 176.4 and 192 kHz:
// the same; up to 88 kHz: the host's rate); then, for a rate of 44.1 to 48 kHz and grids of
// kReducedRateCoarseness or coarser, two thirds of it, or three quarters where that falls below
// 32 kHz (48 kHz: 32; 44.1 kHz: 33.075). That band (flat to 14.4 and 14.9 kHz) holds the grids'
// band and the contacts' overtones above it (docs/MODEL.md, "The host's rate").
SimulatedRate simulatedRateFor(double hostRate_Hz, double gridCoarseness) noexcept;

// The longest lag of the signals behind the simulation at this host rate over every grid's
// simulated rate (HostRateInterpolator::delay in host samples): 96 at 48 kHz, 85.7 at 44.1,
// 192 at 96 (the default's grids), 0 where every grid is simulated at the host's rate. A
// client that keeps one latency whatever drum plays pads every drum to it.
double longestLatencySamples(double hostRate_Hz) noexcept;

} // namespace snaresim
