#pragma once
// How far a candidate strike is from a recording, for --match: its whole-strike distance
// (StrikeFingerprint.h), its features (StrikeFeatures.h) and its spectral envelope over time
// (SpectralEnvelope.h) against the recording's, each difference divided by a scale that makes it
// about 1 where the difference is clearly audible, combined as a weighted RMS (docs/MATCHING.md
// has the formula and why):
//
//   D = sqrt( sum_i w_i z_i^2 / sum_i w_i )
//
//   z_whole    = D_strike / 2 dB                         the whole-strike distance, the main term
//   z_centroid = log2(c / c_rec) / (1/3)                 tail centroid, a third of an octave
//   z_bands    = RMS over the 5 bands of 10 log10((s + 0.001) / (s_rec + 0.001)) / 3 dB
//   z_fall20   = ln(t20 / t20_rec) / ln 1.25              25 % longer or shorter
//   z_fall40   = ln(t40 / t40_rec) / ln 1.25
//   z_peak     = 4 tanh(s / 1 semitone), s the mean of the two lowest strong peaks' distances
//                (semitones) to the nearest peak of the other strike (down to 24 dB): a quarter
//                of a semitone counts about 1, another mode at most 4; a mode just above the
//                12 dB threshold in one strike and just below in the other is still found
//   z_spectrum = RMS over the bands of the envelopes' difference averaged over time / 2 dB
//   z_envelope = RMS difference of the envelopes over every cell / 6 dB
//   weights: the whole-strike distance 8 (half of the sum), the spectrum 2, the others 1
//
// The fall times are compared within the shorter of the two signals (a fall that has not
// happened by then counts as happening at its end). Levels never enter: both are normalised.

#include "SpectralEnvelope.h"
#include "StrikeFeatures.h"
#include "StrikeFingerprint.h"

#include <array>
#include <span>
#include <string_view>

namespace snaresim::render
{

struct StrikeSignature
{
    StrikeFeatures features;
    SpectralEnvelope envelope;
    StrikeFingerprint fingerprint;
};

// The features, the envelope and the fingerprint of mono samples (throws NotAStrike as
// measureStrike and strikeFingerprint do).
StrikeSignature strikeSignature(std::span<const double> samples, double sampleRate_Hz, StrikeRules rules);

struct MatchDistance
{
    static constexpr std::array<std::string_view, 8> kTermNames { "whole",  "centroid", "bands",    "fall20",
                                                                  "fall40", "peak",     "spectrum", "envelope" };
    static constexpr std::array<double, 8> kWeights { 8.0, 1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0 };

    std::array<double, 8> z {}; // each term's scaled difference, in kTermNames' order
    double strike_dB = 0.0;     // the whole-strike distance (StrikeFingerprint.h)
    double total = 0.0;         // D
};

MatchDistance matchDistance(const StrikeSignature& recording, const StrikeSignature& candidate);

} // namespace snaresim::render
