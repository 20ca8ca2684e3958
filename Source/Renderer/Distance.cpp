#include "Distance.h"

#include "AudioFileReader.h"
#include "Errors.h"
#include "Formatted.h"
#include "StrikeFeatures.h"

#include <juce_core/juce_core.h>

#include <glob.h>

#include <algorithm>
#include <iostream>
#include <utility>

namespace snaresim::render
{
namespace
{

namespace fs = std::filesystem;

juce::var text(const std::string& s) { return juce::String(juce::CharPointer_UTF8(s.c_str())); }

std::string absoluteText(const fs::path& file) { return fs::absolute(file).lexically_normal().string(); }

// The files a glob(7) pattern matches, sorted (none: empty).
std::vector<std::string> globbed(const std::string& pattern)
{
    glob_t found {};
    std::vector<std::string> files;
    if (::glob(pattern.c_str(), 0, nullptr, &found) == 0)
        files.assign(found.gl_pathv, found.gl_pathv + found.gl_pathc);
    ::globfree(&found);
    std::sort(files.begin(), files.end());
    return files;
}

// KITDIR's last name ("kits/Forzee/" -> "Forzee").
std::string kitName(const fs::path& kitDir)
{
    auto dir = kitDir.string();
    while (dir.size() > 1 && dir.back() == '/')
        dir.pop_back();
    return fs::path(dir).filename().string();
}

// A recording's fingerprint; one that holds no strike is the user's error, named by `label`.
StrikeFingerprint fingerprintOfFile(const fs::path& file, const std::string& label)
{
    const auto audio = readMonoAudio(file);
    try
    {
        return strikeFingerprint(audio.samples, audio.sampleRate_Hz);
    }
    catch (const NotAStrike& e)
    {
        throw UserError(label + ": " + e.what());
    }
}

// The options that make no sense with --distance (it renders nothing).
void checkDistanceOptions(const RenderJob& job)
{
    // a render's options, and those of the drum and the search
    const std::pair<bool, const char*> refused[] {
        { job.firstRenderOption() != nullptr, job.firstRenderOption() },
        { job.preset.has_value(), "--preset" },
        { ! job.overrides.empty(), "--set" },
        { job.airModel.has_value(), "--model" },
        { job.matchParams.has_value(), "--match-params" },
        { job.matchBudget.has_value(), "--match-budget" },
        { job.matchSeed.has_value(), "--match-seed" },
    };
    for (const auto& [given, option] : refused)
        if (given)
            throw UserError(std::string(option) + " cannot be used with --distance (it measures files, renders nothing; see --help)");
}

} // namespace

std::vector<Reference> loadReferences(const std::vector<ReferenceSpec>& specs)
{
    std::vector<Reference> references;
    for (const auto& spec : specs)
    {
        const auto files = globbed((spec.kitDir / spec.pattern).string());
        if (files.empty())
            throw UserError("--ref " + inQuotes(spec.text) + " matches no file");
        for (const auto& file : files)
        {
            Reference reference;
            reference.kit = kitName(spec.kitDir);
            reference.file = file;
            reference.name = reference.kit + "/" + fs::path(file).lexically_relative(spec.kitDir).string();
            reference.fingerprint = fingerprintOfFile(file, file + " (--ref " + inQuotes(spec.text) + ")");
            references.push_back(std::move(reference));
        }
    }
    return references;
}

StrikeDistances measureDistances(const fs::path& file, const std::string& name, const std::vector<Reference>& references)
{
    StrikeDistances strike;
    strike.file = fs::absolute(file).lexically_normal();
    strike.name = name;
    strike.fingerprint = fingerprintOfFile(file, name);
    for (const auto& reference : references)
        strike.distances_dB.push_back(strikeDistance_dB(strike.fingerprint, reference.fingerprint));
    strike.nearest = (std::size_t)(std::min_element(strike.distances_dB.begin(), strike.distances_dB.end()) - strike.distances_dB.begin());
    return strike;
}

std::string distanceSummary(const DistanceReport& report)
{
    std::string s;
    for (const auto& strike : report.strikes)
    {
        s += strike.name + ": nearest " + report.references[strike.nearest].name +
             formatted(" at %.2f dB (of %d recordings)\n", strike.nearest_dB(), (int) report.references.size());
        for (std::size_t i = 0; i < report.references.size(); ++i)
            s += formatted("  %6.2f dB  ", strike.distances_dB[i]) + report.references[i].name + "\n";
    }
    return s;
}

juce::var distanceJson(const DistanceReport& report)
{
    auto* root = new juce::DynamicObject();
    const juce::var result(root);
    juce::Array<juce::var> references;
    for (const auto& reference : report.references)
    {
        auto* object = new juce::DynamicObject();
        object->setProperty("kit", text(reference.kit));
        object->setProperty("file", text(absoluteText(reference.file)));
        references.add(juce::var(object));
    }
    root->setProperty("references", references);
    juce::Array<juce::var> strikes;
    for (const auto& strike : report.strikes)
    {
        auto* object = new juce::DynamicObject();
        object->setProperty("file", text(strike.file.string()));
        object->setProperty("nearest", text(absoluteText(report.references[strike.nearest].file)));
        object->setProperty("nearest_kit", text(report.references[strike.nearest].kit));
        object->setProperty("distance_db", strike.nearest_dB());
        juce::Array<juce::var> distances, fingerprint;
        for (const double d : strike.distances_dB)
            distances.add(d);
        for (const double level : strike.fingerprint.level_dB)
            fingerprint.add(level);
        object->setProperty("distances_db", distances);
        object->setProperty("fingerprint_db", fingerprint);
        strikes.add(juce::var(object));
    }
    root->setProperty("strikes", strikes);
    return result;
}

int runDistance(const RenderJob& job)
{
    checkDistanceOptions(job);
    DistanceReport report;
    report.references = loadReferences(job.references);
    for (const auto& file : job.distanceFiles)
        report.strikes.push_back(measureDistances(file, file.string(), report.references));
    std::cout << (job.json ? juce::JSON::toString(distanceJson(report), true).toStdString() + "\n" : distanceSummary(report)) << std::flush;
    return 0;
}

} // namespace snaresim::render
