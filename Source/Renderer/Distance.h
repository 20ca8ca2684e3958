#pragma once
// snaresim-render --distance FILE ... --ref KITDIR:GLOB ...: each strike's distance
// (StrikeFingerprint.h) to every recording --ref names, and its nearest; a render with --ref
// measures the WAV it writes the same way.
//
// Every file is read as one channel (WAV, AIFF or FLAC, channels averaged) and measured before
// anything is printed or written: an unreadable file, a silent one, one without a strike or a
// --ref that matches no file is a UserError.

#include "RenderJob.h"
#include "StrikeFingerprint.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace juce
{
class var;
} // namespace juce

namespace snaresim::render
{

// One recording of a --ref: its kit (KITDIR's last name), its file and fingerprint.
struct Reference
{
    std::string kit;
    std::filesystem::path file;
    std::string name; // kit/the file's path under KITDIR
    StrikeFingerprint fingerprint;
};

// One measured strike: its distance to every reference, in their order, and the nearest.
struct StrikeDistances
{
    std::filesystem::path file; // absolute
    std::string name;           // as given
    StrikeFingerprint fingerprint;
    std::vector<double> distances_dB;
    std::size_t nearest = 0;

    double nearest_dB() const { return distances_dB[nearest]; }
};

struct DistanceReport
{
    std::vector<Reference> references;
    std::vector<StrikeDistances> strikes;
};

// The recordings of every --ref, each KITDIR:GLOB's sorted by path, in the order given.
// Throws UserError.
std::vector<Reference> loadReferences(const std::vector<ReferenceSpec>& specs);

// The strike in `file` (read as a recording; `name` in messages) against the references.
// Throws UserError.
StrikeDistances measureDistances(const std::filesystem::path& file, const std::string& name, const std::vector<Reference>& references);

// Per strike, a line with its nearest recording, then a line per recording. Ends with a newline.
std::string distanceSummary(const DistanceReport& report);

// { "references": [{ "kit", "file" }], "strikes": [{ "file", "nearest", "nearest_kit",
// "distance_db", "distances_db", "fingerprint_db" }] }
juce::var distanceJson(const DistanceReport& report);

// Runs --distance; prints the report on stdout (--json: one object). Returns the exit status (0).
int runDistance(const RenderJob& job);

} // namespace snaresim::render
