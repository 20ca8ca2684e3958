#include "SpectralEnvelope.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <numeric>

namespace snaresim::render
{

double envelopeBandCentre_Hz(int band) { return 1000.0 * std::exp2((double) (band - 10) / 3.0); }

SpectralEnvelope spectralEnvelope(std::span<const double> samples, double rate, std::size_t onset)
{
    constexpr int F = SpectralEnvelope::kFrames, B = SpectralEnvelope::kBands;
    const double mean = samples.empty() ? 0.0 : std::accumulate(samples.begin(), samples.end(), 0.0) / (double) samples.size();
    const auto frameLength = (std::size_t) std::max(16L, std::lround(SpectralEnvelope::kFrame_s * rate));
    const auto hop = (std::size_t) std::max(1L, std::lround(SpectralEnvelope::kHop_s * rate));
    std::size_t fftSize = 1;
    while (fftSize < frameLength)
        fftSize *= 2;

    // Each bin's band (-1: none).
    std::vector<int> bandOf(fftSize / 2 + 1, -1);
    for (std::size_t k = 0; k < bandOf.size(); ++k)
    {
        const double hz = (double) k * rate / (double) fftSize;
        for (int b = 0; b < B; ++b)
            if (hz >= envelopeBandCentre_Hz(b) * std::exp2(-1.0 / 6.0) && hz < envelopeBandCentre_Hz(b) * std::exp2(1.0 / 6.0))
                bandOf[k] = b;
    }

    Eigen::FFT<double> fft;
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    std::vector<double> frame(fftSize);
    std::vector<std::complex<double>> spectrum;
    std::vector<double> energy((std::size_t)(F * B), 0.0);
    for (int t = 0; t < F; ++t)
    {
        std::fill(frame.begin(), frame.end(), 0.0);
        const std::size_t start = onset + (std::size_t) t * hop;
        for (std::size_t i = 0; i < frameLength && start + i < samples.size(); ++i)
            frame[i] = (samples[start + i] - mean) * (0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (double) i / (double) frameLength));
        fft.fwd(spectrum, frame);
        for (std::size_t k = 0; k < bandOf.size(); ++k)
            if (bandOf[k] >= 0)
                energy[(std::size_t)(t * B + bandOf[k])] += std::norm(spectrum[k]);
    }

    const double total = std::accumulate(energy.begin(), energy.end(), 0.0);
    SpectralEnvelope envelope;
    envelope.level_dB.resize(energy.size());
    double loudest = -1e300;
    for (std::size_t i = 0; i < energy.size(); ++i)
    {
        envelope.level_dB[i] = total > 0.0 ? 10.0 * std::log10(std::max(energy[i] / total, 1e-30)) : -300.0;
        loudest = std::max(loudest, envelope.level_dB[i]);
    }
    for (auto& level : envelope.level_dB)
        level = std::max(level, loudest - SpectralEnvelope::kFloor_dB);
    return envelope;
}

double envelopeDistance_dB(const SpectralEnvelope& a, const SpectralEnvelope& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.level_dB.size(); ++i)
        sum += (a.level_dB[i] - b.level_dB[i]) * (a.level_dB[i] - b.level_dB[i]);
    return std::sqrt(sum / (double) a.level_dB.size());
}

double spectrumDistance_dB(const SpectralEnvelope& a, const SpectralEnvelope& b)
{
    double sum = 0.0;
    for (int band = 0; band < SpectralEnvelope::kBands; ++band)
    {
        double mean = 0.0;
        for (int t = 0; t < SpectralEnvelope::kFrames; ++t)
            mean += (a.at(t, band) - b.at(t, band)) / SpectralEnvelope::kFrames;
        sum += mean * mean;
    }
    return std::sqrt(sum / SpectralEnvelope::kBands);
}

} // namespace snaresim::render
