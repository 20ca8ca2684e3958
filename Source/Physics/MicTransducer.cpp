#include "MicTransducer.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace snaresim
{

namespace
{
// An analog section (b2 s^2 + b1 s + b0) / (a2 s^2 + a1 s + a0), s in units of its frequency f0.
struct Prototype
{
    double f0, b2, b1, b0, a2, a1, a0;
};

// The SM57's on-axis response relative to 1 kHz: high-pass, presence peak, low-pass.
std::array<Prototype, 3> dynamicCardioid()
{
    const double peak = std::pow(10.0, 3.969 / 40.0); // sqrt of the peak's gain
    constexpr double qHigh = 0.409, qPeak = 1.078, qLow = 1.354;
    return { {
        { 55.31, 1.0, 0.0, 0.0, 1.0, 1.0 / qHigh, 1.0 },
        { 4468.9, 1.0, peak / qPeak, 1.0, 1.0, 1.0 / (peak * qPeak), 1.0 },
        { 8907.3, 0.0, 0.0, 1.0, 1.0, 1.0 / qLow, 1.0 }, // (matched, not bilinear: below)
    } };
}
} // namespace

MicResponse::MicResponse(double sampleRate_Hz) : sampleRate(sampleRate_Hz)
{
    const auto prototypes = dynamicCardioid();
    for (size_t i = 0; i < 2; ++i)
    {
        // The high-pass and the presence peak: s / w0 = K (1 - z^-1) / (1 + z^-1),
        // K = 1 / tan(w0 T / 2), exact at f0 (a peak above the rate's Nyquist frequency is held
        // just below it).
        const Prototype& p = prototypes[i];
        const double w0T = std::min(2.0 * std::numbers::pi * p.f0 / sampleRate_Hz, 0.95 * std::numbers::pi);
        const double K = 1.0 / std::tan(0.5 * w0T), KK = K * K;
        const double a0 = p.a2 * KK + p.a1 * K + p.a0;
        Section& s = sections[i];
        s.b0 = (p.b2 * KK + p.b1 * K + p.b0) / a0;
        s.b1 = 2.0 * (p.b0 - p.b2 * KK) / a0;
        s.b2 = (p.b2 * KK - p.b1 * K + p.b0) / a0;
        s.a1 = 2.0 * (p.a0 - p.a2 * KK) / a0;
        s.a2 = (p.a2 * KK - p.a1 * K + p.a0) / a0;
    }
    // The low-pass, whose skirt reaches the Nyquist frequency: the analog poles mapped by
    // z = exp(sT) and the numerator matched to the analog magnitude at DC and at the Nyquist
    // frequency (M. Vicanek, "Matched Second Order Digital Filters", 2016): within 0.3 dB of the
    // prototype to 15 kHz at 44.1 kHz, where the bilinear transform is 5 dB low. Above the
    // rate's Nyquist frequency it passes all.
    const Prototype& p = prototypes[2];
    const double w0 = 2.0 * std::numbers::pi * p.f0 / sampleRate_Hz;
    Section& s = sections[2];
    if (w0 < 0.9 * std::numbers::pi)
    {
        const double q = 1.0 / p.a1, zeta = 0.5 * p.a1;
        s.a1 = zeta <= 1.0 ? -2.0 * std::exp(-zeta * w0) * std::cos(std::sqrt(1.0 - zeta * zeta) * w0)
                           : -2.0 * std::exp(-zeta * w0) * std::cosh(std::sqrt(zeta * zeta - 1.0) * w0);
        s.a2 = std::exp(-2.0 * zeta * w0);
        const double A0 = (1.0 + s.a1 + s.a2) * (1.0 + s.a1 + s.a2), A1 = (1.0 - s.a1 + s.a2) * (1.0 - s.a1 + s.a2), A2 = -4.0 * s.a2;
        const double phi1 = std::sin(0.5 * w0) * std::sin(0.5 * w0), phi0 = 1.0 - phi1, phi2 = 4.0 * phi0 * phi1;
        const double R1 = (A0 * phi0 + A1 * phi1 + A2 * phi2) * q * q;
        const double B1 = std::max(0.0, (R1 - A0 * phi0) / phi1);
        s.b0 = 0.5 * (std::sqrt(A0) + std::sqrt(B1));
        s.b1 = std::sqrt(A0) - s.b0;
        s.b2 = 0.0;
    }
    // relative to 1 kHz
    const double g = 1.0 / gainAt(1000.0);
    sections[0].b0 *= g;
    sections[0].b1 *= g;
    sections[0].b2 *= g;
}

double MicResponse::process(double x) noexcept
{
    for (Section& s : sections)
    {
        const double y = s.b0 * x + s.s1;
        s.s1 = s.b1 * x - s.a1 * y + s.s2;
        s.s2 = s.b2 * x - s.a2 * y;
        x = y;
    }
    return x;
}

void MicResponse::clear() noexcept
{
    for (Section& s : sections)
        s.s1 = s.s2 = 0.0;
}

double MicResponse::gainAt(double f_Hz) const noexcept
{
    const std::complex<double> z = std::polar(1.0, -2.0 * std::numbers::pi * f_Hz / sampleRate); // z^-1
    std::complex<double> h = 1.0;
    for (const Section& s : sections)
        h *= (s.b0 + s.b1 * z + s.b2 * z * z) / (1.0 + s.a1 * z + s.a2 * z * z);
    return std::abs(h);
}

} // namespace snaresim
