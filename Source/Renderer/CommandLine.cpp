#include "CommandLine.h"

#include "Errors.h"
#include "Microphones.h"
#include "Presets.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace snaresim::render
{
namespace
{

[[noreturn]] void fail(const std::string& message)
{
    throw UserError(message);
}

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
        fail("--hit: time " + inQuotes(text.substr(0, colon)) + " is outside 0.."
             + std::to_string((int) kMaxSeconds) + " s");
    if (hit.velocity < 1 || hit.velocity > 127)
        fail("--hit: velocity " + inQuotes(text.substr(colon + 1)) + " is outside 1..127");
    return hit;
}

// The names of a choice parameter ("none|cavity" -> { "none", "cavity" }).
std::vector<std::string_view> choiceNames(const ParameterSpec& spec)
{
    std::vector<std::string_view> names;
    std::string_view rest = spec.choices;
    while (! rest.empty())
    {
        const auto bar = rest.find('|');
        names.push_back(rest.substr(0, bar));
        rest = bar == std::string_view::npos ? std::string_view {} : rest.substr(bar + 1);
    }
    return names;
}

// The value of a parameter from its text in --set ID=VALUE: a number, or a choice's name;
// integer, toggle and choice parameters take whole numbers only (ParameterSet::set, which
// checks the range later, refuses fractions too; this says why). The one place that reads a
// parameter's value text.
double parseParameterValue(const ParameterSpec& parameter, std::string_view text)
{
    const auto option = "--set " + std::string(parameter.key);
    const auto names = choiceNames(parameter);

    if (parameter.kind == ParamKind::choice)
        if (const auto name = std::find(names.begin(), names.end(), text); name != names.end())
            return (double) (name - names.begin());

    // "0 none, 1 cavity"
    auto choiceList = [&] {
        std::string list;
        for (std::size_t i = 0; i < names.size(); ++i)
        {
            list += (i == 0 ? "" : ", ") + std::to_string(i) + " ";
            list.append(names[i]);
        }
        return list;
    };

    if (parameter.kind == ParamKind::choice && ! text.empty() && ! std::isdigit((unsigned char) text.front())
        && text.front() != '+' && text.front() != '-' && text.front() != '.')
        fail(option + ": " + inQuotes(text) + " is not one of " + choiceList());

    const double value = parseNumber(text, option);
    if (parameter.kind == ParamKind::continuous || value == std::round(value))
        return value;

    std::string takes;
    switch (parameter.kind)
    {
        case ParamKind::toggle: takes = "0 or 1"; break;
        case ParamKind::choice: takes = "one of " + choiceList() + " (the number or the name)"; break;
        case ParamKind::integer:
        case ParamKind::continuous:
            takes = "a whole number from " + numberText(parameter.minValue) + " to " + numberText(parameter.maxValue);
            break;
    }
    fail(option + "=" + std::string(text) + ": " + std::string(parameter.key) + " takes " + takes + ", not a fraction");
}

int parseModel(std::string_view text)
{
    const auto names = choiceNames(spec(ParamId::airModel));
    if (const auto name = std::find(names.begin(), names.end(), text); name != names.end())
        return (int) (name - names.begin());
    std::string list;
    for (const auto name : names)
        (list += list.empty() ? "" : "|").append(name);
    fail("--model: " + inQuotes(text) + " is not one of " + list);
}

MicOutput parseMic(std::string_view text)
{
    if (const auto mic = findMic(text))
        return *mic;
    fail("--mic: " + inQuotes(text) + " is not one of " + std::string(micChoices()));
}

ParameterOverride parseOverride(std::string_view text)
{
    const auto equals = text.find('=');
    if (equals == std::string_view::npos || equals == 0)
        fail("--set: " + inQuotes(text) + " is not ID=VALUE (see --list-params)");

    const auto key = text.substr(0, equals);
    const auto id = findParameter(key);
    if (! id)
        fail("--set: unknown parameter " + inQuotes(key) + " (see --list-params)");

    ParameterOverride result;
    result.id = *id;
    result.value = parseParameterValue(spec(*id), text.substr(equals + 1));
    result.text = std::string(text);
    return result;
}

int parseBlockSize(std::string_view text)
{
    const int size = parseInteger(text, "--block-size");
    if (size < kMinBlockSize || size > kMaxBlockSize)
        fail("--block-size: " + inQuotes(text) + " is outside " + std::to_string(kMinBlockSize) + ".."
             + std::to_string(kMaxBlockSize) + " samples");
    return size;
}

int parseRepeats(std::string_view text)
{
    const int repeats = parseInteger(text, "--bench-repeat");
    if (repeats < 1 || repeats > kMaxBenchRepeats)
        fail("--bench-repeat: " + inQuotes(text) + " is outside 1.." + std::to_string(kMaxBenchRepeats));
    return repeats;
}

BenchScenario parseScenario(std::string_view text)
{
    if (text == "default")
        return BenchScenario::standard;
    if (text == "roll")
        return BenchScenario::roll;
    fail("--bench-scenario: " + inQuotes(text) + " is not one of default|roll");
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
        fail("--seconds: " + inQuotes(text) + " must be greater than 0 and at most "
             + std::to_string((int) kMaxSeconds));
    return seconds;
}

std::filesystem::path parsePath(std::string_view text, std::string_view option)
{
    if (text.empty())
        fail(std::string(option) + ": empty file name");
    return std::filesystem::path(std::string(text));
}

template <typename T>
void setOnce(std::optional<T>& slot, T value, std::string_view option)
{
    if (slot)
        fail(std::string(option) + " given more than once");
    slot = std::move(value);
}

} // namespace

CommandLine parseCommandLine(const std::vector<std::string>& args)
{
    CommandLine result;
    RenderJob& job = result.job;

    for (const auto& arg : args)
        if (arg == "--help" || arg == "-h")
        {
            result.action = CommandLine::Action::help;
            return result;
        }

    std::optional<std::filesystem::path> output;
    std::optional<double> sampleRate;
    bool listParameters = false;

    for (std::size_t i = 0; i < args.size(); ++i)
    {
        std::string option = args[i];
        std::optional<std::string> inlineValue;

        if (option.rfind("--", 0) == 0)
        {
            if (const auto equals = option.find('='); equals != std::string::npos)
            {
                inlineValue = option.substr(equals + 1);
                option.resize(equals);
            }
        }
        else if (option.empty() || option.front() != '-' || option == "-")
        {
            fail("unexpected argument " + inQuotes(option) + " (see --help)");
        }

        // The option's value: "--opt=VALUE" or the next argument. A next argument that
        // looks like an option ("--...") means the value is missing.
        auto value = [&]() -> std::string {
            if (inlineValue)
                return *inlineValue;
            if (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)
                fail("option " + option + " needs a value (see --help)");
            return args[++i];
        };
        auto flag = [&]() {
            if (inlineValue)
                fail("option " + option + " takes no value");
            return true;
        };

        if (option == "-o" || option == "--output")
            setOnce(output, parsePath(value(), option), option);
        else if (option == "--hit")
            job.hits.push_back(parseHit(value()));
        else if (option == "--midi")
            setOnce(job.midiFile, parsePath(value(), option), option);
        else if (option == "--seconds")
            setOnce(job.seconds, parseSeconds(value()), option);
        else if (option == "--sample-rate")
            setOnce(sampleRate, parseSampleRate(value()), option);
        else if (option == "--preset")
        {
            auto name = value();
            if (name.empty())
                fail("--preset: empty preset name");
            setOnce(job.preset, std::move(name), option);
        }
        else if (option == "--set")
            job.overrides.push_back(parseOverride(value()));
        else if (option == "--model")
            setOnce(job.airModel, parseModel(value()), option);
        else if (option == "--mic")
            setOnce(job.mic, parseMic(value()), option);
        else if (option == "--energy-csv")
            setOnce(job.energyCsv, parsePath(value(), option), option);
        else if (option == "--energy-plot")
            setOnce(job.energyPlot, parsePath(value(), option), option);
        else if (option == "--spectrogram")
            setOnce(job.spectrogram, parsePath(value(), option), option);
        else if (option == "--snare-plot")
            setOnce(job.snarePlot, parsePath(value(), option), option);
        else if (option == "--lossless")
            job.lossless = flag();
        else if (option == "--json")
            job.json = flag();
        else if (option == "--list-params")
            listParameters = flag();
        else if (option == "--bench")
            job.bench = flag();
        else if (option == "--bench-short")
            job.benchShort = flag();
        else if (option == "--block-size")
            setOnce(job.blockSize, parseBlockSize(value()), option);
        else if (option == "--bench-repeat")
            setOnce(job.benchRepeats, parseRepeats(value()), option);
        else if (option == "--bench-scenario")
            setOnce(job.benchScenario, parseScenario(value()), option);
        else
            fail("unknown option " + inQuotes(option) + " (see --help)");
    }

    if (sampleRate)
        job.sampleRate_Hz = *sampleRate;

    if (listParameters)
    {
        result.action = CommandLine::Action::listParameters;
        return result;
    }

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
  snaresim-render --list-params
  snaresim-render --help

Strikes:
  --hit TIME:VELOCITY   strike at TIME seconds (>= 0) with MIDI velocity 1..127, at the
                        default strike point; repeatable (e.g. --hit 0:100 --hit 0.5:60)
  --midi FILE           strike on every note-on of a Standard MIDI file (all tracks, tempo
                        map honoured, any note number; velocity-0 note-ons are note-offs)

Output:
  -o, --output FILE     the WAV file to write: 32-bit float (required)
  --mic top|bottom|far|mix|all
                        the signal in the WAV (default mix): top = batter velocity at
                        the top microphone, bottom = carry-head velocity at the bottom
                        (snare-side) microphone, far = far-field pressure, mix = their
                        weighted mix (the plug-in's output); all = four channels in the
                        order top, bottom, far, mix
  --seconds S           length in seconds, 0 < S <= 3600 (default: 2; with --midi, the
                        latest strike + 2). Strikes at or after the end are not played.
  --sample-rate HZ      whole number of Hz, 8000..384000 (default 48000)
  --energy-csv FILE     also write the energy ledger, one row per sample:
                        time_s,batter_J,carry_J,mallets_J,snares_J,cavity_J,total_J,
                        dissipated_J,injected_J,balance_J
                        (total = the five components; balance = total + dissipated
                        - injected, constant up to round-off)
  --energy-plot FILE    also write a PNG (1400 x 600): left, the normalised variation of
                        the energy balance (h^n - h^0) / h^0, h^0 = the total energy right
                        after the first strike; right, the energy of each component and
                        the total, against time in ms
  --spectrogram FILE    also write a PNG (1200 x 700): log-frequency spectrogram of the
                        WAV's signal (with --mic all: the mix), Hann window of 2048
                        samples at 48 kHz (scaled with the rate), 75 % overlap, 90 dB range
  --snare-plot FILE     also write a PNG (1200 x 700) of the snare wires for the first
                        25 ms after the first strike: top, the mean displacement of the
                        wires' interior nodes, the band between their lowest and highest,
                        and the carry head's mean displacement under them (mm); bottom,
                        the number of wire points touching the carry head; time in ms
  --json                print one JSON object with the render statistics on stdout
                        (default: a short human-readable summary on stdout)

Model:
  --preset NAME         start from a factory preset instead of the defaults
  --model cavity|none   the air between the heads: cavity (the enclosed air couples the
                        heads; the default) or none (heads uncoupled); sets air_model
                        after the preset, before any --set
  --set ID=VALUE        set one parameter (after the preset and --model); repeatable.
                        Integer, on/off and choice parameters take whole numbers only;
                        a choice also takes its name (e.g. air_model=none). The snares:
                        snares_engaged (0 off, 1 on), snare_tension, snare_count,
                        carry_tension, shell_depth
  --lossless            switch every loss off (energy is then conserved); reports the
                        energy balance drift (energy_relative_drift_max)
  --list-params         list every parameter (ID, range, unit, default) and exit

Benchmark:
  --bench               time the render as the plug-in runs it: the drum built from the
                        parameters (makeDrumConfig), blocks of --block-size samples through
                        Drum::process (the mix), strikes as MIDI note 38 (Drum::playNote) on
                        their sample, no energy tracking, denormals flushed; every block is
                        timed (steady clock). -o is optional; the other outputs, --lossless
                        and --mic other than mix are refused. The summary / JSON adds
                        realtime_factor (audio s / wall s), mean_block_ms, worst_block_ms,
                        block_budget_ms (one block's duration), worst_block_share (worst /
                        budget), block_size, blocks and the grid (batter_grid_spacing_m,
                        carry_grid_spacing_m, snare_points). Non-finite output: exit 1.
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
                        those times; worst_block_raw_ms is the slowest block of any run
                        and realtime_factor_slowest_run the slowest whole run. The audio,
                        -o and the other figures are of the first run.
)" + presetLine() + R"(
Exit status: 0 success, 2 bad input or unwritable output (one line on stderr starting
with "snaresim-render: error: ", no output file left behind), 1 internal failure,
130 / 143 interrupted by SIGINT / SIGTERM (no output file left behind).
Outputs (WAV, CSV, PNGs; no two may be the same file) are written to a temporary file
next to the target and renamed when complete.
)";
}

} // namespace snaresim::render
