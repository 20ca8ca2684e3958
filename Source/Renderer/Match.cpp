#include "Match.h"

#include "AtomicFile.h"
#include "AudioFileReader.h"
#include "EngineSetup.h"
#include "Errors.h"
#include "Formatted.h"
#include "Interrupt.h"
#include "MatchDistance.h"
#include "MatchSearch.h"
#include "Renderer.h"

#include "DrumConfig.h"
#include "ParameterText.h"
#include "PresetFile.h"
#include "Presets.h"

#include <juce_core/juce_core.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <future>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <thread>
#include <unistd.h>
#include <utility>

namespace snaresim::render
{
namespace
{

using Clock = std::chrono::steady_clock;

constexpr double kUnreachable = 1.0e3; // the distance of a candidate the model cannot render

// ---- coordinates ----------------------------------------------------------------------------

std::string coordinateKey(const MatchCoordinate& c) { return c.id ? std::string(spec(*c.id).key) : std::string("velocity"); }

// A unit coordinate as a value: linear or logarithmic in the parameter's range, whole numbers
// rounded; the velocity 1..127.
double valueAt(const MatchCoordinate& c, double u)
{
    if (! c.id)
        return std::round(1.0 + 126.0 * u);
    const auto& s = spec(*c.id);
    double v =
        s.scale == ParamScale::logarithmic ? s.minValue * std::pow(s.maxValue / s.minValue, u) : s.minValue + u * (s.maxValue - s.minValue);
    if (s.kind != ParamKind::continuous)
        v = std::round(v);
    return std::clamp(v, s.minValue, s.maxValue);
}

double unitOf(const MatchCoordinate& c, double value)
{
    if (! c.id)
        return std::clamp((value - 1.0) / 126.0, 0.0, 1.0);
    const auto& s = spec(*c.id);
    const double u = s.scale == ParamScale::logarithmic ? std::log(value / s.minValue) / std::log(s.maxValue / s.minValue)
                                                        : (value - s.minValue) / (s.maxValue - s.minValue);
    return std::clamp(u, 0.0, 1.0);
}

// What one candidate is: the parameters and the strike's velocity.
struct Candidate
{
    ParameterSet params;
    int velocity = kMatchFixedVelocity;

    // The values that decide the render (the cache's key).
    std::vector<double> key() const
    {
        std::vector<double> k;
        for (std::size_t i = 0; i < kNumParameters; ++i)
            k.push_back(params.get((ParamId) i));
        k.push_back(velocity);
        return k;
    }
};

// ---- rendering --------------------------------------------------------------------------------

// One strike at time 0, the session's mix (what the plug-in plays). Throws
// std::invalid_argument when the candidate cannot be built.
std::vector<double> renderStrike(const Candidate& candidate, double rate)
{
    DrumSession session(DrumSession::Mode::render);
    session.setParameters(candidate.params);
    session.prepareAndStart(rate, kRenderBlockSize);
    RenderPlan plan;
    plan.sampleRate_Hz = rate;
    plan.numSamples = std::lround(kMatchSeconds * rate);
    plan.strikes = { ScheduledStrike { 0, candidate.velocity } };
    std::vector<double> samples;
    samples.reserve((std::size_t) plan.numSamples);
    RenderSinks sinks;
    sinks.audio = [&](std::span<const std::span<const float>> channels) {
        throwIfInterrupted();
        samples.insert(samples.end(), channels.front().begin(), channels.front().end());
    };
    const Channel mix {};
    renderDrum(session, plan, std::span(&mix, 1), sinks);
    return samples;
}

struct Evaluation
{
    double distance = kUnreachable;
    std::optional<StrikeSignature> signature;
    std::optional<MatchDistance> terms;
};

Evaluation evaluateCandidate(const Candidate& candidate, double rate, const StrikeSignature& recording)
{
    Evaluation e;
    try
    {
        const auto samples = renderStrike(candidate, rate);
        e.signature = strikeSignature(samples, rate, StrikeRules::render);
        e.terms = matchDistance(recording, *e.signature);
        e.distance = std::isfinite(e.terms->total) ? e.terms->total : kUnreachable;
    }
    catch (const std::invalid_argument&) // a model the engine refuses, or a silent render
    {}
    return e;
}

// The threads that render candidates: one per core, up to 8.
std::size_t renderThreads() { return (std::size_t) std::clamp(std::thread::hardware_concurrency(), 1u, 8u); }

// The candidates' evaluations, rendered on renderThreads(), each thread taking the next candidate
// when it is free (a drum with 40 wires takes longer than one with 5).
std::vector<Evaluation> evaluateAll(const std::vector<Candidate>& candidates, double rate, const StrikeSignature& recording)
{
    std::vector<Evaluation> results(candidates.size());
    std::atomic<std::size_t> next { 0 };
    auto work = [&] {
        for (std::size_t j; (j = next++) < candidates.size();)
            results[j] = evaluateCandidate(candidates[j], rate, recording);
    };
    std::vector<std::future<void>> workers;
    for (std::size_t t = 0; t < std::min(renderThreads(), candidates.size()); ++t)
        workers.push_back(std::async(std::launch::async, work));
    for (auto& worker : workers)
        worker.get(); // an interruption comes out here
    return results;
}

// ---- progress ---------------------------------------------------------------------------------

// On a terminal one line rewritten in place; otherwise a line each time the best improves; with
// --json nothing.
class MatchProgress
{
public:
    MatchProgress(bool enabled, int budget) : enabled(enabled), terminal(enabled && ::isatty(STDERR_FILENO) == 1), budget(budget) {}
    ~MatchProgress()
    {
        if (shown)
            std::fputc('\n', stderr);
    }

    void update(int renders, double best)
    {
        if (! enabled)
            return;
        const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
        if (terminal)
        {
            std::fprintf(stderr, "\rsnaresim-render: match %d of %d renders  best distance %.3f  %.0f s\033[K", renders, budget, best,
                         elapsed);
            shown = true;
        }
        else if (best < lastPrinted)
            std::fprintf(stderr, "snaresim-render: match %d of %d renders: distance %.3f\n", renders, budget, best);
        lastPrinted = std::min(lastPrinted, best);
        std::fflush(stderr);
    }

    void finish()
    {
        if (shown)
            std::fputc('\n', stderr);
        shown = false;
    }

private:
    bool enabled, terminal;
    int budget;
    bool shown = false;
    double lastPrinted = 1e300;
    Clock::time_point start = Clock::now();
};

// ---- the objective ----------------------------------------------------------------------------

class MatchObjective final : public SearchObjective
{
public:
    MatchObjective(const StrikeSignature& recording, double rate, const ParameterSet& start, std::vector<MatchCoordinate> coordinates,
                   MatchProgress& progress)
        : recording(recording), rate(rate), start(start), coordinates(std::move(coordinates)), progress(progress)
    {}

    Candidate candidateAt(const UnitPoint& point) const
    {
        Candidate c { start, kMatchFixedVelocity };
        for (std::size_t i = 0; i < coordinates.size(); ++i)
        {
            const double value = valueAt(coordinates[i], point[i]);
            if (coordinates[i].id)
                c.params.set(*coordinates[i].id, value);
            else
                c.velocity = (int) value;
        }
        return c;
    }

    UnitPoint startPoint() const
    {
        UnitPoint point;
        for (const auto& c : coordinates)
            point.push_back(unitOf(c, c.id ? start.get(*c.id) : (double) kMatchFixedVelocity));
        return point;
    }

    std::vector<double> evaluate(const std::vector<UnitPoint>& points) override
    {
        std::vector<Candidate> candidates;
        for (const auto& p : points)
            candidates.push_back(candidateAt(p));
        return evaluateCandidates(candidates);
    }

    // The distances of candidates: cached ones at once, the others rendered on every core.
    std::vector<double> evaluateCandidates(const std::vector<Candidate>& candidates)
    {
        std::vector<std::vector<double>> keys;
        std::vector<std::size_t> todo;
        for (std::size_t i = 0; i < candidates.size(); ++i)
        {
            keys.push_back(candidates[i].key());
            if (! cache.count(keys.back()) && std::none_of(todo.begin(), todo.end(), [&](std::size_t j) { return keys[j] == keys.back(); }))
                todo.push_back(i);
        }
        // In chunks of a few per thread (evaluateAll); the progress after each chunk.
        const std::size_t chunk = 4 * renderThreads();
        for (std::size_t first = 0; first < todo.size(); first += chunk)
        {
            throwIfInterrupted();
            const std::size_t last = std::min(todo.size(), first + chunk);
            std::vector<Candidate> batch;
            for (std::size_t j = first; j < last; ++j)
                batch.push_back(candidates[todo[j]]);
            auto results = evaluateAll(batch, rate, recording);
            for (std::size_t j = first; j < last; ++j)
            {
                ++renders;
                best = std::min(best, results[j - first].distance);
                cache.emplace(keys[todo[j]], std::move(results[j - first]));
            }
            progress.update(renders, best);
        }
        std::vector<double> distances;
        for (const auto& key : keys)
            distances.push_back(cache.at(key).distance);
        return distances;
    }

    const Evaluation& evaluation(const Candidate& c) const { return cache.at(c.key()); }

    // Another search's start: the points of the unit cube map onto it from now on (the cache and
    // the cost go on).
    void setStart(const ParameterSet& params) { start = params; }

    int cost() const override { return renders; }

private:
    const StrikeSignature& recording;
    double rate;
    ParameterSet start;
    std::vector<MatchCoordinate> coordinates;
    MatchProgress& progress;
    int renders = 0;
    double best = 1e300;
    std::map<std::vector<double>, Evaluation> cache;
};

// ---- the report -------------------------------------------------------------------------------

struct MatchResult
{
    Candidate match;
    double distance = 0.0;   // the mean over the finalist's three strikes
    double strike_dB = 0.0;  // the chosen strike's whole-strike distance (StrikeFingerprint.h)
    MatchDistance terms;     // the chosen strike's own terms (at its velocity)
    StrikeFeatures features; // the chosen strike's
    int renders = 0;
    double wallSeconds = 0.0;
    std::string startPreset;               // the factory preset the chosen strike's search started from, if it chose one
    double startPreset_dB = 0.0;           // and its strike's whole-strike distance
    std::vector<std::string> startPresets; // every factory preset a search started from, nearest first
};

std::string optionalText(const std::optional<double>& v, const char* format) { return v ? formatted(format, *v) : "n/a"; }

juce::var optionalVar(const std::optional<double>& v) { return v ? juce::var(*v) : juce::var(); }

juce::var featuresJson(const StrikeFeatures& f)
{
    auto* o = new juce::DynamicObject();
    o->setProperty("onset_s", f.onset_s());
    o->setProperty("tail_centroid_hz", optionalVar(f.tailCentroid_Hz));
    auto* shares = new juce::DynamicObject();
    for (std::size_t b = 0; b < f.bandShares.size(); ++b)
        shares->setProperty(juce::String(std::string(kShareBandNames[b])), f.bandShares[b]);
    o->setProperty("band_shares", juce::var(shares));
    o->setProperty("fall_20db_ms", optionalVar(f.fall20_ms));
    o->setProperty("fall_40db_ms", optionalVar(f.fall40_ms));
    o->setProperty("lowest_peak_hz", optionalVar(f.lowestPeak_Hz));
    return juce::var(o);
}

std::string formatJson(const RenderJob& job, const std::vector<MatchCoordinate>& coordinates, const StrikeFeatures& recording,
                       const MatchResult& r, const std::filesystem::path& output)
{
    auto* root = new juce::DynamicObject();
    root->setProperty("recording", juce::String(std::filesystem::absolute(*job.match).lexically_normal().string()));
    root->setProperty("output", juce::String(std::filesystem::absolute(output).lexically_normal().string()));
    root->setProperty("distance", r.distance);
    root->setProperty("strike_distance_db", r.strike_dB);
    auto* params = new juce::DynamicObject();
    for (const auto& s : parameterSpecs())
        params->setProperty(juce::String(std::string(s.key)), r.match.params.get(s.id));
    root->setProperty("parameters", juce::var(params));
    juce::Array<juce::var> searched;
    for (const auto& c : coordinates)
        searched.add(juce::String(coordinateKey(c)));
    root->setProperty("matched", searched);
    root->setProperty("velocity", r.match.velocity);
    auto* terms = new juce::DynamicObject();
    for (std::size_t i = 0; i < r.terms.z.size(); ++i)
        terms->setProperty(juce::String(std::string(MatchDistance::kTermNames[i])), r.terms.z[i]);
    root->setProperty("terms", juce::var(terms));
    root->setProperty("start_preset", r.startPreset.empty() ? juce::var() : juce::var(juce::String(r.startPreset)));
    root->setProperty("start_preset_distance_db", r.startPreset.empty() ? juce::var() : juce::var(r.startPreset_dB));
    juce::Array<juce::var> startPresets;
    for (const auto& name : r.startPresets)
        startPresets.add(juce::String(name));
    root->setProperty("start_presets", startPresets);
    root->setProperty("renders", r.renders);
    root->setProperty("wall_seconds", r.wallSeconds);
    root->setProperty("sample_rate_hz", r.features.sampleRate_Hz);
    root->setProperty("recording_features", featuresJson(recording));
    root->setProperty("match_features", featuresJson(r.features));
    return juce::JSON::toString(juce::var(root), true).toStdString() + "\n";
}

std::string formatSummary(const RenderJob& job, const std::vector<MatchCoordinate>& coordinates, const ParameterSet& start,
                          const StrikeFeatures& recording, const MatchResult& r, const std::filesystem::path& output)
{
    std::string s;
    char line[256];
    std::snprintf(line, sizeof line, "snaresim-render: matched %s in %d renders (%.1f s): distance %.3f, whole-strike distance %.2f dB\n",
                  job.match->filename().c_str(), r.renders, r.wallSeconds, r.distance, r.strike_dB);
    s += line;
    if (! r.startPreset.empty())
    {
        std::snprintf(line, sizeof line, "  started from the factory preset %s (whole-strike distance %.2f dB)\n", r.startPreset.c_str(),
                      r.startPreset_dB);
        s += line;
        for (const auto& other : r.startPresets)
            if (other != r.startPreset)
                s += "  (another search started from " + other + ")\n";
    }
    std::snprintf(line, sizeof line, "  %-22s %16s %16s\n", "parameter", "start", "match");
    s += line;
    for (const auto& c : coordinates)
    {
        const std::string from = c.id ? formatValue(spec(*c.id), start.get(*c.id)) : std::to_string(kMatchFixedVelocity);
        const std::string to = c.id ? formatValue(spec(*c.id), r.match.params.get(*c.id)) : std::to_string(r.match.velocity);
        std::snprintf(line, sizeof line, "  %-22s %16s %16s\n", coordinateKey(c).c_str(), from.c_str(), to.c_str());
        s += line;
    }
    std::snprintf(line, sizeof line, "  %-30s %10s %10s\n", "feature", "recording", "match");
    s += line;
    auto row = [&](const char* name, const std::string& a, const std::string& b) {
        std::snprintf(line, sizeof line, "  %-30s %10s %10s\n", name, a.c_str(), b.c_str());
        s += line;
    };
    const auto& m = r.features;
    row("tail centroid 50-300 ms (Hz)", optionalText(recording.tailCentroid_Hz, "%.0f"), optionalText(m.tailCentroid_Hz, "%.0f"));
    for (std::size_t b = 0; b < kShareBandNames.size(); ++b)
    {
        const std::string name = "share " + std::string(kShareBandNames[b]) + " Hz, 0-300 ms (%)";
        row(name.c_str(), optionalText(100.0 * recording.bandShares[b], "%.1f"), optionalText(100.0 * m.bandShares[b], "%.1f"));
    }
    row("fall 20 dB (ms)", optionalText(recording.fall20_ms, "%.0f"), optionalText(m.fall20_ms, "%.0f"));
    row("fall 40 dB (ms)", optionalText(recording.fall40_ms, "%.0f"), optionalText(m.fall40_ms, "%.0f"));
    row("lowest strong peak (Hz)", optionalText(recording.lowestPeak_Hz, "%.1f"), optionalText(m.lowestPeak_Hz, "%.1f"));
    s += "  terms (z):";
    for (std::size_t i = 0; i < r.terms.z.size(); ++i)
    {
        std::snprintf(line, sizeof line, " %s %.2f", MatchDistance::kTermNames[i].data(), r.terms.z[i]);
        s += line;
    }
    s += "\n  wrote " + std::filesystem::absolute(output).lexically_normal().string() + "\n";
    return s;
}

void writeText(const AtomicFile& file, const std::string& text)
{
    std::ofstream out(file.temporary(), std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (! out)
        throw UserError("cannot write " + file.displayName());
}

// The options that make no sense with --match.
void checkMatchOptions(const RenderJob& job)
{
    if (const char* option = job.firstRenderOption())
        throw UserError(std::string(option) + " cannot be used with --match (see --help)");
}

// The factory presets ranked by how near their strikes (kMatchFixedVelocity) lie to the recording
// by the whole-strike distance, among those with the snares as `start` has them, with --model and
// --set over each as over any preset; nearest first (empty when none renders), and the strikes
// this took.
struct PresetStart
{
    std::string name;
    ParameterSet params;
    double strike_dB = 0.0;
};

struct PresetStarts
{
    std::vector<PresetStart> nearestFirst;
    int renders = 0;
};

PresetStarts nearestPresetStarts(const RenderJob& job, const ParameterSet& start, double rate, const StrikeSignature& recording)
{
    std::vector<PresetStart> presets;
    for (const auto& preset : factoryPresets())
    {
        RenderJob withPreset = job;
        withPreset.preset = std::string(preset.name);
        auto params = makeParameters(withPreset);
        if (params.get(ParamId::snaresEngaged) == start.get(ParamId::snaresEngaged))
            presets.push_back({ std::string(preset.name), params, 0.0 });
    }
    std::vector<Candidate> strikes;
    for (const auto& preset : presets)
        strikes.push_back({ preset.params, kMatchFixedVelocity });
    const auto results = evaluateAll(strikes, rate, recording);
    PresetStarts ranked { {}, (int) presets.size() };
    for (std::size_t j = 0; j < presets.size(); ++j)
        if (results[j].terms)
        {
            ranked.nearestFirst.push_back(presets[j]);
            ranked.nearestFirst.back().strike_dB = results[j].terms->strike_dB;
        }
    std::stable_sort(ranked.nearestFirst.begin(), ranked.nearestFirst.end(),
                     [](const PresetStart& a, const PresetStart& b) { return a.strike_dB < b.strike_dB; });
    return ranked;
}

// The room a recording was made in, as a start: with the room's two parameters searched and the
// start in the free field, the start struck in a few rooms (T60 by volume; the field's level
// falls with the volume, r_c = 0.057 sqrt(V / T60)) and in the free field, and the nearest taken.
// A room changes what the microphones hear of the same strike, so these strikes differ by the
// room alone; from the free field the search would not find one, as a room's volume changes
// nothing there and its first step in T60 (a quarter second in 60 m^3) lies far off.
struct RoomStart
{
    double time_s = 0.0;
    double volume_m3 = 0.0;
    int renders = 0;
};

RoomStart nearestRoomStart(const ParameterSet& start, double rate, const StrikeSignature& recording)
{
    constexpr std::array<double, 3> times { 0.15, 0.3, 0.6 };
    constexpr std::array<double, 3> volumes { 60.0, 350.0, 2000.0 };
    std::vector<Candidate> strikes { { start, kMatchFixedVelocity } };
    for (const double t : times)
        for (const double v : volumes)
        {
            ParameterSet p = start;
            p.set(ParamId::roomTime, t);
            p.set(ParamId::roomVolume, v);
            strikes.push_back({ p, kMatchFixedVelocity });
        }
    const auto results = evaluateAll(strikes, rate, recording);
    RoomStart best { start.get(ParamId::roomTime), start.get(ParamId::roomVolume), (int) strikes.size() };
    double nearest = 1e300;
    for (std::size_t j = 0; j < strikes.size(); ++j)
        if (results[j].terms && results[j].terms->strike_dB < nearest)
        {
            nearest = results[j].terms->strike_dB;
            best.time_s = strikes[j].params.get(ParamId::roomTime);
            best.volume_m3 = strikes[j].params.get(ParamId::roomVolume);
        }
    return best;
}

} // namespace

std::string defaultMatchParams()
{
    return "batter_tension,carry_tension,damping,high_damping,snare_tension,snare_count,strike_position,mallet_mass,"
           "mallet_stiffness,mic_top,mic_bottom,mic_room,room_time,room_volume,velocity";
}

int runMatch(const RenderJob& job)
{
    installInterruptHandlers();
    checkMatchOptions(job);
    const auto begin = Clock::now();

    // The start (defaults, --preset, --model, --set; the nearest factory preset below) and what is
    // searched.
    auto start = makeParameters(job);
    if (start.get(ParamId::airModel) == 2.0)
        throw UserError("--match renders the real-time model: the air box (air_model=airbox) is far too slow for a search");
    std::vector<MatchCoordinate> coordinates;
    if (job.matchParams)
        coordinates = *job.matchParams;
    else
    {
        const auto list = defaultMatchParams();
        for (std::string_view rest = list; ! rest.empty();)
        {
            const auto comma = rest.find(',');
            const auto key = rest.substr(0, comma);
            const MatchCoordinate coordinate { key == "velocity" ? std::nullopt : findParameter(key) };
            // With the snares off (--set snares_engaged=off) their tension and count change nothing.
            const bool snaresOnly = coordinate.id == ParamId::snareTension || coordinate.id == ParamId::snareCount;
            if (! snaresOnly || start.get(ParamId::snaresEngaged) != 0.0)
                coordinates.push_back(coordinate);
            rest = comma == std::string_view::npos ? std::string_view {} : rest.substr(comma + 1);
        }
    }

    // The recording, measured before anything is written or rendered.
    const auto audio = readMonoAudio(*job.match);
    StrikeSignature recording;
    try
    {
        recording = strikeSignature(audio.samples, audio.sampleRate_Hz, StrikeRules::recording);
    }
    catch (const NotAStrike& e)
    {
        throw UserError(job.match->string() + ": " + e.what());
    }
    const double rate = audio.sampleRate_Hz >= 32000.0 && audio.sampleRate_Hz <= 96000.0 ? audio.sampleRate_Hz : 48000.0;
    try
    {
        (void) makeDrumConfig(start, rate);
    }
    catch (const std::invalid_argument& e)
    {
        throw UserError(std::string("the model cannot be configured: ") + e.what());
    }

    std::error_code ec;
    if (std::filesystem::equivalent(*job.match, *job.output, ec))
        throw UserError("-o " + job.output->string() + " is the recording itself; give the preset file another name");
    AtomicFile presetFile(*job.output); // an unusable path fails here, before the search

    const int budget = job.matchBudget.value_or(kDefaultMatchBudget);
    MatchProgress progress(! job.json, budget);

    // A recording's drum lies nearer one of the factory presets than the defaults: without
    // --preset and --match-params the search starts from the nearest (what it does not search,
    // such as a felt mallet's exponent, comes with it); with kSecondStartBudget, another from the
    // second-nearest, and with more, from the next (presetSearches).
    PresetStarts ranked;
    if (! job.preset && ! job.matchParams && presetSearches(budget) > 0)
        ranked = nearestPresetStarts(job, start, rate, recording);
    auto& presetStarts = ranked.nearestFirst;
    presetStarts.resize(std::min<std::size_t>(presetStarts.size(), (std::size_t) presetSearches(budget)));
    int startRenders = ranked.renders;
    std::vector<ParameterSet> starts;
    for (const auto& p : presetStarts)
        starts.push_back(p.params);
    if (starts.empty())
        starts.push_back(start);
    auto searched = [&](ParamId id) {
        return std::any_of(coordinates.begin(), coordinates.end(), [id](const MatchCoordinate& c) { return c.id == id; });
    };
    MatchObjective objective(recording, rate, starts.front(), coordinates, progress);

    // Each search, then the finalists of all each struck twice more (velocity -4 and +4): the
    // chaotic snares make one strike's distance noisy, the mean of three is the one that decides.
    struct Finalist
    {
        Candidate candidate;
        double distance = 0.0;
        std::size_t start = 0;
    };
    std::vector<Finalist> finalists;
    const int searchesBudget = budget - 2 * kMatchFinalists - startRenders;
    for (std::size_t i = 0; i < starts.size(); ++i)
    {
        int roomRenders = 0;
        if (searched(ParamId::roomTime) && searched(ParamId::roomVolume) && starts[i].get(ParamId::roomTime) == 0.0 &&
            budget >= kPresetStartBudget)
        {
            const auto room = nearestRoomStart(starts[i], rate, recording);
            starts[i].set(ParamId::roomTime, room.time_s);
            starts[i].set(ParamId::roomVolume, room.volume_m3);
            roomRenders = room.renders;
        }
        startRenders += roomRenders;
        objective.setStart(starts[i]);
        SearchSettings settings;
        settings.budget = searchesBudget / (int) starts.size() - roomRenders;
        settings.seed = (std::uint64_t) job.matchSeed.value_or(kDefaultMatchSeed);
        for (const auto& point : searchMinimum(objective.startPoint(), objective, settings, kMatchFinalists))
            finalists.push_back({ objective.candidateAt(point.point), point.distance, i });
    }
    std::stable_sort(finalists.begin(), finalists.end(), [](const Finalist& a, const Finalist& b) { return a.distance < b.distance; });
    finalists.resize(std::min<std::size_t>(finalists.size(), kMatchFinalists));

    MatchResult result;
    double bestMean = 1e300;
    std::size_t chosenStart = 0;
    for (const auto& finalist : finalists)
    {
        const auto& candidate = finalist.candidate;
        std::vector<Candidate> strikes { candidate, candidate, candidate };
        strikes[1].velocity = std::max(1, candidate.velocity - 4);
        strikes[2].velocity = std::min(127, candidate.velocity + 4);
        const auto distances = objective.evaluateCandidates(strikes);
        const double mean = (distances[0] + distances[1] + distances[2]) / 3.0;
        if (mean < bestMean)
        {
            bestMean = mean;
            result.match = candidate;
            chosenStart = finalist.start;
        }
    }
    start = starts[chosenStart];
    progress.finish();
    const auto& chosen = objective.evaluation(result.match);
    if (! chosen.signature || ! chosen.terms)
        throw UserError("no candidate could be rendered (the model refused every one)");
    result.distance = bestMean;
    result.strike_dB = chosen.terms->strike_dB;
    result.terms = *chosen.terms;
    result.features = chosen.signature->features;
    result.renders = objective.cost() + startRenders;
    if (! presetStarts.empty())
    {
        result.startPreset = presetStarts[chosenStart].name;
        result.startPreset_dB = presetStarts[chosenStart].strike_dB;
        for (const auto& p : presetStarts)
            result.startPresets.push_back(p.name);
    }

    // The preset file: a comment that says what it is, then the parameters.
    char comment[512];
    std::snprintf(comment, sizeof comment,
                  "# Matched to %s by snaresim-render --match: distance %.3f, whole-strike distance %.2f dB, strike velocity %d\n",
                  job.match->filename().c_str(), result.distance, result.strike_dB, result.match.velocity);
    writeText(presetFile, comment + formatPresetFile("Match " + job.match->stem().string(), result.match.params));
    throwIfInterrupted();
    presetFile.commit();
    result.wallSeconds = std::chrono::duration<double>(Clock::now() - begin).count();

    std::cout << (job.json ? formatJson(job, coordinates, recording.features, result, *job.output)
                           : formatSummary(job, coordinates, start, recording.features, result, *job.output))
              << std::flush;
    return 0;
}

} // namespace snaresim::render
