#pragma once
// A microphone's transducer: what it makes of the sound pressure at its point. The pressure
// microphone gives the pressure itself. The dynamic cardioid gives the published on-axis
// response of the Shure SM57 (the Unidyne III capsule, also in the SM58), relative to 1 kHz:
// an analog prototype of three sections, high-pass (55 Hz, Q 0.41), presence peak (4.47 kHz,
// +3.97 dB, Q 1.08) and low-pass (8.91 kHz, Q 1.35), within 1.2 dB of the chart's points from
// 40 Hz to 15 kHz (docs/MODEL.md, "Microphones"); the first two taken to the sample rate by the
// bilinear transform prewarped at their own frequencies, the low-pass by matching its poles and
// magnitude (within 0.3 dB to 15 kHz at 44.1 kHz). The proximity effect of the capsule's
// pressure-gradient half is not modelled. A listener's part: no energy, no force.
// Real-time safe: process allocates nothing.

#include <array>

namespace snaresim
{

enum class MicTransducer
{
    pressure,       // the sound pressure itself
    dynamicCardioid // the SM57's response
};

class MicResponse
{
public:
    explicit MicResponse(double sampleRate_Hz);

    // The dynamic cardioid's output for the next pressure sample (Pa in, Pa at 1 kHz out).
    double process(double pressure) noexcept;
    void clear() noexcept;

    // The dynamic cardioid's gain at f (Hz) at this rate, as process applies it (tests).
    double gainAt(double f_Hz) const noexcept;

private:
    struct Section // direct form II transposed
    {
        double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
        double s1 = 0.0, s2 = 0.0;
    };
    std::array<Section, 3> sections;
    double sampleRate;
};

} // namespace snaresim
