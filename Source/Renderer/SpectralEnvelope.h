#pragma once
// A strike's spectral envelope over time, for --match: the level in third-octave bands
// (centres 1000 * 2^(j/3) Hz, j = -10..9: 99 Hz to 8 kHz) of short frames over the first
// 300 ms after the onset (Hann frames of 40 ms every 10 ms: 27 of them), in dB of the whole
// picture's energy, so that the recording's arbitrary level drops out, and floored 45 dB below
// the loudest cell, above a recording's noise floor (typically 55 to 70 dB down), so that neither
// noise nor silence far below the strike counts.

#include <cstddef>
#include <span>
#include <vector>

namespace snaresim::render
{

struct SpectralEnvelope
{
    static constexpr int kFrames = 27;
    static constexpr int kBands = 20;
    static constexpr double kFrame_s = 0.040, kHop_s = 0.010, kFloor_dB = 45.0;

    std::vector<double> level_dB; // kFrames x kBands, frame-major

    double at(int frame, int band) const { return level_dB[(std::size_t)(frame * kBands + band)]; }
};

// The centre of band b (0 .. kBands - 1), Hz.
double envelopeBandCentre_Hz(int band);

// samples: mono; onset: the index of t = 0 (StrikeFeatures::onset). Frames past the end hold
// zeros. Bands above the Nyquist frequency stay at the floor.
SpectralEnvelope spectralEnvelope(std::span<const double> samples, double sampleRate_Hz, std::size_t onset);

// The RMS difference of two envelopes over every cell, dB.
double envelopeDistance_dB(const SpectralEnvelope& a, const SpectralEnvelope& b);

// The RMS over the bands of their difference averaged over the frames, dB: the spectrum's
// shape over the 300 ms. A chaotic buzz varies from cell to cell and strike to strike; its
// average over the frames much less.
double spectrumDistance_dB(const SpectralEnvelope& a, const SpectralEnvelope& b);

} // namespace snaresim::render
