#include "CommandLine.h"

#include "Errors.h"
#include "Match.h"
#include "Microphones.h"
#include "ParameterText.h"
#include "Presets.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <optional>
#include <set>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace snaresim::render
{
namespace
{

[[noreturn]] void fail(const std::string& message) { throw UserError(message); }

// A finite decimal number, the whole text (std::from_chars: no locale, no leading spaces).
double parseNumber(std::string_view text, std::string_view what)
{
    std::string_view digits = text;
    if (digits.size() > 1 && digits.front() == '+')
        digits.remove_prefix(1);

    double value = 0.0;
    const auto* last = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), last, value);

    if (digits.empty() || ec == std::errc::invalid_argument || ptr != last)
        fail(std::string(what) + ": " + inQuotes(text) + " is not a number");
    if (ec == std::errc::result_out_of_range || ! std::isfinite(value))
        fail(std::string(what) + ": " + inQuotes(text) + " is not a finite number");
    return value;
}

int parseInteger(std::string_view text, std::string_view what)
{
    int value = 0;
    const auto* last = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), last, value);
    if (text.empty() || ec != std::errc {} || ptr != last)
        fail(std::string(what) + ": " + inQuotes(text) + " is not an integer");
    return value;
}

Strike parseHit(std::string_view text)
{
    const auto colon = text.find(':');
    if (colon == std::string_view::npos)
        fail("--hit: " + inQuotes(text) + " is not TIME:VELOCITY (e.g. 0.5:100)");

    Strike hit;
    hit.time_s = parseNumber(text.substr(0, colon), "--hit time");
    hit.velocity = parseInteger(text.substr(colon + 1), "--hit velocity");

    if (hit.time_s < 0.0 || hit.time_s > kMaxSeconds)
        fail("--hit: time " + inQuotes(text.substr(0, colon)) + " is outside 0.." + std::to_string((int) kMaxSeconds) + " s");
    if (hit.velocity < 1 || hit.velocity > 127)
        fail("--hit: velocity " + inQuotes(text.substr(colon + 1)) + " is outside 1..127");
    return hit;
}

// "0 none, 1 cavity"
std::string choiceList(const ParameterSpec& parameter)
{
    std::string list;
    for (int i = 0; i < numChoiceNames(parameter); ++i)
        (list += (i == 0 ? "" : ", ") + std::to_string(i) + " ").append(choiceName(parameter, i));
    return list;
}

// The value of a parameter from its text in --set ID=VALUE, read by the schema's text rule
// (ParameterText.h): a number in the schema's unit or with a unit ("140 mm"), a choice's or a
// toggle's name; integer, toggle and choice parameters take whole numbers only
// (ParameterSet::set, which checks the range later, refuses fractions too; this says why).
double parseParameterValue(const ParameterSpec& parameter, std::string_view text, std::string_view optionName = "--set")
{
    const auto option = std::string(optionName) + " " + std::string(parameter.key);
    const bool named = parameter.kind == ParamKind::choice || parameter.kind == ParamKind::toggle;
    const auto value = parseValue(parameter, text, BareNumber::schemaUnit);

    if (! value)
    {
        if (named && ! text.empty() && ! std::isdigit((unsigned char) text.front()) && text.front() != '+' && text.front() != '-' &&
            text.front() != '.')
            fail(option + ": " + inQuotes(text) + " is not one of " + choiceList(parameter));
        // A number followed by a unit the parameter does not have; otherwise why it is not a number.
        std::string_view digits = text.substr(! text.empty() && text.front() == '+' ? 1 : 0);
        double number = 0.0;
        const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
        if (ec != std::errc {} || end == digits.data() + digits.size() || ! std::isfinite(number))
            parseNumber(text, option);
        const auto unit = valueFormat(parameter);
        fail(option + ": " + inQuotes(text) + " is not a number in " + (unit.unit.empty() ? std::string("no unit") : unit.unit) +
             (unit.schemaUnit != unit.unit ? " or " + unit.schemaUnit : std::string()));
    }
    if (parameter.kind == ParamKind::continuous || *value == std::round(*value))
        return *value;

    std::string takes;
    switch (parameter.kind)
    {
        case ParamKind::toggle: takes = "0 or 1"; break;
        case ParamKind::choice: takes = "one of " + choiceList(parameter) + " (the number or the name)"; break;
        case ParamKind::integer:
        case ParamKind::continuous:
            takes = "a whole number from " + numberText(parameter.minValue) + " to " + numberText(parameter.maxValue);
            break;
    }
    fail(option + "=" + std::string(text) + ": " + std::string(parameter.key) + " takes " + takes + ", not a fraction");
}

int parseModel(std::string_view text)
{
    const auto& air = spec(ParamId::airModel);
    if (const auto index = choiceIndex(air, text))
        return *index;
    std::string list;
    for (int i = 0; i < numChoiceNames(air); ++i)
        (list += list.empty() ? "" : "|").append(choiceName(air, i));
    fail("--model: " + inQuotes(text) + " is not one of " + list);
}

MicOutput parseMic(std::string_view text)
{
    if (const auto mic = findMic(text))
        return *mic;
    fail("--mic: " + inQuotes(text) + " is not one of " + std::string(micChoices()));
}

ParameterOverride parseOverrideOf(std::string_view text, const std::string& option)
{
    const auto equals = text.find('=');
    if (equals == std::string_view::npos || equals == 0)
        fail(option + ": " + inQuotes(text) + " is not ID=VALUE (see --list-params)");

    const auto key = text.substr(0, equals);
    const auto id = findParameter(key);
    ParameterOverride result;
    if (id)
    {
        result.id = *id;
        result.value = parseParameterValue(spec(*id), text.substr(equals + 1), option);
    }
    else
    {
        // An older schema's key: its value migrated as a saved state's is (grid_coarseness=2 is
        // Quality's 7.84 kHz), clamped into today's range.
        std::optional<std::pair<ParamId, double>> old;
        try
        {
            old = readOldKey(key, text.substr(equals + 1));
        }
        catch (const std::invalid_argument& e)
        {
            fail(option + " " + std::string(key) + ": " + e.what());
        }
        if (! old)
            fail(option + ": unknown parameter " + inQuotes(key) + " (see --list-params)");
        result.id = old->first;
        result.value = old->second;
    }
    result.text = std::string(text);
    return result;
}

ParameterOverride parseOverride(std::string_view text) { return parseOverrideOf(text, "--set"); }

TimedOverride parseTimedOverride(std::string_view text)
{
    const auto colon = text.find(':');
    if (colon == std::string_view::npos || colon == 0)
        fail("--set-at: " + inQuotes(text) + " is not TIME:ID=VALUE (e.g. 0.5:snare_tension=60)");
    TimedOverride result;
    result.time_s = parseNumber(text.substr(0, colon), "--set-at time");
    if (result.time_s < 0.0 || result.time_s > kMaxSeconds)
        fail("--set-at: time " + inQuotes(text.substr(0, colon)) + " is outside 0.." + std::to_string((int) kMaxSeconds) + " s");
    result.change = parseOverrideOf(text.substr(colon + 1), "--set-at");
    result.change.text = std::string(text);
    return result;
}

// A whole number within lo..hi; "--opt: 'text' is outside lo..hi[ unit]" otherwise.
int parseIntegerIn(std::string_view text, std::string_view option, int lo, int hi, std::string_view unit = "")
{
    const int n = parseInteger(text, option);
    if (n < lo || n > hi)
        fail(std::string(option) + ": " + inQuotes(text) + " is outside " + std::to_string(lo) + ".." + std::to_string(hi) +
             (unit.empty() ? "" : " ") + std::string(unit));
    return n;
}

// One of a few names; "--opt: 'text' is not one of a|b" otherwise.
template <typename Value>
Value parseName(std::string_view text, std::string_view option, std::initializer_list<std::pair<std::string_view, Value>> names)
{
    std::string list;
    for (const auto& [name, value] : names)
    {
        if (name == text)
            return value;
        (list += list.empty() ? "" : "|").append(name);
    }
    fail(std::string(option) + ": " + inQuotes(text) + " is not one of " + list);
}

// --match-params ID,ID,...: parameters --match may search (continuous or whole-number ones
// that change the sound; not the output level, which the level-normalised match ignores), or
// "velocity" for the strike's; each once.
std::vector<MatchCoordinate> parseMatchParams(std::string_view text)
{
    std::vector<MatchCoordinate> coordinates;
    for (std::string_view rest = text;;)
    {
        const auto comma = rest.find(',');
        const auto key = rest.substr(0, comma);
        MatchCoordinate coordinate;
        if (key.empty())
            fail("--match-params: " + inQuotes(text) + " is not a comma-separated list of parameter IDs");
        if (key != "velocity")
        {
            const auto id = findParameter(key);
            if (! id)
                fail("--match-params: unknown parameter " + inQuotes(key) + " (see --list-params)");
            const auto& parameter = spec(*id);
            if (parameter.kind == ParamKind::toggle || parameter.kind == ParamKind::choice)
                fail("--match-params: " + inQuotes(key) + " is a switch or a choice, not searched; set it with --set");
            if (*id == ParamId::outputGain || *id == ParamId::offlineAirBox)
                fail("--match-params: " + inQuotes(key) + " does not change the matched sound");
            coordinate.id = id;
        }
        if (std::find(coordinates.begin(), coordinates.end(), coordinate) != coordinates.end())
            fail("--match-params: " + inQuotes(key) + " is given twice");
        coordinates.push_back(coordinate);
        if (comma == std::string_view::npos)
            break;
        rest = rest.substr(comma + 1);
    }
    return coordinates;
}

int parseMatchSeed(std::string_view text) { return parseIntegerIn(text, "--match-seed", 0, 2147483647); }

int parseMatchBudget(std::string_view text) { return parseIntegerIn(text, "--match-budget", kMinMatchBudget, kMaxMatchBudget, "renders"); }

int parseBlockSize(std::string_view text) { return parseIntegerIn(text, "--block-size", kMinBlockSize, kMaxBlockSize, "samples"); }

int parseRepeats(std::string_view text) { return parseIntegerIn(text, "--bench-repeat", 1, kMaxBenchRepeats); }

BenchScenario parseScenario(std::string_view text)
{
    return parseName<BenchScenario>(text, "--bench-scenario", { { "default", BenchScenario::standard }, { "roll", BenchScenario::roll } });
}

// The benchmark runs the plug-in's path (Drum::process, the mix, no energy tracking) and
// writes nothing but the optional WAV: the options that need more are refused with it.
void checkBenchOptions(const RenderJob& job, bool haveSeconds)
{
    if (! job.bench)
    {
        if (job.blockSize)
            fail("--block-size is an option of --bench");
        if (job.benchScenario)
            fail("--bench-scenario is an option of --bench");
        if (job.benchShort)
            fail("--bench-short is an option of --bench");
        if (job.benchRepeats)
            fail("--bench-repeat is an option of --bench");
        return;
    }

    const std::pair<bool, const char*> outputs[] { { job.energyCsv.has_value(), "--energy-csv" },
                                                   { job.energyPlot.has_value(), "--energy-plot" },
                                                   { job.spectrogram.has_value(), "--spectrogram" },
                                                   { job.snarePlot.has_value(), "--snare-plot" } };
    for (const auto& [given, option] : outputs)
        if (given)
            fail(std::string(option) + " cannot be used with --bench (the benchmark writes only the WAV, -o)");
    if (job.lossless)
        fail("--lossless cannot be used with --bench (the benchmark runs the plug-in's configuration)");
    if (! job.references.empty())
        fail("--ref cannot be used with --bench (the benchmark measures time, not sound)");
    if (job.mic && *job.mic != MicOutput::mix)
        fail("--mic: --bench renders the mix only (Drum::process, the plug-in's output)");
    if (job.benchShort && haveSeconds)
        fail("--bench-short renders " + numberText(kBenchShortSeconds) + " s; leave out --seconds");
    if (job.benchShort && job.benchScenario)
        fail("--bench-short runs the default scenario; leave out --bench-scenario");
}

double parseSampleRate(std::string_view text)
{
    const double rate = parseNumber(text, "--sample-rate");
    if (rate < kMinSampleRate_Hz || rate > kMaxSampleRate_Hz)
        fail("--sample-rate: " + inQuotes(text) + " is outside 8000..384000 Hz");
    if (rate != std::floor(rate))
        fail("--sample-rate: " + inQuotes(text) + " is not a whole number of Hz (WAV stores integers)");
    return rate;
}

double parseSeconds(std::string_view text)
{
    const double seconds = parseNumber(text, "--seconds");
    if (seconds <= 0.0 || seconds > kMaxSeconds)
        fail("--seconds: " + inQuotes(text) + " must be greater than 0 and at most " + std::to_string((int) kMaxSeconds));
    return seconds;
}

// "X,Y,Z" in metres (or one number S when `cube`: S,S,S).
Point3 parsePoint(std::string_view text, std::string_view option, bool cube)
{
    std::vector<std::string_view> parts;
    for (std::string_view rest = text;;)
    {
        const auto comma = rest.find(',');
        parts.push_back(rest.substr(0, comma));
        if (comma == std::string_view::npos || parts.size() > 3)
            break;
        rest = rest.substr(comma + 1);
    }
    if (parts.size() != 3 && ! (cube && parts.size() == 1))
        fail(std::string(option) + ": " + inQuotes(text) + " is not X,Y,Z in metres" + (cube ? " (or one size S)" : ""));
    std::vector<double> v;
    for (const auto part : parts)
        v.push_back(parseNumber(part, option));
    if (v.size() == 1)
        return { v[0], v[0], v[0] };
    return { v[0], v[1], v[2] };
}

Point3 parseAirMic(std::string_view text) { return parsePoint(text, "--air-mic", false); }

Point3 parseBox(std::string_view text)
{
    const Point3 p = parsePoint(text, "--box", true);
    if (p.x <= 0.0 || p.y <= 0.0 || p.z <= 0.0)
        fail("--box: " + inQuotes(text) + " must be positive sizes in metres");
    return p;
}

double parseBoxMargin(std::string_view text)
{
    const double m = parseNumber(text, "--box-margin");
    if (m <= 0.0)
        fail("--box-margin: " + inQuotes(text) + " must be greater than 0 (metres)");
    return m;
}

Walls parseWalls(std::string_view text)
{
    return parseName<Walls>(text, "--walls", { { "absorbing", Walls::absorbing }, { "reflecting", Walls::reflecting } });
}

int parseThreads(std::string_view text) { return parseIntegerIn(text, "--threads", 1, 64); } // DrumConfig's air box: 1..64

std::filesystem::path parsePath(std::string_view text, std::string_view option)
{
    if (text.empty())
        fail(std::string(option) + ": empty file name");
    return std::filesystem::path(std::string(text));
}

// --ref KITDIR:GLOB: split at the first ':'.
ReferenceSpec parseReference(std::string_view text)
{
    const auto colon = text.find(':');
    if (colon == std::string_view::npos || colon == 0 || colon + 1 == text.size())
        fail("--ref: " + inQuotes(text) + " is not KITDIR:GLOB (e.g. kits/Forzee:'Snare-*.wav')");
    return { std::filesystem::path(std::string(text.substr(0, colon))), std::string(text.substr(colon + 1)), std::string(text) };
}

std::string parsePresetName(std::string_view text)
{
    if (text.empty())
        fail("--preset: empty preset name");
    return std::string(text);
}

template <typename T>
void setOnce(std::optional<T>& slot, T value, std::string_view option)
{
    if (slot)
        fail(std::string(option) + " given more than once");
    slot = std::move(value);
}

// parse(VALUE), or parse(VALUE, OPTION) for a parser that names the option in its messages.
template <typename Parse>
auto parseValue(const Parse& parse, std::string_view value, std::string_view option)
{
    if constexpr (std::is_invocable_v<const Parse&, std::string_view, std::string_view>)
        return parse(value, option);
    else
        return parse(value);
}

// The options, on a CLI::App that finds each one and its value. Every value is read when CLI11
// meets it (trigger_on_parse), so the first mistake from the left is the one reported and
// repeated options keep their order. Nothing of CLI11's is printed: its errors become
// UserErrors worded here.
class OptionTable
{
public:
    explicit OptionTable(const std::vector<std::string>& args) : args(args)
    {
        app.set_help_flag(); // --help and -h are looked for before (parseCommandLine)
        app.allow_extras();  // unknown options and stray arguments: failOnExtras
    }

    // An option with a value, given at most once: slot = parse(VALUE).
    template <typename T, typename Parse>
    void once(std::string_view names, std::optional<T>& slot, Parse parse)
    {
        addValueOption(names, [&slot, parse](std::string_view value, const std::string& option) {
            setOnce(slot, T(parseValue(parse, value, option)), option);
        });
    }

    // A repeatable option with a value: parse(VALUE) for each, in order.
    template <typename T, typename Parse>
    void each(std::string_view names, std::vector<T>& list, Parse parse)
    {
        addValueOption(
            names, [&list, parse](std::string_view value, const std::string& option) { list.push_back(parseValue(parse, value, option)); });
    }

    // An option without a value; it may be repeated.
    void flag(std::string_view names, bool& slot)
    {
        for (const auto& option : spellings(names))
            app.add_option(option,
                           [this, option, &slot](const CLI::results_t&) {
                               failOnExtras();
                               // Not --flag=VALUE (CLI11 would take =true, =0, ...).
                               if (args.at(next++) != option)
                                   fail("option " + option + " takes no value");
                               slot = true;
                               return true;
                           })
                ->expected(0)
                ->trigger_on_parse()
                ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    }

    void parse()
    {
        // CLI11 takes "--opt=" as "--opt" with the next argument as its value; it is an empty value.
        std::vector<std::string> tokens;
        for (const auto& arg : args)
            if (const auto equals = arg.find('='); equals == arg.size() - 1 && longValueOptions.count(arg.substr(0, equals)) > 0)
            {
                tokens.push_back(arg.substr(0, equals));
                tokens.emplace_back();
            }
            else
                tokens.push_back(arg);
        std::reverse(tokens.begin(), tokens.end()); // CLI11 takes them from the back

        try
        {
            app.parse(tokens);
        }
        catch (const CLI::ArgumentMismatch&)
        {
            // A value option as the last argument (CLI11 takes any next argument as the value).
            failOnExtras();
            fail("option " + args.back() + " needs a value (see --help)");
        }
        catch (const CLI::Error&)
        {
            failOnExtras();
            fail("the command line cannot be read (see --help)");
        }
        failOnExtras();
    }

private:
    using Handler = std::function<void(std::string_view value, const std::string& option)>;

    // "-o,--output" -> { "-o", "--output" }: each is an option of its own in CLI11, so that
    // messages name the spelling used.
    static std::vector<std::string> spellings(std::string_view names)
    {
        std::vector<std::string> result;
        for (auto rest = names; ! rest.empty();)
        {
            const auto comma = rest.find(',');
            result.emplace_back(rest.substr(0, comma));
            rest = comma == std::string_view::npos ? std::string_view {} : rest.substr(comma + 1);
        }
        return result;
    }

    void addValueOption(std::string_view names, Handler handler)
    {
        for (const auto& option : spellings(names))
        {
            if (option.starts_with("--"))
                longValueOptions.insert(option);
            app.add_option(option,
                           [this, option, handler](const CLI::results_t& results) {
                               failOnExtras();
                               handler(checkedValue(option, results.front()), option);
                               return true;
                           })
                ->trigger_on_parse()
                ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
        }
    }

    // CLI11 does not tell whether the value was attached (--opt=VALUE, -oVALUE) or the next
    // argument; the argument at `next` does. Attached to a long option it is taken as it is;
    // -oVALUE and -o=VALUE are not options; a next argument starting with "--" is an option,
    // so the value is missing.
    const std::string& checkedValue(const std::string& option, const std::string& value)
    {
        const auto& arg = args.at(next);
        const bool attached = arg != option;
        next += attached ? 1 : 2;
        if (attached && ! option.starts_with("--"))
            fail("unknown option " + inQuotes(arg) + " (see --help)");
        if (! attached && value.starts_with("--"))
            fail("option " + option + " needs a value (see --help)");
        return value;
    }

    // What CLI11 did not know, kept in order (allow_extras): the first of it is the error.
    void failOnExtras() const
    {
        const auto extras = app.remaining();
        if (extras.empty())
            return;
        const auto& arg = extras.front();
        if (arg.empty() || arg.front() != '-' || arg == "-")
            fail("unexpected argument " + inQuotes(arg) + " (see --help)");
        fail("unknown option " + inQuotes(arg.starts_with("--") ? arg.substr(0, arg.find('=')) : arg) + " (see --help)");
    }

    const std::vector<std::string>& args;
    // The argument of the option CLI11 is at: options are met in order and nothing unknown
    // before them (failOnExtras), so it is where the last option's arguments ended.
    std::size_t next = 0;
    std::set<std::string> longValueOptions;
    CLI::App app;
};

} // namespace

CommandLine parseCommandLine(const std::vector<std::string>& args)
{
    CommandLine result;
    RenderJob& job = result.job;

    // Anywhere, even where a value is expected, and before any error.
    for (const auto& arg : args)
        if (arg == "--help" || arg == "-h")
        {
            result.action = CommandLine::Action::help;
            return result;
        }

    std::optional<std::filesystem::path> output;
    std::optional<double> sampleRate;
    bool listParameters = false;

    // One line per option (what each does: helpText).
    OptionTable options(args);
    options.once("-o,--output", output, parsePath);
    options.each("--hit", job.hits, parseHit);
    options.once("--midi", job.midiFile, parsePath);
    options.once("--seconds", job.seconds, parseSeconds);
    options.once("--sample-rate", sampleRate, parseSampleRate);
    options.once("--preset", job.preset, parsePresetName);
    options.each("--set", job.overrides, parseOverride);
    options.each("--set-at", job.automation, parseTimedOverride);
    options.once("--model", job.airModel, parseModel);
    options.once("--mic", job.mic, parseMic);
    options.once("--energy-csv", job.energyCsv, parsePath);
    options.once("--energy-plot", job.energyPlot, parsePath);
    options.once("--spectrogram", job.spectrogram, parsePath);
    options.once("--snare-plot", job.snarePlot, parsePath);
    options.flag("--lossless", job.lossless);
    options.flag("--json", job.json);
    options.flag("--list-params", listParameters);
    options.flag("--bench", job.bench);
    options.flag("--bench-short", job.benchShort);
    options.once("--block-size", job.blockSize, parseBlockSize);
    options.once("--bench-repeat", job.benchRepeats, parseRepeats);
    options.once("--bench-scenario", job.benchScenario, parseScenario);
    options.each("--air-mic", job.airMics, parseAirMic);
    options.once("--walls", job.walls, parseWalls);
    options.once("--box", job.boxSize, parseBox);
    options.once("--box-margin", job.boxMargin, parseBoxMargin);
    options.once("--threads", job.threads, parseThreads);
    options.once("--match", job.match, parsePath);
    options.once("--match-params", job.matchParams, parseMatchParams);
    options.once("--match-budget", job.matchBudget, parseMatchBudget);
    options.once("--match-seed", job.matchSeed, parseMatchSeed);
    options.each("--distance", job.distanceFiles, parsePath);
    options.each("--ref", job.references, parseReference);
    options.parse();

    if (sampleRate)
        job.sampleRate_Hz = *sampleRate;

    if (listParameters)
    {
        result.action = CommandLine::Action::listParameters;
        return result;
    }

    if (! job.distanceFiles.empty())
    {
        if (output)
            fail("-o cannot be used with --distance (it prints the distances, writes nothing)");
        if (job.references.empty())
            fail("--distance: missing --ref KITDIR:GLOB, the recordings to measure against (see --help)");
        if (sampleRate)
            fail("--sample-rate cannot be used with --distance (it renders nothing)");
        if (job.match)
            fail("--match cannot be used with --distance");
        return result; // the options it refuses: Distance.cpp
    }

    if (job.match)
    {
        if (! job.references.empty())
            fail("--ref cannot be used with --match");
        if (! output)
            fail("--match: missing -o PRESET_FILE, the preset file to write (see --help)");
        if (sampleRate)
            fail("--sample-rate cannot be used with --match (the candidates are rendered at the recording's rate)");
        job.output = output;
        return result; // the options it refuses: Match.cpp
    }
    if (job.matchParams)
        fail("--match-params is an option of --match");
    if (job.matchBudget)
        fail("--match-budget is an option of --match");
    if (job.matchSeed)
        fail("--match-seed is an option of --match");

    checkBenchOptions(job, job.seconds.has_value());

    if (! output && ! job.bench)
        fail("missing -o OUTPUT.wav (see --help)");
    job.output = output;

    if (job.hits.empty() && ! job.midiFile && ! job.bench)
        fail("nothing to play: give --hit TIME:VELOCITY or --midi FILE (see --help)");

    return result;
}

std::string helpText()
{
    auto presetLine = [] {
        std::string line = "Presets (--preset, case-insensitive):";
        const char* separator = " ";
        for (const auto& preset : factoryPresets())
        {
            line += separator;
            line += '"';
            line.append(preset.name);
            line += '"';
            separator = ", ";
        }
        return line + "\n";
    };

    return R"(snaresim-render: render strikes of the SnareSim physical snare drum model to a WAV file.

Usage:
  snaresim-render -o OUT.wav (--hit TIME:VELOCITY ... | --midi FILE.mid) [options]
  snaresim-render --bench [-o OUT.wav] [--bench-scenario default|roll | --bench-short]
                  [--block-size N] [--hit ... | --midi ...] [options]
  snaresim-render --match RECORDING -o PRESET_FILE [--match-params ID,ID,...]
                  [--match-budget N] [--preset ...] [--set ...] [--json]
  snaresim-render --distance FILE ... --ref KITDIR:GLOB ... [--json]
  snaresim-render --list-params
  snaresim-render --help

Strikes:
  --hit TIME:VELOCITY   strike at TIME seconds (>= 0) with MIDI velocity 1..127, at the
                        default strike point (where note 38 strikes: strike_position
                        from the centre, 0.4 rad from the snares' direction);
                        repeatable (e.g. --hit 0:100 --hit 0.5:60)
  --midi FILE           strike on every note-on of a Standard MIDI file (all tracks, tempo
                        map honoured, any note number; velocity-0 note-ons are note-offs)

Output:
  -o, --output FILE     the WAV file to write: 32-bit float (required)
  --mic top|bottom|far|mix|all|air
                        the signal in the WAV (default mix; with --model airbox, air):
                        the sound pressure at the top microphone (above the batter),
                        the bottom one (under the snares) and the room one (far), where
                        the mic_* parameters put them (air box: the box's own pressure
                        there unless --air-mic is given), mix = their weighted mix (the
                        plug-in's output); all = four channels in the order
                        top, bottom, far, mix; air = the air box's microphones, one
                        channel each in order (pressure, 0.005 per Pa)
  --seconds S           length in seconds, 0 < S <= 3600 (default: 2; with --midi, the
                        latest strike + 2). Strikes at or after the end are not played.
  --sample-rate HZ      whole number of Hz, 8000..384000 (default 48000). The drum is
                        simulated at the rate halved while the half stays at 44.1 kHz or
                        above; where that is 44.1 to 48 kHz, the default's grids
                        (bandwidth to 8.1 kHz) at two thirds of it (32 kHz; 33.075 kHz
                        at 44.1), resampled to the rate; the air box at the rate itself.
                        The resampling's delay (about 2 ms) is taken off: a strike at t
                        sounds at t
  --energy-csv FILE     also write the energy ledger, one row per sample (where the drum
                        is simulated at a lower rate, the last simulated step's ledger):
                        time_s, one column per term of the ledger (batter_J, carry_J,
                        mallets_J, snares_J, cavity_J, then the air's terms in play:
                        cavity_modes_J, outside_J, near_field_J, or airbox_J), total_J,
                        dissipated_J, injected_J, balance_J (total = the terms' sum;
                        balance = total + dissipated - injected, constant up to
                        round-off)
  --energy-plot FILE    also write a PNG (1400 x 600): left, the normalised variation of
                        the energy balance (h^n - h^0) / h^0, h^0 = the total energy right
                        after the first strike; right, the energy of each component and
                        the total, against time in ms
  --spectrogram FILE    also write a PNG (1200 x 700): log-frequency spectrogram of the
                        WAV's first channel (with --mic all: the mix), Hann window of 2048
                        samples at 48 kHz (scaled with the rate), 75 % overlap, 90 dB range
  --snare-plot FILE     also write a PNG (1200 x 700) of the snare wires for the first
                        25 ms after the first strike: top, the mean displacement of the
                        wires' interior nodes, the band between their lowest and highest,
                        and the carry head's mean displacement under them (mm); bottom,
                        the number of wire points touching the carry head; time in ms
  --json                print one JSON object with the render statistics on stdout
                        (default: a short human-readable summary on stdout); it names
                        the engine's vector target (vector_target)

Model:
  --preset NAME|FILE    start from a factory preset, or a preset file (a path ending in
                        .snarepreset), instead of the defaults
  --model cavity|none|airbox
                        the air: cavity (the enclosed air couples the heads; the
                        default), none (heads uncoupled) or airbox (the paper's full
                        model: the drum in a 3D box of air that radiates, far slower
                        than real time); sets air_model after the preset, before any --set
  --air-mic X,Y,Z       air box: a pressure microphone at X,Y,Z metres from the drum's
                        centre (z up, the batter at +depth/2); repeatable, up to 8, one
                        WAV channel each. None given: the drum's top, bottom and room
                        mics (the mic_* parameters), each held a cell and a half inside
                        the box's walls
  --walls absorbing|reflecting
                        air box: the box's walls (default absorbing; --lossless:
                        reflecting)
  --box X,Y,Z | --box S air box: its size in metres (default 0.6 m cube), or
  --box-margin M        the drum's extent plus M metres of air on every side
  --threads N           air box: threads for the air update, 1..64 (default: every core,
                        64 at most)
  --set ID=VALUE        set one parameter (after the preset and --model); repeatable.
                        A number may carry a unit (shell_depth=120mm); integer, on/off
                        and choice parameters take whole numbers only; on/off and choice
                        parameters also take their names (snares_engaged=off). The snares:
                        snares_engaged (0 off, 1 on), snare_tension, snare_count,
                        carry_tension, shell_depth
  --set-at TIME:ID=VALUE
                        from TIME seconds on, set one parameter as a host's automation
                        does: smoothed over 30 ms, or a new drum built and crossfaded in
                        (20 ms) where the parameter needs one (snare_count, bandwidth, ...);
                        repeatable (e.g. --set-at 1:snares_engaged=off)
  --lossless            switch every loss off (energy is then conserved); reports the
                        energy balance drift (energy_relative_drift_max)
  --list-params         list every parameter (ID, range, unit, default) and exit

Benchmark:
  --bench               time the render as the plug-in runs it: the same session as the
                        plug-in's processBlock, blocks of --block-size samples (the mix),
                        strikes as MIDI note 38 and --set-at changes on their sample, no
                        energy tracking, denormals flushed; every block is
                        timed (steady clock). -o is optional; the other outputs, --lossless
                        and --mic other than mix are refused. The summary / JSON adds
                        realtime_factor (audio s / wall s), mean_block_ms, worst_block_ms,
                        block_budget_ms (one block's duration), worst_block_share (worst /
                        budget), block_size, blocks, simulation_rate (the physics' rate,
                        Hz), the grid (batter_grid_spacing_m, carry_grid_spacing_m,
                        snare_points),
                        compute_seconds_per_audio_second and peak_resident_mb. With
                        --model airbox the drum is built with the air options (--threads,
                        --box, ...), and afterwards the air update is timed against a
                        bare 7-point stencil on the same grid (double, one thread):
                        air_points, air_spacing_m, air_threads, air_precision,
                        air_updates_per_second (one thread),
                        air_updates_per_second_threads, bare_stencil_updates_per_second,
                        bare_stencil_float_updates_per_second, air_to_bare_ratio (one
                        thread) and air_to_bare_ratio_threads. Then one more run with
                        the drum's step profile on: profile (the compute per second of
                        audio and the share of each phase of the step, their sum, and the
                        profiling's overhead against the fastest timed run). Non-finite
                        output: exit 1.
  --block-size N        samples per block, 1..8192 (default 64)
  --bench-scenario S    the strikes when no --hit / --midi is given: default = velocity
                        127 every 0.5 s for --seconds (default 2); roll = 16 strikes at
                        velocity 127, 60 ms apart from 0.1 s, 1.5 s long (--seconds changes
                        the length only)
  --bench-short         a quick check (for CI): the default scenario for 0.25 s, one run;
                        fails only on a crash or non-finite output, never on time
  --bench-repeat N      render the scenario N times (1..50; default 5, --bench-short 1),
                        each on a new drum, and time every block by its fastest run: the
                        engine's own cost of the block, without what the machine took
                        meanwhile (other processes, interrupts, a virtual machine's
                        host). realtime_factor, mean_block_ms and worst_block_ms are of
                        those times (worst_block_at_s: where the worst block starts);
                        worst_block_raw_ms is the slowest block of any run
                        and realtime_factor_slowest_run the slowest whole run. The audio,
                        -o and the other figures are of the first run.

Matching a recording:
  --match FILE          search the drum's parameters for the strike closest to a recorded
                        one (a WAV, AIFF or FLAC file of one strike; channels averaged) and
                        write them as a preset file to -o (--preset FILE and the plug-in's
                        File button load it). The distance is mainly the whole-strike
                        distance (as --distance measures it), with the features of
                        scripts/snare_features.py (tail centroid, band shares, the 20 / 40
                        dB fall times, lowest strong peak) and the level in third-octave
                        bands every 10 ms over the first 300 ms as smaller terms, levels
                        normalised (docs/MATCHING.md). Each candidate is one 0.6 s strike at the
                        recording's sample rate (48 kHz outside 32..96 kHz). The search:
                        the start (the defaults, --preset, --set; without --preset and
                        --match-params, and with a budget of 60 or more, the factory
                        preset whose strike lies nearest the recording, --set over it;
                        with 300 or more, a second search from the second-nearest, and
                        from 1200 one more from the next for each 400 renders, the budget
                        shared evenly) and a Latin hypercube, then a compass search;
                        the three best of all struck again at velocity -4 and +4, the
                        best mean wins. Prints the best distance as it goes
                        (stderr; one line in place on a terminal), then the match's
                        whole-strike distance to the recording (dB), the parameters and
                        the features of recording and match (--json: one object with
                        "parameters", every ID to its value, "distance",
                        "strike_distance_db", "velocity", "terms", the features,
                        "start_preset" and "start_preset_distance_db" (the match's start;
                        null without a preset start), "start_presets" (each search's),
                        "renders", "wall_seconds"). Not a strike
                        (unreadable, silent, shorter than 100 ms, no 20 dB fall): exit 2.
  --match-params LIST   the comma-separated parameter IDs to search (continuous or whole
                        numbers; not output_gain), "velocity" for the strike's MIDI
                        velocity; the others keep their start values (velocity 100).
                        Default: batter_tension, carry_tension, damping, high_damping,
                        snare_tension, snare_count, strike_position, mallet_mass,
                        mallet_stiffness, mic_top, mic_bottom, mic_room, room_time,
                        room_volume, velocity
                        (with --set snares_engaged=off, not the two snare ones)
  --match-budget N      renders the match may use, 12..100000 (default )" +
           std::to_string(kDefaultMatchBudget) + R"()
  --match-seed N        the search's random numbers, 0..2147483647 (default 20240611):
                        the same seed gives the same preset file; another explores other
                        candidates (the distance varies with it: try a few)

Distance to recordings:
  --distance FILE       measure a recorded strike (WAV, AIFF or FLAC; channels averaged, any
                        level) against the recordings of --ref: its distance to each and
                        its nearest; repeatable. Nothing is rendered or written
  --ref KITDIR:GLOB     the recordings to measure against: the files under KITDIR that the
                        glob matches (e.g. kits/Forzee:'Snare-*.wav'; the kit is KITDIR's
                        name); repeatable. With a render (-o ... --hit ...) the WAV written
                        (its channels averaged) is measured against them too, and the
                        summary or the JSON ("distance") adds the result.
                        The distance: the energy in 23 third-octave bands (100 Hz to 16
                        kHz) over 0-30, 30-100 and 100-300 ms after the onset, in dB of
                        the whole, floored at -60 dB; the RMS of two strikes' difference
                        in dB (docs/MATCHING.md). Strikes of one drum lie about 2-5 dB
                        apart, snares of different kits 5-8 dB. Prints, per strike, its
                        nearest recording and then each distance (--json: one object with
                        "references" (kit, file) and "strikes" (file, nearest,
                        nearest_kit, distance_db, distances_db in the references' order,
                        fingerprint_db)). A file unreadable, silent or without a strike
                        (its level 100-300 ms after the onset not 3 dB below the first
                        30 ms'), or a --ref matching no file: exit 2, nothing written.
)" + presetLine() +
           R"(
Environment: SNARESIM_VECTOR_TARGET=baseline|avx2|avx512 runs the engine's hot loops on
that build (default: the widest the processor has; one it lacks: a line on stderr and the
widest). baseline rounds the same on every x86-64 processor: the golden renders use it.
Exit status: 0 success, 2 bad input or unwritable output (one line on stderr starting
with "snaresim-render: error: ", no output file left behind), 1 internal failure,
130 / 143 / 129 interrupted by SIGINT / SIGTERM / SIGHUP (no output file left behind).
Outputs (WAV, CSV, PNGs; no two may be the same file) are written to a temporary file
next to the target and renamed when complete.
)";
}

} // namespace snaresim::render
