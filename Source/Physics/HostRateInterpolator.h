#pragma once
// The drum's signals at the host's rate when the physics runs at a whole fraction of it: at
// 88.2 kHz and above the drum is simulated at the host's rate / L (L a power of two, the
// simulated rate 44.1 kHz or more: physicsRateFor) and each signal interpolated L times by a
// linear-phase low-pass FIR in polyphase form. Its band: flat to 0.45 of the simulated rate
// (21.6 kHz at 48 kHz, 19.8 at 44.1), everything from 0.5 of it (the images of the simulated
// band) at least 100 dB down (Kaiser window, beta 10.06); its delay (taps - 1) / 2 host
// samples, 1.34 ms at 96 and 192 kHz. The grids' cost grows with the rate squared and more,
// the interpolation's with the rate.
// Not a component: it stores no energy and exerts no force. Real-time safe after construction.

#include <array>
#include <vector>

namespace snaresim
{

class HostRateInterpolator
{
public:
    static constexpr int numChannels = 4;

    // factor L (1: the signals pass as they are)
    explicit HostRateInterpolator(int factor);

    int factor() const { return L; }
    // the filter's delay in host samples (0 for L = 1)
    int delay() const { return L > 1 ? (taps - 1) / 2 : 0; }
    int length() const { return taps; }

    // a new simulated sample of each channel (once every L host samples, before phase 0)
    void push(const std::array<double, numChannels>& x) noexcept;
    // channel c at host phase p (0 .. L - 1) after the last push
    double value(int c, int phase) const noexcept;
    void clear() noexcept;

private:
    int L;
    int perPhase = 1;         // taps of each phase (M)
    int taps = 1;             // M L - 1, odd: a whole delay
    std::vector<double> h;    // phase-major: phase p's taps h[p + m L] at [p M + m]
    std::vector<double> ring; // per channel, 2 M samples, the newest at pos and pos + M
    int pos = 0;
};

// The rate the drum is simulated at for a host rate: the host's rate halved while it stays at
// 44.1 kHz or above (88.2 and 96 kHz: 44.1 and 48; 176.4 and 192 kHz: the same; up to 88 kHz:
// the host's rate).
double physicsRateFor(double hostRate_Hz) noexcept;

} // namespace snaresim
