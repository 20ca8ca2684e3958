#pragma once
// snaresim-render --match RECORDING -o PRESET_FILE: the drum's parameters whose strike comes
// closest to a recorded one (MatchDistance.h), found by MatchSearch.h's search over the
// parameters of --match-params, written as a preset file (docs/MATCHING.md).
//
// The recording is read (WAV, AIFF or FLAC, channels averaged) and measured first: unreadable,
// silent, shorter than 100 ms or no strike is a UserError before any render. Each candidate is
// one strike of the drum built from the parameters (makeDrumConfig, played through the
// player as the plug-in plays it), kMatchSeconds long, at the recording's sample rate
// (48 kHz when that is outside 32..96 kHz; the features are in Hz and ms either way).

#include "RenderJob.h"

#include <algorithm>
#include <string>

namespace snaresim::render
{

inline constexpr double kMatchSeconds = 0.6;
inline constexpr int kMatchFixedVelocity = 100;    // when velocity is not searched
inline constexpr int kMatchFinalists = 3;          // re-rendered at velocity -4 and +4 at the end
inline constexpr int kDefaultMatchSeed = 20240611; // --match-seed
// Without --preset and --match-params, and with at least this budget, the search starts from the
// factory preset whose strike lies nearest the recording (its renders count in the budget).
inline constexpr int kPresetStartBudget = 60;
// With at least this budget, a second search starts from the second-nearest factory preset and
// the searches share what is left evenly: the nearest preset by one strike is not always the
// basin of the best match (what is not searched, such as the mallet's felt and the shell, comes
// with it).
inline constexpr int kSecondStartBudget = 300;
// From three times this budget on, one search from each of the budget / kRendersPerSearch
// nearest factory presets (--match-budget 1200: three, 2400: six), up to every preset.
inline constexpr int kRendersPerSearch = 400;

// How many searches a budget starts from the nearest factory presets.
constexpr int presetSearches(int budget)
{
    if (budget < kPresetStartBudget)
        return 0;
    if (budget < kSecondStartBudget)
        return 1;
    return std::max(2, budget / kRendersPerSearch);
}

// The default --match-params (velocity: the strike's MIDI velocity, searched with them); with
// the snares off at the start, snare_tension and snare_count are left out.
std::string defaultMatchParams();

// Runs the match; prints the progress on stderr (not with --json) and the result on stdout.
// Returns the exit status (0).
int runMatch(const RenderJob& job);

} // namespace snaresim::render
