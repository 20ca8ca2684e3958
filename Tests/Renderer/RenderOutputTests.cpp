// snaresim-render's successful runs: the WAV, the JSON report, MIDI input, the energy
// CSV, --list-params and --help.

#include "RendererTestSupport.h"

#include "Parameters.h"
#include "Presets.h"

#include <catch2/catch.hpp>

#include <sstream>

#include <juce_audio_basics/juce_audio_basics.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace rendertest;

namespace
{

// Checks the run succeeded and the WAV is mono 32-bit float, of this length and rate,
// non-silent and finite. Returns its samples.
std::vector<float> requireGoodWav(const RunResult& run, const fs::path& file, double rate, long long length)
{
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    REQUIRE(fs::is_regular_file(file));

    const auto wav = readWav(file);
    REQUIRE(wav.opened);
    CHECK(wav.sampleRate == rate);
    CHECK(wav.channels == 1);
    CHECK(wav.bitsPerSample == 32);
    CHECK(wav.floatingPoint);
    CHECK(wav.length == length);

    float peak = 0.0f;
    long long nonfinite = 0;
    for (const float x : wav.samples)
    {
        if (! std::isfinite(x))
            ++nonfinite;
        else
            peak = std::max(peak, std::abs(x));
    }
    CHECK(nonfinite == 0);
    CHECK(peak > 1.0e-6f);
    return wav.samples;
}

double number(const juce::var& object, const char* key)
{
    const auto& value = object[key];
    INFO("key " << key);
    REQUIRE((value.isDouble() || value.isInt() || value.isInt64()));
    return (double) value;
}

} // namespace

TEST_CASE("hits: --hit renders a mono float WAV of the asked length and rate", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "hits.wav";

    // Lengths are kept short: the full model renders slower than real time. The rates are
    // 44.1 / 48 kHz, which the engine must always accept (lower ones depend on its grid rules).
    SECTION("48 kHz, two hits")
    {
        const auto run =
            runRenderer({ "-o", wav.string(), "--hit", "0:100", "--hit", "0.5:60", "--seconds", "0.6", "--sample-rate", "48000" },
                        dir.root() / "capture");
        const auto samples = requireGoodWav(run, wav, 48000.0, 28800);

        // The second hit, at sample 24000 exactly, brings the level up again.
        auto peakIn = [&](std::size_t from, std::size_t to) {
            float peak = 0.0f;
            for (std::size_t i = from; i < to; ++i)
                peak = std::max(peak, std::abs(samples[i]));
            return peak;
        };
        CHECK(peakIn(24000, 26400) > 2.0f * peakIn(21600, 24000));
    }

    SECTION("default sample rate: 48 kHz")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:127", "--seconds", "0.1" }, dir.root() / "capture");
        requireGoodWav(run, wav, 48000.0, 4800);
    }

    SECTION("default length: 2 s")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:127", "--sample-rate", "44100" }, dir.root() / "capture");
        requireGoodWav(run, wav, 44100.0, 88200);
    }

    SECTION("44.1 kHz, a length that is not a whole number of samples")
    {
        const auto run =
            runRenderer({ "--hit=0.01:90", "--seconds=0.30001", "--sample-rate=44100", "--output", wav.string() }, dir.root() / "capture");
        requireGoodWav(run, wav, 44100.0, std::llround(0.30001 * 44100.0));
    }

    SECTION("a preset and --set")
    {
        const auto& presets = snaresim::factoryPresets();
        REQUIRE(! presets.empty());
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:100", "--seconds", "0.25", "--sample-rate", "44100", "--preset",
                                       std::string(presets.back().name), "--set", "mallet_mass=0.02", "--set", "output_gain=-6" },
                                     dir.root() / "capture");
        requireGoodWav(run, wav, 44100.0, 11025);
    }

    // Nothing but the output in the target directory (no temporaries).
    CHECK(entries(dir.out()) == std::vector<std::string> { "hits.wav" });
}

TEST_CASE("hits: a strike sounds when it is struck at 48 and 96 kHz as on the drum played at its simulated rate", "[renderer]")
{
    // The default's grids are simulated at 32 kHz and interpolated to 48 or 96 kHz, 2 ms late
    // (HostRateInterpolator.h); the renderer takes that lag off. At 32 kHz the same drum plays
    // uninterpolated, so the host's samples that fall on its steps (every third) hold its
    // samples up to the interpolation's band (14.4 kHz): -22 dB apart, where a step early or
    // late gives -7.5 dB, and the lag left on, 96 or 192 samples, more.
    TempDir dir;
    auto renderAt = [&](const std::string& rate) {
        const auto wav = dir.out() / ("strike-" + rate + ".wav");
        const auto run =
            runRenderer({ "-o", wav.string(), "--hit", "0.02:100", "--seconds", "0.1", "--sample-rate", rate }, dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        return readWav(wav).samples;
    };
    const auto simulated = renderAt("32000");
    REQUIRE(simulated.size() == 3200);
    // every third host sample against every second (48 kHz) or every (96 kHz) simulated one
    for (const auto& [rateName, stepPerSample] : std::vector<std::pair<std::string, std::size_t>> { { "48000", 2 }, { "96000", 1 } })
    {
        const std::string rate = rateName;
        const std::size_t step = stepPerSample;
        const auto host = renderAt(rate);
        auto errorAt = [&](int shift) { // dB of the difference against the signal, the simulated drum `shift` steps later
            double error = 0.0, signal = 0.0;
            for (std::size_t k = 10; k * 3 < host.size() && k * step + 10 < simulated.size(); ++k)
            {
                const double want = simulated[k * step - (std::size_t) shift], got = host[k * 3];
                error += (got - want) * (got - want);
                signal += want * want;
            }
            return 10.0 * std::log10(error / signal);
        };
        INFO(rate << " Hz: " << errorAt(0) << " dB, a step early " << errorAt(-1) << " dB, late " << errorAt(1) << " dB");
        CHECK(errorAt(0) < -15.0);
        CHECK(errorAt(-1) > -10.0);
        CHECK(errorAt(1) > -10.0);
    }
}

TEST_CASE("json: --json prints one JSON object with the render statistics", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "a.wav";
    const auto run =
        runRenderer({ "-o", wav.string(), "--hit", "0:100", "--hit", "0.1:80", "--seconds", "0.4", "--sample-rate", "44100", "--json" },
                    dir.root() / "capture");
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    CHECK(run.err.empty());
    CHECK(lines(run.out).size() == 1);

    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    for (const char* key :
         { "seconds_rendered", "wall_seconds", "realtime_factor", "peak", "rms", "nonfinite_samples", "sample_rate", "output" })
    {
        INFO("key " << key);
        CHECK(json.hasProperty(key));
    }

    CHECK(number(json, "seconds_rendered") == Approx(0.4));
    CHECK(number(json, "sample_rate") == 44100.0);
    CHECK(number(json, "nonfinite_samples") == 0.0);
    CHECK(number(json, "peak") > 0.0);
    CHECK(number(json, "rms") > 0.0);
    CHECK(number(json, "rms") <= number(json, "peak"));
    CHECK(number(json, "wall_seconds") > 0.0);
    CHECK(number(json, "realtime_factor") == Approx(number(json, "seconds_rendered") / number(json, "wall_seconds")).epsilon(1e-6));
    CHECK(number(json, "strikes") == 2.0);
    CHECK(json["output"].toString().toStdString() == fs::absolute(wav).string());
    CHECK(! json.hasProperty("energy_relative_drift_max"));
    CHECK(number(json, "channels") == 1.0);
    CHECK(json["mic"].toString() == "mix");
    for (const char* key : { "energy_csv", "energy_plot", "spectrogram", "snare_plot" })
    {
        INFO("key " << key);
        CHECK(json.hasProperty(key));
        CHECK(json[key].isVoid()); // null
    }
    // The statistics are the engine's for this render: the default drum at 44.1 kHz, played
    // in-process with the same strikes (samples 0 and 4410).
    const auto config = snaresim::makeDrumConfig(snaresim::ParameterSet {}, 44100.0);
    const auto engine = playInProcess(config, { { 0, 100 }, { 4410, 80 } }, 17640);
    INFO("engine: " << engine.stats.maxIterations << " Newton iterations at most, penetration " << engine.stats.maxSnarePenetration_m
                    << " m, peak " << engine.peak << ", rms " << engine.rms);
    CHECK(number(json, "solver_max_iterations") == engine.stats.maxIterations);
    CHECK(number(json, "solver_max_iterations") >= 1.0); // the mallets' contact is solved by Newton
    // The quadratised snare solve (the default) is one linear solve per step: no iteration.
    CHECK(config.snares.scheme == snaresim::CollisionScheme::quadratised);
    CHECK(number(json, "snare_max_iterations") == 0.0);
    CHECK(number(json, "snare_max_penetration_m") == Approx(engine.stats.maxSnarePenetration_m).epsilon(1e-9));
    // The wires press into the head, by far less than a carry-head grid cell.
    const snaresim::Drum drum(config);
    CHECK(number(json, "snare_max_penetration_m") > 0.0);
    CHECK(number(json, "snare_max_penetration_m") < 0.01 * drum.carry().grid().spacing());
    CHECK(number(json, "solver_fallbacks") == 0.0);

    // The peak and RMS it reports are the file's, and the engine's.
    const auto data = readWav(wav);
    REQUIRE(data.samples.size() == 17640);
    CHECK(data.samples == engine.mix);
    float peak = 0.0f;
    double sumSquares = 0.0;
    for (const float x : data.samples)
    {
        peak = std::max(peak, std::abs(x));
        sumSquares += (double) x * (double) x;
    }
    CHECK(number(json, "peak") == Approx(peak));
    CHECK(number(json, "rms") == Approx(std::sqrt(sumSquares / 17640.0)).epsilon(1e-9));
}

TEST_CASE("lossless: --lossless --json reports an energy balance drift below 1e-10 with double-precision heads", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "lossless.wav";
    const auto csv = dir.out() / "lossless.csv";
    const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:127", "--hit", "0.05:100", "--seconds", "0.3", "--sample-rate", "44100",
                                   "--lossless", "--json", "--energy-csv", csv.string(), "--set", "head_precision=double" },
                                 dir.root() / "capture");
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exitCode == 0);

    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    REQUIRE(json.hasProperty("energy_relative_drift_max"));
    const double drift = number(json, "energy_relative_drift_max");
    CHECK(drift < 1.0e-10);

    // It is max_n |balance_n - balance_0| / max_n total_n of the ledger, which the CSV holds
    // (numbers written to round-trip exactly).
    const auto rows = lines(readText(csv));
    REQUIRE(rows.size() == 13231); // the header and 0.3 s at 44.1 kHz
    const auto columns = energyColumns(rows.front());
    double balance0 = 0.0, deviation = 0.0, largest = 0.0;
    for (std::size_t i = 1; i < rows.size(); ++i)
    {
        std::vector<double> fields;
        for (const char *p = rows[i].data(), *end = p + rows[i].size(); p < end;)
        {
            double v = 0.0;
            const auto [next, ec] = std::from_chars(p, end, v);
            if (ec != std::errc {})
                break;
            fields.push_back(v);
            p = next + 1;
        }
        INFO("row " << i << ": " << rows[i]);
        REQUIRE(fields.size() == columns.names.size());
        if (i == 1)
            balance0 = fields[columns.balance];
        deviation = std::max(deviation, std::abs(fields[columns.balance] - balance0));
        largest = std::max(largest, std::abs(fields[columns.total]));
    }
    REQUIRE(largest > 0.0);
    INFO("from the CSV: " << deviation / largest);
    CHECK(drift == Approx(deviation / largest).epsilon(1e-9));
    CHECK(number(json, "nonfinite_samples") == 0.0);
    CHECK(number(json, "peak") > 0.0);
}

TEST_CASE("lossless: single-precision heads hold the energy balance to float round-off", "[renderer]")
{
    // 2^-24 per step, a random walk over the 13 230 steps: 2^-24 sqrt(13230) = 6.9e-6.
    TempDir dir;
    const auto run = runRenderer({ "-o", (dir.out() / "lossless.wav").string(), "--hit", "0:127", "--hit", "0.05:100", "--seconds", "0.3",
                                   "--sample-rate", "44100", "--lossless", "--json", "--set", "head_precision=single" },
                                 dir.root() / "capture");
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    const double drift = number(json, "energy_relative_drift_max");
    CHECK(drift < std::ldexp(1.0, -24) * std::sqrt(13230.0));
    CHECK(drift > 1.0e-10); // the heads do run in float
}

TEST_CASE("midi: --midi renders the note-ons of a Standard MIDI file, tempo map honoured", "[renderer]")
{
    TempDir dir;
    const auto midiPath = dir.in() / "groove.mid";
    const auto wav = dir.out() / "groove.wav";

    // Track 0: tempo 600 bpm, then 300 bpm from beat 1. Track 1: notes. 960 ticks per beat.
    //   beat 0 (0 s): note 38 vel 100; beat 0.5: a 0-velocity note-on (a note-off);
    //   beat 1 (0.1 s): note 40 vel 60; beat 2 (0.1 + 0.2 = 0.3 s): note 38 vel 127.
    {
        juce::MidiMessageSequence tempo;
        tempo.addEvent(juce::MidiMessage::tempoMetaEvent(100000), 0.0);
        tempo.addEvent(juce::MidiMessage::tempoMetaEvent(200000), 960.0);
        tempo.addEvent(juce::MidiMessage::endOfTrack(), 1920.0);

        juce::MidiMessageSequence notes;
        notes.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 100), 0.0);
        notes.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 0), 480.0); // a note-off
        notes.addEvent(juce::MidiMessage::noteOn(10, 40, (juce::uint8) 60), 960.0);
        notes.addEvent(juce::MidiMessage::noteOff(10, 40), 1200.0);
        notes.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127), 1920.0);
        notes.addEvent(juce::MidiMessage::noteOff(10, 38), 2000.0);

        juce::MidiFile file;
        file.setTicksPerQuarterNote(960);
        file.addTrack(tempo);
        file.addTrack(notes);

        juce::FileOutputStream out(juce::File(fs::absolute(midiPath).string()));
        REQUIRE(out.openedOk());
        REQUIRE(file.writeTo(out, 1));
    }

    SECTION("length: last note-on + 2 s")
    {
        const auto run =
            runRenderer({ "-o", wav.string(), "--midi", midiPath.string(), "--sample-rate", "44100", "--json" }, dir.root() / "capture");
        requireGoodWav(run, wav, 44100.0, std::llround(2.3 * 44100.0));

        const auto json = parseJson(run.out);
        REQUIRE(json.isObject());
        CHECK(number(json, "strikes") == 3.0);
        CHECK(number(json, "seconds_rendered") == Approx(2.3));
    }

    SECTION("--seconds cuts it short; later note-ons are not played")
    {
        const auto run =
            runRenderer({ "-o", wav.string(), "--midi", midiPath.string(), "--sample-rate", "44100", "--seconds", "0.2", "--json" },
                        dir.root() / "capture");
        requireGoodWav(run, wav, 44100.0, 8820);

        const auto json = parseJson(run.out);
        REQUIRE(json.isObject());
        CHECK(number(json, "strikes") == 2.0);
    }

    CHECK(entries(dir.out()) == std::vector<std::string> { "groove.wav" });
}

TEST_CASE("energy csv: --energy-csv writes the header and one row per sample", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "e.wav";
    const auto csv = dir.out() / "e.csv";
    const double rate = 44100.0;
    const long long length = 4410; // 0.1 s

    // The heads in double precision: the balance below is then constant to double round-off.
    const auto run = runRenderer({ "-o", wav.string(), "--energy-csv", csv.string(), "--hit", "0.01:100", "--seconds", "0.1",
                                   "--sample-rate", "44100", "--set", "head_precision=double" },
                                 dir.root() / "capture");
    requireGoodWav(run, wav, rate, length);
    REQUIRE(fs::is_regular_file(csv));

    const auto rows = lines(readText(csv));
    REQUIRE(rows.size() == (std::size_t) length + 1);
    // The ledger's terms (the default drum's six: the outside air's too), their total, and the balance terms.
    CHECK(rows.front() == "time_s,batter_J,carry_J,mallets_J,snares_J,cavity_J,outside_J,total_J,dissipated_J,injected_J,balance_J");
    const auto columns = energyColumns(rows.front());

    double maxTotal = 0.0, firstBalance = 0.0, maxDeviation = 0.0;
    for (std::size_t i = 1; i < rows.size(); ++i)
    {
        std::vector<double> fields;
        const char* p = rows[i].data();
        const char* end = p + rows[i].size();
        while (p <= end)
        {
            double v = 0.0;
            const auto [next, ec] = std::from_chars(p, end, v);
            REQUIRE(ec == std::errc {});
            fields.push_back(v);
            p = next + 1; // skip the comma
        }
        INFO("row " << i << ": " << rows[i]);
        REQUIRE(fields.size() == columns.names.size());
        CHECK(fields[0] == Approx((double) (i - 1) / rate));
        for (const double v : fields)
            REQUIRE(std::isfinite(v));
        double sum = 0.0;
        for (const auto t : columns.terms)
            sum += fields[t];
        CHECK(fields[columns.total] == Approx(sum)); // total
        CHECK(fields[columns.balance] ==
              Approx(fields[columns.total] + fields[columns.dissipated] - fields[columns.injected]).margin(1e-12));

        maxTotal = std::max(maxTotal, fields[columns.total]);
        if (i == 1)
            firstBalance = fields[columns.balance];
        maxDeviation = std::max(maxDeviation, std::abs(fields[columns.balance] - firstBalance));
    }
    CHECK(maxTotal > 0.0); // the strike put energy in:
    // the mallet's (1/2) M v^2 at velocity 100, less what the first step's losses took (1e-6 of it)
    const snaresim::ParameterSet defaults;
    const double v = snaresim::strikeSpeedFromVelocity(100, defaults.get(snaresim::ParamId::strikeSpeedMax));
    CHECK(maxTotal == Approx(0.5 * defaults.get(snaresim::ParamId::malletMass) * v * v).epsilon(1e-5));
    CHECK(maxDeviation <= 1.0e-9 * maxTotal); // balance constant (lossy run)

    CHECK(entries(dir.out()) == std::vector<std::string> { "e.csv", "e.wav" });
}

TEST_CASE("energy terms: the CSV's columns and the JSON's energy_max_J are the engine ledger's terms, in order", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "terms.wav";
    const auto csv = dir.out() / "terms.csv";
    const auto run = runRenderer(
        { "-o", wav.string(), "--energy-csv", csv.string(), "--hit", "0:110", "--seconds", "0.05", "--sample-rate", "44100", "--json" },
        dir.root() / "capture");
    INFO("stdout: " << run.out << "\nstderr: " << run.err);
    REQUIRE(run.exitCode == 0);

    // The ledger of the drum the renderer builds (the default parameters).
    const snaresim::Drum drum(snaresim::makeDrumConfig(snaresim::ParameterSet {}, 44100.0));
    std::vector<std::string> termColumns;
    for (const auto& term : drum.energy().terms())
        termColumns.push_back(snaresim::EnergyLedger::columnName(term.name));
    REQUIRE(! termColumns.empty());

    const auto rows = lines(readText(csv));
    REQUIRE(rows.size() == 2206); // the header and 0.05 s at 44.1 kHz
    const auto columns = energyColumns(rows.front());
    std::vector<std::string> csvTerms;
    for (const auto t : columns.terms)
        csvTerms.push_back(columns.names[t]);
    CHECK(csvTerms == termColumns);

    // The JSON: energy_max_J holds each term and the total, in the CSV's order, each the
    // largest value of its column.
    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    const auto maxima = json["energy_max_J"];
    REQUIRE(maxima.getDynamicObject() != nullptr);
    std::vector<std::string> keys;
    for (const auto& property : maxima.getDynamicObject()->getProperties())
        keys.push_back(property.name.toString().toStdString());
    auto expectedKeys = termColumns;
    expectedKeys.push_back("total_J");
    CHECK(keys == expectedKeys);

    std::vector<std::size_t> checked = columns.terms;
    checked.push_back(columns.total);
    std::vector<double> largest(checked.size(), -std::numeric_limits<double>::infinity());
    for (std::size_t i = 1; i < rows.size(); ++i)
    {
        const auto fields = csvFields(rows[i]);
        REQUIRE(fields.size() == columns.names.size());
        for (std::size_t c = 0; c < checked.size(); ++c)
            largest[c] = std::max(largest[c], std::stod(fields[checked[c]]));
    }
    for (std::size_t c = 0; c < checked.size(); ++c)
    {
        const auto& name = columns.names[checked[c]];
        INFO("column " << name);
        CHECK((double) maxima[juce::Identifier(name)] == Approx(largest[c]).epsilon(1e-12));
    }
    // The mallet brought the strike's energy and gave some of it to the batter.
    CHECK((double) maxima["batter_J"] > 0.0);
    CHECK((double) maxima["mallets_J"] > 0.0);
    CHECK((double) maxima["total_J"] > 0.0);
}

TEST_CASE("list params: --list-params lists every parameter", "[renderer]")
{
    TempDir dir;
    const auto run = runRenderer({ "--list-params" }, dir.root() / "capture");
    REQUIRE(run.exitCode == 0);
    CHECK(run.err.empty());
    CHECK(run.out == snaresim::describeParameters());
    // A header, then one line per parameter in the schema's order: key, min, max, default, unit.
    std::istringstream lines(run.out);
    std::string line;
    REQUIRE(std::getline(lines, line));
    CHECK(line.rfind("# id", 0) == 0);
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        REQUIRE(std::getline(lines, line));
        std::istringstream fields(line);
        std::string key, unit;
        double lo = 0.0, hi = 0.0, def = 0.0;
        fields >> key >> lo >> hi >> def >> unit;
        CHECK(key == spec.key);
        CHECK(lo == Approx(spec.minValue));
        CHECK(hi == Approx(spec.maxValue));
        CHECK(def == Approx(spec.defaultValue));
        CHECK(unit == (spec.unit.empty() ? "-" : std::string(spec.unit)));
        CHECK((line.find("(rebuilds the model)") != std::string::npos) == spec.rebuildsModel());
    }
    CHECK_FALSE(std::getline(lines, line));
}

TEST_CASE("help: --help prints the usage and exits 0", "[renderer]")
{
    TempDir dir;
    for (const char* option : { "--help", "-h" })
    {
        const auto run = runRenderer({ option }, dir.root() / "capture");
        CHECK(run.exitCode == 0);
        CHECK(run.out.find("Usage:") != std::string::npos);
        CHECK(run.out.find("--hit") != std::string::npos);
        CHECK(run.err.empty());
    }
}

TEST_CASE("the air box renders its air microphones, one channel each", "[renderer][airbox]")
{
    TempDir dir;
    const auto wav = dir.out() / "box.wav";
    // Default microphones: close top, bottom, far; a short render at 22.05 kHz.
    auto run =
        runRenderer({ "-o", wav.string(), "--hit", "0:110", "--seconds", "0.03", "--sample-rate", "22050", "--model", "airbox", "--json" },
                    dir.root() / "capture");
    REQUIRE(run.exitCode == 0);
    CHECK(run.out.find("\"mic\": \"air\"") != std::string::npos);
    auto data = readWav(wav);
    REQUIRE(data.opened);
    CHECK(data.channels == 3);
    float close = 0.0f, far = 0.0f;
    for (const float x : data.channelSamples[0])
        close = std::max(close, std::abs(x));
    for (const float x : data.channelSamples[2])
        far = std::max(far, std::abs(x));
    INFO("peaks: close top " << close << ", far " << far);
    CHECK(close > 1.0e-3f);
    CHECK(close < 4.0f);
    CHECK(far < close); // farther from the batter, quieter

    // Two microphones given: two channels, the one above the batter louder than the one
    // beside the shell at the same height farther out.
    run = runRenderer({ "-o", wav.string(), "--hit", "0:110", "--seconds", "0.03", "--sample-rate", "22050", "--model", "airbox",
                        "--air-mic", "0.1,0,0.12", "--air-mic", "0.24,0,0.12" },
                      dir.root() / "capture");
    REQUIRE(run.exitCode == 0);
    data = readWav(wav);
    REQUIRE(data.channels == 2);
    float near = 0.0f, side = 0.0f;
    for (std::size_t i = 0; i < data.channelSamples[0].size(); ++i)
    {
        near = std::max(near, std::abs(data.channelSamples[0][i]));
        side = std::max(side, std::abs(data.channelSamples[1][i]));
        REQUIRE(std::isfinite(data.channelSamples[0][i]));
    }
    INFO("peaks: above the batter " << near << ", beside " << side);
    CHECK(near > side);
}
