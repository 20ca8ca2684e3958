#pragma once
// A whole strike's fingerprint and the distance of two strikes (docs/MATCHING.md, "The
// distance of two strikes"): the energy in 23 third-octave bands (centres 100 * 2^(k/3) Hz,
// k = 0..22: 100 Hz to 16 kHz) over three windows after the onset (0-30, 30-100, 100-300 ms),
// each of the 69 energies in dB of their sum, floored at -60 dB. The distance is the RMS of
// two fingerprints' difference, in dB.
//
// The samples are normalised to their peak; the onset is the first sample above 5 % of it,
// moved 1 ms earlier. A window runs from sample int(a * rate) to int(b * rate) after the onset,
// is Hann-weighted (symmetric), zero-padded to the next power of two of at least 8192 points
// and its power spectrum's bins f with c * 2^(-1/6) <= f < c * 2^(1/6) make band c; a window
// shorter than 16 samples holds nothing.

#include "StrikeFeatures.h"

#include <array>
#include <cstddef>
#include <span>

namespace snaresim::render
{

struct StrikeFingerprint
{
    static constexpr int kWindows = 3;
    static constexpr int kBands = 23;
    static constexpr int kCells = kWindows * kBands;
    static constexpr double kFloor_dB = -60.0;
    static constexpr std::array<double, kWindows + 1> kWindowEdges_s { 0.0, 0.030, 0.100, 0.300 };

    std::array<double, kCells> level_dB {}; // window-major

    double at(int window, int band) const { return level_dB[(std::size_t)(window * kBands + band)]; }
};

// The centre of band k (0 .. kBands - 1), Hz.
double fingerprintBandCentre_Hz(int band);

// The fingerprint of mono samples at any level. Throws NotAStrike (StrikeFeatures.h) when they
// are empty, not finite, silent (peak below -140 dB of full scale) or, with the recording rules,
// hold no strike: their level does not fall, the RMS of 100-300 ms after the onset less than
// 3 dB below that of the first 30 ms (a candidate of --match may ring longer).
StrikeFingerprint strikeFingerprint(std::span<const double> samples, double sampleRate_Hz, StrikeRules rules = StrikeRules::recording);

// The RMS of the 69 differences, dB: 0 for the same strike, symmetric.
double strikeDistance_dB(const StrikeFingerprint& a, const StrikeFingerprint& b);

} // namespace snaresim::render
