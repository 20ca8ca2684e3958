// snaresim-render and the whole drum: --model (the air cavity), --mic (the microphones),
// the snare controls through --set, and the PNG outputs (--energy-plot, --spectrogram,
// --snare-plot).
// Renders are short (0.3 s) and coarse (grid_coarseness=2) where detail does not matter.

#include "RendererTestSupport.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace rendertest;

namespace
{

const std::vector<std::string> kQuick { "--hit", "0:100", "--seconds", "0.3", "--set", "grid_coarseness=2" };

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more)
{
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// Runs a render that must succeed with a WAV of 0.3 s at 48 kHz and `channels` finite
// channels; returns them.
std::vector<std::vector<float>> renderOk(const TempDir& dir, const fs::path& wav, const std::vector<std::string>& args,
                                         int channels = 1)
{
    const auto run = runRenderer(with({ "-o", wav.string() }, args), dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);

    const auto data = readWav(wav);
    REQUIRE(data.opened);
    CHECK(data.sampleRate == 48000.0);
    REQUIRE(data.channels == channels);
    CHECK(data.length == 14400);
    for (const auto& channel : data.channelSamples)
        for (const float x : channel)
            REQUIRE(std::isfinite(x));
    return data.channelSamples;
}

double number(const juce::var& object, const char* key)
{
    const auto& value = object[key];
    INFO("key " << key);
    REQUIRE((value.isDouble() || value.isInt() || value.isInt64()));
    return (double) value;
}

// Two signals differ clearly: the RMS of their difference is at least 1 % of the larger peak.
bool clearlyDifferent(const std::vector<float>& a, const std::vector<float>& b)
{
    return rmsDifference(a, b) > 0.01 * std::max(peakOf(a), peakOf(b));
}

} // namespace

TEST_CASE("model: --model none and --model cavity both render and sound different", "[renderer]")
{
    TempDir dir;
    const auto none = renderOk(dir, dir.out() / "none.wav", with(kQuick, { "--model", "none" }));
    const auto cavity = renderOk(dir, dir.out() / "cavity.wav", with(kQuick, { "--model=cavity" }));

    CHECK(peakOf(none[0]) > 1.0e-6f);
    CHECK(peakOf(cavity[0]) > 1.0e-6f);
    CHECK(clearlyDifferent(none[0], cavity[0]));

    // A later --set air_model wins over --model (and the engine is deterministic).
    const auto overridden = renderOk(dir, dir.out() / "overridden.wav",
                                     with(kQuick, { "--model", "none", "--set", "air_model=cavity" }));
    CHECK(overridden[0] == cavity[0]);

    CHECK(entries(dir.out()) == std::vector<std::string> { "cavity.wav", "none.wav", "overridden.wav" });
}

TEST_CASE("mic: --mic all writes four channels (top, bottom, far, mix)", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "all.wav";
    const auto run = runRenderer(with({ "-o", wav.string(), "--mic", "all", "--json" }, kQuick), dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto json = parseJson(run.out);
    REQUIRE(json.isObject());
    CHECK(number(json, "channels") == 4.0);
    CHECK(json["mic"].toString() == "all");
    CHECK(number(json, "nonfinite_samples") == 0.0);

    const auto data = readWav(wav);
    REQUIRE(data.opened);
    REQUIRE(data.channels == 4);
    CHECK(data.length == 14400);
    float peak = 0.0f;
    for (const auto& channel : data.channelSamples)
    {
        for (const float x : channel)
            REQUIRE(std::isfinite(x));
        peak = std::max(peak, peakOf(channel));
    }
    CHECK(number(json, "peak") == Approx(peak)); // over every channel

    const auto& top = data.channelSamples[0];
    const auto& bottom = data.channelSamples[1];
    const auto& far = data.channelSamples[2];
    CHECK(peakOf(top) > 1.0e-6f);
    CHECK(peakOf(bottom) > 1.0e-6f);
    CHECK(peakOf(far) > 1.0e-6f);
    CHECK(clearlyDifferent(top, bottom));
    CHECK(clearlyDifferent(top, far));
    CHECK(clearlyDifferent(bottom, far));

    // The order is top, bottom, far, mix: the single-signal renders match their channel.
    const auto mix = renderOk(dir, dir.out() / "mix.wav", kQuick);
    CHECK(mix[0] == data.channelSamples[3]);
    const auto onlyFar = renderOk(dir, dir.out() / "far.wav", with(kQuick, { "--mic", "far" }));
    CHECK(onlyFar[0] == far);
}

TEST_CASE("snares: --set snares_engaged=0 renders and differs from the default", "[renderer]")
{
    TempDir dir;
    const auto capture = dir.root() / "capture";

    const auto onRun = runRenderer(with({ "-o", (dir.out() / "on.wav").string(), "--json" }, kQuick), capture);
    INFO("stderr: " << onRun.err);
    REQUIRE(onRun.exitCode == 0);
    const auto onJson = parseJson(onRun.out);

    const auto offRun = runRenderer(
        with({ "-o", (dir.out() / "off.wav").string(), "--json", "--set", "snares_engaged=0" }, kQuick), capture);
    INFO("stderr: " << offRun.err);
    REQUIRE(offRun.exitCode == 0);
    const auto offJson = parseJson(offRun.out);

    const auto on = readWav(dir.out() / "on.wav");
    const auto off = readWav(dir.out() / "off.wav");
    REQUIRE(on.opened);
    REQUIRE(off.opened);
    REQUIRE(on.length == off.length);
    CHECK(peakOf(off.samples) > 1.0e-6f);
    CHECK(clearlyDifferent(on.samples, off.samples));

    // Snares off: no snare contact at all.
    REQUIRE(offJson.isObject());
    CHECK(number(offJson, "snare_max_iterations") == 0.0);
    CHECK(number(offJson, "snare_max_penetration_m") == 0.0);
    REQUIRE(onJson.isObject());
    CHECK(number(onJson, "snare_max_penetration_m") >= 0.0);

    // The other snare controls reach the engine too.
    renderOk(dir, dir.out() / "controls.wav",
             with(kQuick, { "--set", "snare_tension=50", "--set", "snare_count=12", "--set", "carry_tension=2500",
                            "--set", "shell_depth=0.1" }));
}

TEST_CASE("plots: --energy-plot and --spectrogram write PNG images", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "drum.wav";
    const auto energy = dir.out() / "energy.png";
    const auto spectrum = dir.out() / "spectrum.png";

    SECTION("both, with the four microphones and the CSV")
    {
        const auto csv = dir.out() / "energy.csv";
        const auto run = runRenderer(with({ "-o", wav.string(), "--mic", "all", "--energy-plot", energy.string(),
                                            "--spectrogram", spectrum.string(), "--energy-csv", csv.string(), "--json" },
                                          kQuick),
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        REQUIRE(json.isObject());
        CHECK(json["energy_plot"].toString().toStdString() == fs::absolute(energy).string());
        CHECK(json["spectrogram"].toString().toStdString() == fs::absolute(spectrum).string());
        CHECK(json["energy_tracking"] == juce::var(true));

        requirePicture(energy, 1400, 600);
        // Inside each panel: curves over white and grid, not one colour.
        CHECK(distinctColours(energy, 150, 80, 450, 400) > 10);
        CHECK(distinctColours(energy, 820, 80, 380, 400) > 10);

        requirePicture(spectrum, 1200, 700);
        CHECK(distinctColours(spectrum, 200, 100, 800, 500) > 50); // the spectrogram itself

        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "energy.csv", "energy.png", "spectrum.png" });
    }

    SECTION("a render shorter than one analysis window, lossless")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:127", "--seconds", "0.02", "--lossless",
                                       "--energy-plot", energy.string(), "--spectrogram", spectrum.string() },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        requirePicture(energy, 1400, 600);
        CHECK(distinctColours(energy, 150, 80, 450, 400) > 10);
        requirePicture(spectrum, 1200, 700);
        CHECK(distinctColours(spectrum, 200, 100, 800, 500) > 10);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "energy.png", "spectrum.png" });
    }
}

TEST_CASE("plots: --snare-plot writes a PNG of the snare wires", "[renderer]")
{
    TempDir dir;
    const auto wav = dir.out() / "drum.wav";
    const auto snares = dir.out() / "snares.png";

    // The PNG is 1200 x 700; inside the top panel (wires and carry head) and the bottom one
    // (contact count), more than white and grid.
    auto checkImage = [&](int topColours, int bottomColours) {
        requirePicture(snares, 1200, 700);
        CHECK(distinctColours(snares, 130, 70, 750, 300) > topColours);
        CHECK(distinctColours(snares, 130, 490, 750, 120) > bottomColours);
    };

    SECTION("after a strike, with the other outputs")
    {
        const auto energy = dir.out() / "energy.png";
        const auto run = runRenderer(with({ "-o", wav.string(), "--snare-plot", snares.string(), "--energy-plot",
                                            energy.string(), "--json" },
                                          kQuick),
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        REQUIRE(json.isObject());
        CHECK(json["snare_plot"].toString().toStdString() == fs::absolute(snares).string());
        checkImage(50, 5);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "energy.png", "snares.png" });
    }

    SECTION("a render shorter than 25 ms after a late strike, lossless, at 44.1 kHz")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0.012:127", "--seconds", "0.02", "--lossless",
                                       "--sample-rate", "44100", "--snare-plot", snares.string() },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        CHECK(run.out.find("(snare plot)") != std::string::npos);
        checkImage(20, 2);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "snares.png" });
    }

    SECTION("snares thrown off: the carry head alone")
    {
        renderOk(dir, wav, with(kQuick, { "--set", "snares_engaged=0", "--snare-plot", snares.string() }));
        checkImage(10, 1);
    }

    SECTION("no strike inside the render")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0.5:100", "--seconds", "0.01", "--set",
                                       "grid_coarseness=2", "--snare-plot", snares.string(), "--json" },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        CHECK(number(parseJson(run.out), "strikes") == 0.0);
        requirePicture(snares, 1200, 700);
    }
}
