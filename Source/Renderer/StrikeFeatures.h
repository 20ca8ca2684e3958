#pragma once
// The sound features of one drum strike, as scripts/snare_features.py defines them (its
// docstring is the reference; the two agree to rounding): the onset, the tail's spectral
// centroid (50-300 ms), the band shares of the first 300 ms, the times after which the level
// stays 20 / 40 dB down, and the lowest strong spectral peak of the first 500 ms. --match
// compares a recording's with each candidate's.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace snaresim::render
{

// Why samples are not one strike: silent, shorter than 100 ms, not finite, no strike.
struct NotAStrike : std::invalid_argument
{
    using std::invalid_argument::invalid_argument;
};

// The bands of bandShares: < 1, 1-2, 2-5, 5-10, > 10 kHz.
inline constexpr std::array<double, 6> kShareBandEdges_Hz { 0.0, 1000.0, 2000.0, 5000.0, 10000.0, 1.0e300 };
inline constexpr std::array<std::string_view, 5> kShareBandNames { "<1k", "1-2k", "2-5k", "5-10k", ">10k" };

struct StrikeFeatures
{
    double sampleRate_Hz = 0.0;
    std::size_t onset = 0;                 // sample index of the onset (t = 0)
    double length_ms = 0.0;                // from the onset to the end of the samples
    std::optional<double> tailCentroid_Hz; // 50-300 ms; empty when under 10 ms of tail
    std::array<double, 5> bandShares {};   // of the first 300 ms; they sum to 1
    std::optional<double> fall20_ms;       // empty when the samples end first
    std::optional<double> fall40_ms;
    std::optional<double> lowestPeak_Hz; // empty when no peak qualifies
    // Every peak of that spectrum found as the lowest strong peak is, but down to 24 dB below
    // the largest value: (Hz, dB relative to it), lowest first. --match compares each strike's
    // lowest strong peak with the other's peaks, so that a mode just above 12 dB down in one
    // and just below in the other still counts as the same mode.
    std::vector<std::pair<double, double>> peaks;

    double onset_s() const { return (double) onset / sampleRate_Hz; }
};

// Which of the script's bad-input rules apply.
enum class StrikeRules
{
    recording, // all: shorter than 100 ms, non-finite, silent, no strike (no 20 dB fall after the
               // level's peak, or that peak more than 100 ms after the onset)
    render     // only non-finite and silent: a candidate render may ring past its end
};

// The features of mono samples (the DC offset is removed here). Throws NotAStrike with a
// short reason ("silent", "shorter than 100 ms (50.0 ms)", ...).
StrikeFeatures measureStrike(std::span<const double> samples, double sampleRate_Hz, StrikeRules rules = StrikeRules::recording);

} // namespace snaresim::render
