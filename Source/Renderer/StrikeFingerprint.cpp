#include "StrikeFingerprint.h"

#include "Formatted.h"
#include "StrikeFeatures.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace snaresim::render
{
namespace
{

constexpr std::size_t kShortestWindow = 16;
constexpr std::size_t kShortestTransform = 8192;
constexpr double kSilent = 1e-7;         // -140 dB of full scale
constexpr double kOnsetThreshold = 0.05; // of the peak
constexpr double kOnsetLead_s = 0.001;
constexpr double kLeastFall_dB = 3.0; // a strike's tail below its attack

// The band energies of one window: Hann-weighted, zero-padded, |rfft|^2 summed per band.
std::array<double, StrikeFingerprint::kBands> bandEnergies(std::span<const double> window, double rate)
{
    std::array<double, StrikeFingerprint::kBands> energy {};
    if (window.size() < kShortestWindow)
        return energy; // a window of zeros

    std::size_t n = 1;
    while (n < std::max(window.size(), kShortestTransform))
        n *= 2;
    std::vector<double> frame(n, 0.0);
    const double last = (double) (window.size() - 1);
    for (std::size_t i = 0; i < window.size(); ++i)
        frame[i] = window[i] * (0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (double) i / last));

    Eigen::FFT<double> fft;
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, frame);

    // numpy.fft.rfftfreq's bin spacing, computed as it computes it.
    const double binSpacing = 1.0 / ((double) n * (1.0 / rate));
    for (int b = 0; b < StrikeFingerprint::kBands; ++b)
    {
        const double centre = fingerprintBandCentre_Hz(b);
        const double lower = centre * std::pow(2.0, -1.0 / 6.0), upper = centre * std::pow(2.0, 1.0 / 6.0);
        for (std::size_t k = (std::size_t) std::max(0.0, std::floor(lower / binSpacing) - 1.0); k < n / 2 + 1; ++k)
        {
            const double f = (double) k * binSpacing;
            if (f >= upper)
                break;
            if (f >= lower)
                energy[(std::size_t) b] += std::norm(spectrum[k]);
        }
    }
    return energy;
}

double rms(std::span<const double> x)
{
    double sum = 0.0;
    for (const double v : x)
        sum += v * v;
    return x.empty() ? 0.0 : std::sqrt(sum / (double) x.size());
}

} // namespace

double fingerprintBandCentre_Hz(int band) { return 100.0 * std::pow(2.0, (double) band / 3.0); }

StrikeFingerprint strikeFingerprint(std::span<const double> samples, double rate, StrikeRules rules)
{
    if (samples.empty())
        throw NotAStrike("no samples");
    double peak = 0.0;
    for (const double v : samples)
    {
        if (! std::isfinite(v))
            throw NotAStrike("non-finite samples");
        peak = std::max(peak, std::abs(v));
    }
    if (peak < kSilent)
        throw NotAStrike("silent");

    // Normalised to the peak; the strike starts 1 ms before the first sample above 5 % of it.
    std::vector<double> x(samples.begin(), samples.end());
    for (auto& v : x)
        v /= peak;
    std::size_t firstLoud = 0;
    while (! (std::abs(x[firstLoud]) > kOnsetThreshold))
        ++firstLoud;
    const auto lead = (std::size_t)(kOnsetLead_s * rate);
    const std::span<const double> strike = std::span<const double>(x).subspan(firstLoud > lead ? firstLoud - lead : 0);

    // Window w: samples int(a * rate) to int(b * rate) of the strike, as far as it goes.
    auto window = [&](int w) {
        const auto from = std::min((std::size_t)(StrikeFingerprint::kWindowEdges_s[(std::size_t) w] * rate), strike.size());
        const auto to = std::min((std::size_t)(StrikeFingerprint::kWindowEdges_s[(std::size_t) w + 1] * rate), strike.size());
        return strike.subspan(from, std::max(from, to) - from);
    };

    // A strike falls: its last window's RMS lies 3 dB or more below its first's.
    const double attack = rms(window(0)), tail = rms(window(StrikeFingerprint::kWindows - 1));
    if (rules == StrikeRules::recording && tail > attack * std::pow(10.0, -kLeastFall_dB / 20.0))
        throw NotAStrike(formatted("no strike (its level does not fall: 100-300 ms after the onset %+.1f dB against the first 30 ms,"
                                   " not %.0f dB below)",
                                   20.0 * std::log10(tail / attack), kLeastFall_dB));

    // The 69 energies in dB of their sum, floored.
    std::array<double, StrikeFingerprint::kCells> energy {};
    for (int w = 0; w < StrikeFingerprint::kWindows; ++w)
    {
        const auto bands = bandEnergies(window(w), rate);
        std::copy(bands.begin(), bands.end(), energy.begin() + w * StrikeFingerprint::kBands);
    }
    double total = 0.0;
    for (const double e : energy)
        total += e;
    total = std::max(total, 1e-300);

    StrikeFingerprint fingerprint;
    for (std::size_t i = 0; i < energy.size(); ++i)
        fingerprint.level_dB[i] = std::max(10.0 * std::log10(energy[i] / total + 1e-300), StrikeFingerprint::kFloor_dB);
    return fingerprint;
}

double strikeDistance_dB(const StrikeFingerprint& a, const StrikeFingerprint& b)
{
    double sum = 0.0;
    for (std::size_t i = 0; i < a.level_dB.size(); ++i)
        sum += (a.level_dB[i] - b.level_dB[i]) * (a.level_dB[i] - b.level_dB[i]);
    return std::sqrt(sum / (double) a.level_dB.size());
}

} // namespace snaresim::render
