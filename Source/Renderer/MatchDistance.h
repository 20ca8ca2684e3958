#pragma once
// How far a candidate strike is from a recording, for --match: its features (StrikeFeatures.h)
// and its spectral envelope over time (SpectralEnvelope.h) against the recording's, each
// difference divided by a scale that makes it about 1 where the difference is clearly audible,
// combined as a weighted RMS (docs/MATCHING.md has the formula and why):
//
//   D = sqrt( sum_i w_i z_i^2 / sum_i w_i )
//
//   z_centroid = log2(c / c_rec) / (1/3)                 tail centroid, a third of an octave
//   z_bands    = RMS over the 5 bands of 10 log10((s + 0.001) / (s_rec + 0.001)) / 3 dB
//   z_fall20   = ln(t20 / t20_rec) / ln 1.25              25 % longer or shorter
//   z_fall40   = ln(t40 / t40_rec) / ln 1.25
//   z_peak     = 12 log2(p / p_rec) / 1, clipped to +-4   semitones; a different mode counts 4
//   z_envelope = RMS difference of the envelopes / 6 dB
//   weights: 1 each, the envelope 2
//
// The fall times are compared within the shorter of the two signals (a fall that has not
// happened by then counts as happening at its end). Levels never enter: both are normalised.

#include "SpectralEnvelope.h"
#include "StrikeFeatures.h"

#include <array>
#include <span>
#include <string_view>

namespace snaresim::render
{

struct StrikeSignature
{
    StrikeFeatures features;
    SpectralEnvelope envelope;
};

// The features and the envelope of mono samples (throws NotAStrike as measureStrike does).
StrikeSignature strikeSignature(std::span<const double> samples, double sampleRate_Hz, StrikeRules rules);

struct MatchDistance
{
    static constexpr std::array<std::string_view, 6> kTermNames { "centroid", "bands", "fall20", "fall40", "peak", "envelope" };
    static constexpr std::array<double, 6> kWeights { 1.0, 1.0, 1.0, 1.0, 1.0, 2.0 };

    std::array<double, 6> z {}; // each term's scaled difference, in kTermNames' order
    double total = 0.0;         // D
};

MatchDistance matchDistance(const StrikeSignature& recording, const StrikeSignature& candidate);

} // namespace snaresim::render
