// snaresim-render --bench: the timing report (keys and sane values, never a time limit), the
// block size, the scenarios, --bench-short, and the options it refuses.
// Coarse grids (Quality at 7.8 or 5.1 kHz: bandwidth=7839.5127 or 5093.8628) keep the renders quick.

#include "RendererTestSupport.h"

#include "AirBox.h"
#include "Cavity.h"
#include "Membrane.h"
#include "StepProfile.h"

#include <catch2/catch.hpp>

#include <juce_audio_basics/juce_audio_basics.h>

#include <cmath>

using namespace rendertest;

namespace
{

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more)
{
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

double number(const juce::var& object, const char* key)
{
    const auto& value = object[key];
    INFO("key " << key);
    REQUIRE((value.isDouble() || value.isInt() || value.isInt64()));
    return (double) value;
}

// Runs a benchmark that must succeed and print one JSON object; returns it.
juce::var benchJson(const TempDir& dir, const std::vector<std::string>& args)
{
    std::string command;
    for (const auto& a : args)
        command += " " + a;
    INFO("snaresim-render --bench --json" << command);

    const auto run = runRenderer(with({ "--bench", "--json" }, args), dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    CHECK(run.err.empty());
    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    CHECK((bool) json["bench"]);
    return json;
}

} // namespace

TEST_CASE("bench: --json reports the block timings with sane values", "[renderer][bench]")
{
    TempDir dir;
    const auto json = benchJson(dir, { "--seconds", "0.25", "--block-size", "32", "--set", "bandwidth=7839.5127" });

    // 0.25 s at 48 kHz in blocks of 32 samples; the default scenario strikes once, at 0.
    CHECK(number(json, "samples") == 12000);
    CHECK(number(json, "block_size") == 32);
    CHECK(number(json, "blocks") == 375);
    CHECK(number(json, "strikes") == 1);
    CHECK(json["bench_scenario"].toString() == "default");
    CHECK(! (bool) json["bench_short"]);
    CHECK(json["output"].isVoid()); // no -o: nothing written
    CHECK(! (bool) json["energy_tracking"]);
    CHECK(json["mic"].toString() == "mix");

    const double mean = number(json, "mean_block_ms");
    const double worst = number(json, "worst_block_ms");
    const double budget = number(json, "block_budget_ms");
    const double wall = number(json, "wall_seconds");
    CHECK(mean > 0.0);
    CHECK(worst >= mean);
    CHECK(budget == Approx(1000.0 * 32.0 / 48000.0));
    CHECK(number(json, "worst_block_share") == Approx(worst / budget));
    // the worst block starts on a block's boundary within the 0.25 s rendered
    const double at = number(json, "worst_block_at_s");
    CHECK(at >= 0.0);
    CHECK(at < 0.25);
    CHECK(std::fmod(at * 48000.0 + 0.5, 32.0) == Approx(0.5).margin(1e-6));
    CHECK(wall > 0.0);
    CHECK(mean == Approx(1000.0 * wall / 375.0));
    CHECK(number(json, "realtime_factor") > 0.0);
    CHECK(number(json, "realtime_factor") == Approx(0.25 / wall));
    // Five runs by default; the block times are each block's fastest run, so no raw block is
    // faster than the worst of them and no run is faster than their sum.
    CHECK(number(json, "repeats") == 5);
    CHECK(number(json, "worst_block_raw_ms") >= worst);
    CHECK(number(json, "realtime_factor_slowest_run") > 0.0);
    CHECK(number(json, "realtime_factor_slowest_run") <= number(json, "realtime_factor"));

    // The model's size: the default drum's at its default Quality, 48 kHz (simulated at 32 kHz
    // on grids designed at the 48 kHz step). Each head's spacing is the Quality's coarseness
    // times the bound of eq. (39) at that step for the largest tension and sigma1 the controls
    // allow, widened for the air's reserve there (Membrane::gridSpacing); every interior wire
    // node is a point.
    snaresim::ParameterSet params;
    params.set(snaresim::ParamId::bandwidth, 7839.5127);
    const auto config = snaresim::makeDrumConfig(params, 48000.0);
    const snaresim::Drum drum(config);
    const double k = 1.0 / 48000.0;
    for (const bool ofBatter : { true, false })
    {
        const auto* head = ofBatter ? &config.batter : &config.carry;
        const double reserve = config.designReserve(ofBatter);
        const double bound = std::sqrt(
            (2.0 * k * k * head->gridTension_N_per_m / head->density_kg_per_m2 + 8.0 * head->gridSigma1_m2_per_s * k) / (1.0 - reserve));
        CHECK(snaresim::Membrane::gridSpacing(*head, k, reserve) == Approx(snaresim::gridCoarsenessFor(7839.5127) * bound).epsilon(1e-12));
    }
    CHECK(number(json, "batter_grid_spacing_m") == Approx(drum.batter().grid().spacing()).epsilon(1e-12));
    CHECK(number(json, "carry_grid_spacing_m") == Approx(drum.carry().grid().spacing()).epsilon(1e-12));
    CHECK(config.sampleRate_Hz == 32000.0);
    CHECK(number(json, "simulation_rate") == 32000.0);
    CHECK(drum.batter().grid().spacing() ==
          Approx(snaresim::Membrane::gridSpacing(config.batter, 1.0 / config.sampleRate_Hz, config.kineticReserve(true),
                                                 config.designReserve(true))));
    CHECK(drum.batter().grid().spacing() == Approx(snaresim::Membrane::gridSpacing(config.batter, k, config.designReserve(true))));
    CHECK(number(json, "batter_nodes") == drum.batter().grid().numInterior());
    CHECK(number(json, "carry_nodes") == drum.carry().grid().numInterior());
    CHECK(number(json, "snare_points") == config.snares.count * (drum.snareWires().intervals() - 1));

    // The whole drum's compute per second of audio, and the process's peak size; no air box figures.
    CHECK(number(json, "compute_seconds_per_audio_second") == Approx(wall / 0.25));
    CHECK(number(json, "peak_resident_mb") > 1.0);
    CHECK(json["air_points"].isVoid());
    CHECK(json["air_updates_per_second"].isVoid());

    CHECK(number(json, "nonfinite_samples") == 0);
    CHECK(number(json, "peak") > 0.0);
    // The peak is the engine's: the same drum, MIDI note 38 at velocity 127 at sample 0, the
    // mix as float, denormals flushed as the benchmark does (Benchmark.h).
    {
        const juce::ScopedNoDenormals noDenormals;
        snaresim::Drum played(config);
        played.playNote(38, 127);
        float peak = 0.0f;
        for (int n = 0; n < 12000; ++n)
            peak = std::max(peak, std::abs((float) played.step()));
        CHECK(number(json, "peak") == Approx(peak).epsilon(1e-9));
    }
}

TEST_CASE("bench: with the air box it reports the air update against a bare stencil, the drum's compute and the peak size",
          "[renderer][bench][airbox]")
{
    TempDir dir;
    // 22.05 kHz: the default 0.6 m box on a grid of twice the spacing (eq. 41), about 12 000 points
    const auto json = benchJson(dir, { "--model", "airbox", "--sample-rate", "22050", "--seconds", "0.02", "--bench-repeat", "1",
                                       "--threads", "2", "--set", "bandwidth=5093.8628" });
    CHECK(number(json, "samples") == 441);
    CHECK(number(json, "nonfinite_samples") == 0);

    // The size of the air: the drum's box (its config, as the renderer makes it) on its grid.
    snaresim::ParameterSet params;
    params.set(snaresim::ParamId::bandwidth, 5093.8628);
    params.set(snaresim::ParamId::airModel, (double) snaresim::AirModel::airbox);
    const auto config = snaresim::makeDrumConfig(params, 22050.0);
    const snaresim::AirBox box(config.airBoxSpec(), 1.0 / 22050.0);
    CHECK(number(json, "air_points") == box.numPoints());
    CHECK(number(json, "air_spacing_m") == Approx(box.spacing()).epsilon(1e-12));
    CHECK(box.numPoints() > 5000);
    CHECK(number(json, "air_threads") == 2);
    CHECK(json["air_precision"].toString() == "double");

    // Rates: positive and consistent with each other (their values are the machine's).
    const double air = number(json, "air_updates_per_second");
    const double airThreads = number(json, "air_updates_per_second_threads");
    const double bare = number(json, "bare_stencil_updates_per_second");
    const double bareFloat = number(json, "bare_stencil_float_updates_per_second");
    for (const double rate : { air, airThreads, bare, bareFloat })
    {
        CHECK(rate > 0.0);
        CHECK(std::isfinite(rate));
    }
    CHECK(number(json, "air_to_bare_ratio") == Approx(air / bare));
    CHECK(number(json, "air_to_bare_ratio_threads") == Approx(airThreads / bare));

    // The whole drum's compute per second of audio is the blocks' time over the audio's length.
    const double wall = number(json, "wall_seconds");
    CHECK(wall > 0.0);
    CHECK(number(json, "compute_seconds_per_audio_second") == Approx(wall / 0.02));
    CHECK(number(json, "realtime_factor") == Approx(0.02 / wall));

    // The peak resident size holds at least the air's three time levels.
    const double levels_mb = 3.0 * 8.0 * (double) box.numPoints() / (1024.0 * 1024.0);
    CHECK(number(json, "peak_resident_mb") > levels_mb);
    CHECK(number(json, "peak_resident_mb") < 1.0e6);
}

TEST_CASE("bench: the block size defaults to 64 and does not change the audio", "[renderer][bench]")
{
    TempDir dir;
    const auto a = dir.out() / "a.wav";
    const auto b = dir.out() / "b.wav";
    const std::vector<std::string> quick { "--seconds", "0.2", "--set", "bandwidth=5093.8628", "--hit", "0.013:127", "--hit", "0.05:90" };

    const auto json = benchJson(dir, with({ "-o", a.string() }, quick));
    CHECK(number(json, "block_size") == 64);
    CHECK(number(json, "blocks") == 150); // 9600 samples
    CHECK(number(json, "strikes") == 2);
    CHECK(json["bench_scenario"].toString() == "custom");
    CHECK(json["output"].toString().toStdString() == fs::absolute(a).string());

    // Blocks of 7 split differently around the strikes: the same samples.
    benchJson(dir, with({ "-o", b.string(), "--block-size", "7" }, quick));
    const auto wavA = readWav(a);
    const auto wavB = readWav(b);
    REQUIRE(wavA.opened);
    REQUIRE(wavB.opened);
    CHECK(wavA.channels == 1);
    CHECK(wavA.floatingPoint);
    CHECK(wavA.length == 9600);
    CHECK(peakOf(wavA.samples) > 0.0f);
    CHECK(wavA.samples == wavB.samples);

    // One run or three: the WAV is the first run's, the same samples.
    const auto c = dir.out() / "c.wav";
    const auto once = benchJson(dir, with({ "-o", c.string(), "--bench-repeat", "1" }, quick));
    CHECK(number(once, "repeats") == 1);
    CHECK(number(once, "worst_block_raw_ms") == Approx(number(once, "worst_block_ms")));
    const auto wavC = readWav(c);
    REQUIRE(wavC.opened);
    CHECK(wavA.samples == wavC.samples);
}

TEST_CASE("bench: the roll scenario renders 16 strikes in 1.5 s", "[renderer][bench]")
{
    TempDir dir;
    const auto json = benchJson(dir, { "--bench-scenario", "roll", "--set", "bandwidth=5093.8628" });
    CHECK(json["bench_scenario"].toString() == "roll");
    CHECK(number(json, "strikes") == 16);
    CHECK(number(json, "strikes_outside") == 0);
    CHECK(number(json, "samples") == 72000);
    CHECK(number(json, "seconds_rendered") == Approx(1.5));
    CHECK(number(json, "nonfinite_samples") == 0);
    CHECK(number(json, "worst_block_ms") >= number(json, "mean_block_ms"));
}

TEST_CASE("bench: the default scenario strikes every 0.5 s, --hit replaces it", "[renderer][bench]")
{
    TempDir dir;
    const auto every = benchJson(dir, { "--seconds", "1.2", "--set", "bandwidth=5093.8628" });
    CHECK(number(every, "strikes") == 3); // 0, 0.5, 1.0
    CHECK(number(every, "samples") == 57600);

    const auto hit = benchJson(dir, { "--seconds", "0.1", "--hit", "0.02:40", "--set", "bandwidth=5093.8628" });
    CHECK(number(hit, "strikes") == 1);
    CHECK(hit["bench_scenario"].toString() == "custom");
}

TEST_CASE("bench: --bench-short renders 0.25 s of the default scenario", "[renderer][bench]")
{
    TempDir dir;
    const auto json = benchJson(dir, { "--bench-short" });
    CHECK((bool) json["bench_short"]);
    CHECK(json["bench_scenario"].toString() == "default");
    CHECK(number(json, "samples") == 12000);
    CHECK(number(json, "strikes") == 1);
    CHECK(number(json, "block_size") == 64);
    CHECK(number(json, "nonfinite_samples") == 0);
    CHECK(number(json, "repeats") == 1);

    // Without --json: a readable summary.
    const auto run = runRenderer({ "--bench", "--bench-short" }, dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    CHECK(run.out.find("realtime factor") != std::string::npos);
    CHECK(run.out.find("worst") != std::string::npos);
    CHECK(run.out.find("budget") != std::string::npos);
    CHECK(entries(dir.out()).empty());
}

TEST_CASE("bench: the step profile of one more run, phase by phase, with shares that add up to 1", "[renderer][bench][profile]")
{
    TempDir dir;
    const bool airBox = GENERATE(false, true);
    const auto json = airBox ? benchJson(dir, { "--model", "airbox", "--sample-rate", "22050", "--seconds", "0.02", "--bench-repeat", "1",
                                                "--set", "bandwidth=5093.8628" })
                             : benchJson(dir, { "--bench-short" });
    const auto& profile = json["profile"];
    REQUIRE(profile.isObject());
    const auto path = airBox ? snaresim::StepPath::airBox : snaresim::StepPath::cavity;
    CHECK(profile["path"].toString() == juce::String(std::string(snaresim::StepProfile::name(path))));
    // a step a simulated sample: 2 in 3 of the host's at 48 kHz (HostRateInterpolator.h)
    CHECK(number(profile, "steps") ==
          Approx(number(json, "samples") * number(json, "simulation_rate") / number(json, "sample_rate")).margin(1.0));

    const auto& phases = profile["phases"];
    REQUIRE(phases.isObject());
    const auto expected = snaresim::StepProfile::phasesOf(path);
    CHECK(phases.getDynamicObject()->getProperties().size() == (int) expected.size());
    double shares = 0.0, perSecond = 0.0;
    for (const auto phase : expected)
    {
        const std::string name(snaresim::StepProfile::name(phase));
        INFO("phase " << name);
        const auto& entry = phases[juce::Identifier(juce::String(name))];
        REQUIRE(entry.isObject());
        const double share = number(entry, "share"), seconds = number(entry, "compute_seconds_per_audio_second");
        CHECK(share >= 0.0);
        CHECK(share <= 1.0);
        CHECK(seconds >= 0.0);
        shares += share;
        perSecond += seconds;
    }
    CHECK(std::abs(shares - 1.0) <= 1e-6);
    CHECK(number(phases["energy"], "share") == 0.0); // no energy tracking in the benchmark

    // The phases' sum, inside the profiled run's blocks; the overhead against the fastest timed run.
    const double steps = number(profile, "compute_seconds_per_audio_second");
    const double run = number(profile, "run_compute_seconds_per_audio_second");
    const double fastest = number(profile, "fastest_run_compute_seconds_per_audio_second");
    CHECK(steps > 0.0);
    CHECK(steps == Approx(perSecond).epsilon(1e-9));
    CHECK(run >= steps);
    CHECK(fastest > 0.0);
    CHECK(number(profile, "overhead") == Approx(run / fastest - 1.0).margin(1e-9));
    // The timed figures are the unprofiled runs': no run is faster than the sum of each block's fastest.
    CHECK(fastest >= number(json, "compute_seconds_per_audio_second") * (1.0 - 1e-9));

    // The summary lists the phases too.
    if (! airBox)
    {
        const auto summary = runRenderer({ "--bench", "--bench-short" }, dir.root() / "capture");
        REQUIRE(summary.exitCode == 0);
        CHECK(summary.out.find("profile (one more run, cavity path)") != std::string::npos);
        CHECK(summary.out.find("snare_contact") != std::string::npos);
        CHECK(summary.out.find("batter_free") != std::string::npos);
    }
}

TEST_CASE("bench: bad block sizes and refused options exit with 2", "[renderer][bench][errors]")
{
    TempDir dir;
    const auto wav = (dir.out() / "out.wav").string();

    requireRejected(dir, { "--bench", "--block-size", "0" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size", "8193" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size", "-64" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size", "64.5" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size", "big" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size" }, "--block-size");
    requireRejected(dir, { "--bench", "--block-size", "64", "--block-size", "32" }, "more than once");
    requireRejected(dir, { "--bench", "--bench-scenario", "march" }, "--bench-scenario");
    requireRejected(dir, { "--bench", "--bench-repeat", "0" }, "--bench-repeat");
    requireRejected(dir, { "--bench", "--bench-repeat", "51" }, "--bench-repeat");
    requireRejected(dir, { "--bench", "--bench-repeat", "two" }, "--bench-repeat");
    requireRejected(dir, { "--bench", "--bench-short", "--seconds", "1" }, "--bench-short");
    requireRejected(dir, { "--bench", "--bench-short", "--bench-scenario", "roll" }, "--bench-short");
    requireRejected(dir, { "--bench", "--energy-csv", (dir.out() / "e.csv").string() }, "--energy-csv");
    requireRejected(dir, { "--bench", "--spectrogram", (dir.out() / "s.png").string() }, "--spectrogram");
    requireRejected(dir, { "--bench", "--lossless" }, "--lossless");
    requireRejected(dir, { "--bench", "--mic", "top" }, "--mic");
    requireRejected(dir, { "--bench=yes" }, "--bench");

    // The benchmark options belong to --bench.
    requireRejected(dir, { "-o", wav, "--hit", "0:100", "--block-size", "64" }, "--block-size");
    requireRejected(dir, { "-o", wav, "--hit", "0:100", "--bench-short" }, "--bench-short");
    requireRejected(dir, { "-o", wav, "--hit", "0:100", "--bench-repeat", "2" }, "--bench-repeat");
    requireRejected(dir, { "-o", wav, "--hit", "0:100", "--bench-scenario", "roll" }, "--bench-scenario");

    // The engine's checks still apply.
    requireRejected(dir, { "--bench", "--set", "bandwidth=99" }, "bandwidth");
}
