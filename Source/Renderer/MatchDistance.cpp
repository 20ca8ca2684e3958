#include "MatchDistance.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace snaresim::render
{
namespace
{

constexpr double kWholeScale_dB = 2.0; // the low end of one drum's strikes' spread
constexpr double kCentroidScale_octaves = 1.0 / 3.0;
constexpr double kShareFloor = 0.001; // shares below 0.1 % count as 0.1 % (-30 dB)
constexpr double kShareScale_dB = 3.0;
const double kFallScale = std::log(1.25);
constexpr double kPeakScale_semitones = 0.25;
constexpr double kPeakClip = 4.0;
constexpr double kSpectrumScale_dB = 2.0;
constexpr double kEnvelopeScale_dB = 6.0;
constexpr double kMissing = 4.0; // a feature one signal has and the other not

double ratioTerm(std::optional<double> value, std::optional<double> reference, double scale)
{
    if (! value && ! reference)
        return 0.0;
    if (! value || ! reference || *value <= 0.0 || *reference <= 0.0)
        return kMissing;
    return std::log(*value / *reference) / scale;
}

// Semitones from a peak to the nearest of others (kMissing when there is none).
double nearestPeak_semitones(std::optional<double> peak, const std::vector<std::pair<double, double>>& others)
{
    if (! peak || others.empty())
        return kMissing;
    double nearest = 1e300;
    for (const auto& other : others)
        nearest = std::min(nearest, std::abs(12.0 * std::log2(other.first / *peak)));
    return nearest;
}

} // namespace

StrikeSignature strikeSignature(std::span<const double> samples, double rate, StrikeRules rules)
{
    StrikeSignature signature;
    signature.features = measureStrike(samples, rate, rules);
    signature.envelope = spectralEnvelope(samples, rate, signature.features.onset);
    signature.fingerprint = strikeFingerprint(samples, rate, rules);
    return signature;
}

MatchDistance matchDistance(const StrikeSignature& recording, const StrikeSignature& candidate)
{
    const auto& r = recording.features;
    const auto& c = candidate.features;
    MatchDistance d;

    d.strike_dB = strikeDistance_dB(recording.fingerprint, candidate.fingerprint);
    d.z[0] = d.strike_dB / kWholeScale_dB;

    d.z[1] = ratioTerm(c.tailCentroid_Hz, r.tailCentroid_Hz, kCentroidScale_octaves * std::log(2.0));

    double sum = 0.0;
    for (std::size_t b = 0; b < r.bandShares.size(); ++b)
    {
        const double dB = 10.0 * std::log10((c.bandShares[b] + kShareFloor) / (r.bandShares[b] + kShareFloor));
        sum += (dB / kShareScale_dB) * (dB / kShareScale_dB);
    }
    d.z[2] = std::sqrt(sum / (double) r.bandShares.size());

    // Falls within the window both signals cover; one not seen by then happens at its end.
    const double window_ms = std::min(r.length_ms, c.length_ms);
    auto within = [&](std::optional<double> fall) { return std::max(1.0, std::min(fall.value_or(window_ms), window_ms)); };
    d.z[3] = std::log(within(c.fall20_ms) / within(r.fall20_ms)) / kFallScale;
    d.z[4] = std::log(within(c.fall40_ms) / within(r.fall40_ms)) / kFallScale;

    if (c.lowestPeak_Hz || r.lowestPeak_Hz)
    {
        const double semitones = 0.5 * (nearestPeak_semitones(c.lowestPeak_Hz, r.peaks) + nearestPeak_semitones(r.lowestPeak_Hz, c.peaks));
        d.z[5] = kPeakClip * std::tanh(semitones / (kPeakClip * kPeakScale_semitones));
    }

    d.z[6] = spectrumDistance_dB(recording.envelope, candidate.envelope) / kSpectrumScale_dB;
    d.z[7] = envelopeDistance_dB(recording.envelope, candidate.envelope) / kEnvelopeScale_dB;

    double weighted = 0.0, weights = 0.0;
    for (std::size_t i = 0; i < d.z.size(); ++i)
    {
        weighted += MatchDistance::kWeights[i] * d.z[i] * d.z[i];
        weights += MatchDistance::kWeights[i];
    }
    d.total = std::sqrt(weighted / weights);
    return d;
}

} // namespace snaresim::render
