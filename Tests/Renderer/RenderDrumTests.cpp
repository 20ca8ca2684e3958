// snaresim-render and the whole drum: --model (the air cavity), --mic (the microphones),
// the snare controls through --set, and the PNG outputs (--energy-plot, --spectrogram,
// --snare-plot).
// Renders are short (0.3 s) and coarse (the default Quality, bandwidth 7.84 kHz) where detail does not matter.

#include "RendererTestSupport.h"

#include "PresetFile.h"
#include "Presets.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "EnergyPlot.h"
#include "SnarePlot.h"
#include "Spectrogram.h"

#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>

using namespace rendertest;

namespace
{

const std::vector<std::string> kQuick { "--hit", "0:100", "--seconds", "0.3", "--set", "bandwidth=7839.5127" };

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more)
{
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// Runs a render that must succeed with a WAV of 0.3 s at 48 kHz and `channels` finite
// channels; returns them.
std::vector<std::vector<float>> renderOk(const TempDir& dir, const fs::path& wav, const std::vector<std::string>& args, int channels = 1)
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

// The rows of a CSV of numbers, header left out.
std::vector<std::vector<double>> csvRows(const fs::path& file)
{
    std::vector<std::vector<double>> rows;
    const auto text = lines(readText(file));
    for (std::size_t i = 1; i < text.size(); ++i)
    {
        std::vector<double> fields;
        const char* p = text[i].data();
        const char* end = p + text[i].size();
        bool parsed = true;
        while (p < end && parsed)
        {
            double v = 0.0;
            const auto [next, ec] = std::from_chars(p, end, v);
            parsed = ec == std::errc {};
            fields.push_back(v);
            p = next + 1; // skip the comma
        }
        INFO("row " << i << ": " << text[i]);
        REQUIRE(parsed);
        rows.push_back(std::move(fields));
    }
    return rows;
}

// The topmost (or bottommost) pixel of a plot area's inside (its frame left out) whose colour
// passes `is`; the leftmost of its row. None when no pixel does.
std::optional<juce::Point<int>> extremePixel(const juce::Image& image, juce::Rectangle<float> area,
                                             const std::function<bool(juce::Colour)>& is, bool topmost)
{
    const auto inside = area.toNearestInt().reduced(1);
    for (int i = 0; i < inside.getHeight(); ++i)
    {
        const int y = topmost ? inside.getY() + i : inside.getBottom() - 1 - i;
        for (int x = inside.getX(); x < inside.getRight(); ++x)
            if (is(image.getPixelAt(x, y)))
                return juce::Point<int>(x, y);
    }
    return std::nullopt;
}

// The rightmost pixel of row y of a plot area's inside whose colour passes `is` (-1: none).
int rightmostInRow(const juce::Image& image, juce::Rectangle<float> area, int y, const std::function<bool(juce::Colour)>& is)
{
    const auto inside = area.toNearestInt().reduced(1);
    for (int x = inside.getRight() - 1; x >= inside.getX(); --x)
        if (is(image.getPixelAt(x, y)))
            return x;
    return -1;
}

// A curve pixel, at half coverage or more, of the energy plot's balance curve (0xff1f4e9c) or
// of the snare plot's contact count (0xff08519c over its light blue fill 0xffc6dbef): blue well
// above red, unlike the grey frame, grid and text.
bool isBlueCurve(juce::Colour c) { return c.getRed() < 128 && c.getBlue() >= c.getRed() + 60; }

// A pixel of the energy plot's total (black, 2.2 px wide), at its full width: dark and grey.
bool isBlack(juce::Colour c)
{
    return c.getRed() < 90 && std::abs(c.getRed() - c.getGreen()) < 15 && std::abs(c.getGreen() - c.getBlue()) < 15;
}

// The curves' pixels lie within this of the pixel position of the point they draw: half the
// widest stroke (2.2 px), plus a pixel of anti-aliasing, plus a little for a mitered corner.
constexpr double kCurveTolerance_px = 2.0;

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
    const auto overridden = renderOk(dir, dir.out() / "overridden.wav", with(kQuick, { "--model", "none", "--set", "air_model=cavity" }));
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

    const auto offRun =
        runRenderer(with({ "-o", (dir.out() / "off.wav").string(), "--json", "--set", "snares_engaged=0" }, kQuick), capture);
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
    // Snares on: the wires press into the carry head, by far less than one of its grid cells
    // (the default drum at the default Quality).
    snaresim::ParameterSet params;
    params.set(snaresim::ParamId::bandwidth, 7839.5127);
    const snaresim::Drum drum(snaresim::makeDrumConfig(params, 48000.0));
    CHECK(number(onJson, "snare_max_penetration_m") > 0.0);
    CHECK(number(onJson, "snare_max_penetration_m") < 0.01 * drum.carry().grid().spacing());

    // The other snare controls reach the engine too.
    renderOk(dir, dir.out() / "controls.wav",
             with(kQuick,
                  { "--set", "snare_tension=50", "--set", "snare_count=12", "--set", "carry_tension=2500", "--set", "shell_depth=0.1" }));
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
        // The heads in double precision: the balance is then a curve at double round-off, not
        // float round-off's random walk. Light damping (25 %, high damping 4e-4 m^2/s, 20 N
        // wires): the total's plateau then ends on a slope the pixels resolve. Grids of 12 kHz,
        // simulated at the host's 48 kHz: a row a step.
        const auto run = runRenderer(with({ "-o",
                                            wav.string(),
                                            "--mic",
                                            "all",
                                            "--energy-plot",
                                            energy.string(),
                                            "--spectrogram",
                                            spectrum.string(),
                                            "--energy-csv",
                                            csv.string(),
                                            "--json",
                                            "--set",
                                            "head_precision=double",
                                            "--set",
                                            "damping=25",
                                            "--set",
                                            "high_damping=4e-4",
                                            "--set",
                                            "snare_tension=20",
                                            "--hit",
                                            "0:100",
                                            "--seconds",
                                            "0.3",
                                            "--set",
                                            "bandwidth=12000" },
                                          {}),
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

        // The plotted curves against the ledger that drew them (the CSV holds the same rows).
        const auto rows = csvRows(csv);
        REQUIRE(rows.size() == 14400);
        const auto columns = energyColumns(lines(readText(csv)).front());
        const auto image = loadImage(energy);
        REQUIRE(image.isValid());
        const double rate = 48000.0, durationMs = 300.0;
        auto xOf = [&](juce::Rectangle<float> area, double ms) { return area.getX() + ms / durationMs * area.getWidth(); };

        // Left panel: (h^n - h^0) / h^0 of the balance, h^0 the total of the strike's first row
        // (the strike is at sample 0). Its highest and lowest points lie where the axis range
        // puts them: 8 % of the span inside the top and the bottom. The pixels are compared
        // from the third column in (the first lie on the frame), with the extremes of the rows
        // drawn there.
        const double h0 = rows.front()[columns.total], balance0 = rows.front()[columns.balance];
        REQUIRE(h0 > 0.0);
        const auto balanceArea = snaresim::render::EnergyPlot::balanceArea();
        const float edge_px = 3.0f;
        const auto inner = balanceArea.withTrimmedLeft(edge_px);
        const auto firstInner = (std::size_t) std::ceil((edge_px + 1.0) / balanceArea.getWidth() * durationMs / 1000.0 * rate);
        double lo = 0.0, hi = 0.0, innerLo = 1.0e300, innerHi = -1.0e300;
        std::size_t loAt = 0, hiAt = 0;
        for (std::size_t n = 0; n < rows.size(); ++n)
        {
            const double v = (rows[n][columns.balance] - balance0) / h0;
            if (v < lo)
                lo = v, loAt = n;
            if (v > hi)
                hi = v, hiAt = n;
            if (n >= firstInner)
                innerLo = std::min(innerLo, v), innerHi = std::max(innerHi, v);
        }
        const auto axisRange = snaresim::render::EnergyPlot::balanceRange(lo, hi);
        const double axisLo = axisRange.first, axisHi = axisRange.second; // (no structured binding: a lambda captures them)
        CHECK(axisLo == Approx(lo - 0.08 * (hi - lo)).epsilon(1e-12));
        CHECK(axisHi == Approx(hi + 0.08 * (hi - lo)).epsilon(1e-12));
        auto yOfBalance = [&](double v) { return balanceArea.getBottom() - (v - axisLo) / (axisHi - axisLo) * balanceArea.getHeight(); };
        const auto top = extremePixel(image, inner, isBlueCurve, true);
        const auto bottom = extremePixel(image, inner, isBlueCurve, false);
        REQUIRE(top.has_value());
        REQUIRE(bottom.has_value());
        INFO("balance from " << lo << " (sample " << loAt << ") to " << hi << " (sample " << hiAt << "), from sample " << firstInner << " "
                             << innerLo << " to " << innerHi << "; curve there from pixel " << top->toString() << " to "
                             << bottom->toString() << ", expected y " << yOfBalance(innerHi) << " and " << yOfBalance(innerLo));
        CHECK(std::abs(top->y + 0.5 - yOfBalance(innerHi)) <= kCurveTolerance_px);
        CHECK(std::abs(bottom->y + 0.5 - yOfBalance(innerLo)) <= kCurveTolerance_px);
        // Where they are drawn: the columns around the extreme pixels hold samples that reach
        // the extremes' heights (at round-off the curve may touch its extreme more than once).
        // Only the rows the extremes are taken from count: near the panel's left edge the
        // columns also hold earlier rows, which may lie beyond the inner extremes.
        auto reachedNear = [&](float x, bool highest) {
            const double first = (x - kCurveTolerance_px - balanceArea.getX()) / balanceArea.getWidth() * durationMs / 1000.0 * rate;
            const double last = (x + 1.0 + kCurveTolerance_px - balanceArea.getX()) / balanceArea.getWidth() * durationMs / 1000.0 * rate;
            double reached = highest ? lo : hi;
            for (std::size_t n = std::max(firstInner, (std::size_t) std::max(0.0, first)); n < std::min((double) rows.size(), last); ++n)
            {
                const double v = (rows[n][columns.balance] - balance0) / h0;
                reached = highest ? std::max(reached, v) : std::min(reached, v);
            }
            return reached;
        };
        CHECK(std::abs(yOfBalance(reachedNear(top->x, true)) - yOfBalance(innerHi)) <= kCurveTolerance_px);
        CHECK(std::abs(yOfBalance(reachedNear(bottom->x, false)) - yOfBalance(innerLo)) <= kCurveTolerance_px);

        // Right panel, logarithmic: the total starts at the strike's energy, (1/2) M v^2 with v
        // the velocity curve's speed for velocity 100, and stays there (a flat top from the
        // left edge) until the player takes the mallet back; the axis ends at the decade above.
        const auto params = snaresim::ParameterSet {};
        const double v = snaresim::strikeSpeedFromVelocity(100, params.get(snaresim::ParamId::strikeSpeedMax));
        const double strikeEnergy = 0.5 * params.get(snaresim::ParamId::malletMass) * v * v;
        CHECK(h0 == Approx(strikeEnergy).epsilon(1e-5)); // less the first step's losses
        double largest = 0.0;                            // over the ledger's terms and the total, as the panel plots them
        for (const auto& row : rows)
        {
            for (const auto c : columns.terms)
                largest = std::max(largest, row[c]);
            largest = std::max(largest, row[columns.total]);
        }
        CHECK(largest == h0);
        const double axisTop = snaresim::render::EnergyPlot::componentTop(largest);
        CHECK(axisTop == 1.0);
        const double axisBottom = axisTop * std::pow(10.0, -snaresim::render::EnergyPlot::componentDecades);
        const auto componentArea = snaresim::render::EnergyPlot::componentArea();
        const double yTotal = componentArea.getBottom() -
                              std::log10(strikeEnergy / axisBottom) / std::log10(axisTop / axisBottom) * componentArea.getHeight();
        std::size_t kept = 0; // the last row the total holds the strike's energy (within 1 %)
        while (kept + 1 < rows.size() && rows[kept + 1][columns.total] > 0.99 * h0)
            ++kept;
        const auto totalTop = extremePixel(image, componentArea, isBlack, true);
        REQUIRE(totalTop.has_value());
        const int plateauEnd = rightmostInRow(image, componentArea, totalTop->y, isBlack);
        INFO("total: top at pixel " << totalTop->toString() << " to x = " << plateauEnd << ", expected y " << yTotal
                                    << " from the left edge to about x = " << xOf(componentArea, kept / rate * 1000.0));
        CHECK(std::abs(totalTop->y + 0.5 - yTotal) <= kCurveTolerance_px);
        CHECK(totalTop->x <= componentArea.getX() + 2.0f);
        // The plot keeps one point per pixel column (its largest value), 0.68 ms each here.
        CHECK(std::abs(plateauEnd + 0.5 - xOf(componentArea, kept / rate * 1000.0)) <= kCurveTolerance_px + 1.0);
    }

    SECTION("a render shorter than one analysis window, lossless")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0:127", "--seconds", "0.02", "--lossless", "--energy-plot",
                                       energy.string(), "--spectrogram", spectrum.string() },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        requirePicture(energy, 1400, 600);
        CHECK(distinctColours(energy, 150, 80, 450, 400) > 10);
        requirePicture(spectrum, 1200, 700);
        CHECK(distinctColours(spectrum, 200, 100, 800, 500) > 10);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "energy.png", "spectrum.png" });

        // Lossless: the total stays at the strike's energy, (1/2) M v^2 at velocity 127, from
        // the left edge on; the logarithmic axis ends at the decade above it (1 J).
        const auto params = snaresim::ParameterSet {};
        const double v = snaresim::strikeSpeedFromVelocity(127, params.get(snaresim::ParamId::strikeSpeedMax));
        const double strikeEnergy = 0.5 * params.get(snaresim::ParamId::malletMass) * v * v;
        const double axisTop = snaresim::render::EnergyPlot::componentTop(strikeEnergy);
        CHECK(axisTop == 1.0);
        const double decades = snaresim::render::EnergyPlot::componentDecades;
        const auto area = snaresim::render::EnergyPlot::componentArea();
        const double yTotal = area.getBottom() - (std::log10(strikeEnergy / axisTop) + decades) / decades * area.getHeight();
        const auto image = loadImage(energy);
        REQUIRE(image.isValid());
        const auto totalTop = extremePixel(image, area, isBlack, true);
        REQUIRE(totalTop.has_value());
        INFO("total: top at pixel " << totalTop->toString() << ", expected y " << yTotal);
        CHECK(std::abs(totalTop->y + 0.5 - yTotal) <= kCurveTolerance_px);
        CHECK(totalTop->x <= area.getX() + 2.0f);
    }
}

TEST_CASE("plots: the spectrogram's first frames are brightest at the batter's (0,1) mode", "[renderer]")
{
    // A centre strike heard at the batter's centre, with no air (no cavity, no outside air) and no snares: the batter's
    // axisymmetric modes alone, of which the lowest, (0,1) at f01 = 2.4048 c / (2 pi R), is by
    // far the loudest (the strike lasts about a period of it).
    TempDir dir;
    const auto png = dir.out() / "spectrum.png";
    renderOk(dir, dir.out() / "top.wav",
             with(kQuick, { "--mic", "top", "--set", "strike_position=0", "--set", "mic_top_position=0", "--model", "none", "--set",
                            "outside_air=off", "--set", "snares_engaged=0", "--spectrogram", png.string() }));
    requirePicture(png, 1200, 700);
    const auto image = loadImage(png);
    REQUIRE(image.isValid());

    const auto batter = snaresim::makeDrumConfig(snaresim::ParameterSet {}, 48000.0).batter;
    const double f01 =
        2.404825557695773 * std::sqrt(batter.tension_N_per_m / batter.density_kg_per_m2) / (2.0 * std::numbers::pi * batter.radius_m);
    // The axis (Spectrogram.h): rows of equal steps of log frequency from 40 Hz to Nyquist,
    // row 0 at the bottom of the area.
    const double rate = 48000.0, samples = 14400.0;
    const auto area = snaresim::render::Spectrogram::plotArea();
    const int rows = area.getHeight();
    auto rowOf = [&](double f) { return (int) std::floor(rows * std::log(f / 40.0) / std::log(rate / 2.0 / 40.0)); };
    CHECK(snaresim::render::Spectrogram::rowEdge_Hz(0, rate) == Approx(40.0));
    CHECK(snaresim::render::Spectrogram::rowEdge_Hz(rows, rate) == Approx(rate / 2.0));
    CHECK(snaresim::render::Spectrogram::rowEdge_Hz(rowOf(f01), rate) <= f01);
    CHECK(snaresim::render::Spectrogram::rowEdge_Hz(rowOf(f01) + 1, rate) > f01);
    // A frame's loudest bin is one of the two around f01: within a bin (rate / 2048) of it.
    const double bin = rate / 2048.0;
    const int lowest = rowOf(f01 - bin), highest = rowOf(f01 + bin);

    // The first four frames (Hann 2048, hop 512), each in the pixel column holding its centre.
    // The colour map grows lighter with level, so a column's lightest pixel is its loudest row.
    for (int frame = 0; frame < 4; ++frame)
    {
        const int column = (int) std::floor((1024.0 + 512.0 * frame) / samples * area.getWidth());
        const int x = area.getX() + column;
        int brightest = 0;
        float lightest = -1.0f;
        for (int r = 0; r < rows; ++r)
        {
            const float light = image.getPixelAt(x, area.getBottom() - 1 - r).getPerceivedBrightness();
            if (light > lightest)
                lightest = light, brightest = r;
        }
        INFO("frame " << frame << " (pixel column " << x << "): brightest row " << brightest << " ("
                      << snaresim::render::Spectrogram::rowEdge_Hz(brightest, rate) << " Hz); f01 = " << f01 << " Hz at row " << rowOf(f01)
                      << ", rows " << lowest << " to " << highest << " within a bin of it");
        CHECK(brightest >= lowest);
        CHECK(brightest <= highest);
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
        const auto run =
            runRenderer(with({ "-o", wav.string(), "--snare-plot", snares.string(), "--energy-plot", energy.string(), "--json" }, kQuick),
                        dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        REQUIRE(json.isObject());
        CHECK(json["snare_plot"].toString().toStdString() == fs::absolute(snares).string());
        checkImage(50, 5);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "energy.png", "snares.png" });

        // The contact count against the data that drew it: the same drum played in-process
        // (the renderer's default drum at the default Quality, velocity 100 at sample 0); the
        // count at time n + 1 is the step of sample n's (SnarePlot.h).
        snaresim::ParameterSet params;
        params.set(snaresim::ParamId::bandwidth, 7839.5127);
        const auto config = snaresim::makeDrumConfig(params, 48000.0);
        snaresim::Drum drum(config);
        const int points = drum.snareContact().numPoints();
        CHECK(points == config.snares.count * (drum.snareWires().intervals() - 1)); // every interior node
        drum.strikeAtDefaultPoint(snaresim::strikeSpeedFromVelocity(100, config.strikeSpeedMax_m_per_s));
        const int window = 1200;         // 25 ms
        std::vector<int> contacts { 0 }; // time 0, before the first step
        for (int n = 0; n < window; ++n)
        {
            drum.step();
            contacts.push_back(drum.solverStats().snareContacts);
        }
        // Right after the strike the carry head pulls the wires down with it: every point
        // touches, the count reaches the top of its data (first at time `first`, until `last`).
        const auto most = std::max_element(contacts.begin(), contacts.end());
        CHECK(*most == points);
        const auto first = most - contacts.begin();
        auto last = first;
        while (last + 1 < (std::ptrdiff_t) contacts.size() && contacts[(std::size_t) last + 1] == *most)
            ++last;

        const auto image = loadImage(snares);
        REQUIRE(image.isValid());
        const auto area = snaresim::render::SnarePlot::contactArea();
        const double axisTop = snaresim::render::SnarePlot::contactAxisTop(points);
        CHECK(axisTop == Approx(1.08 * points));
        const double yMost = area.getBottom() - *most / axisTop * area.getHeight();
        auto xOf = [&](double time) { return area.getX() + time / window * area.getWidth(); }; // 25 ms wide
        const auto top = extremePixel(image, area, isBlueCurve, true);
        REQUIRE(top.has_value());
        const int end = rightmostInRow(image, area, top->y, isBlueCurve);
        INFO(*most << " of " << points << " points touch from time " << first << " to " << last << "; the count's top at pixel "
                   << top->toString() << " to x = " << end << ", expected y " << yMost << " from x " << xOf((double) first) << " to "
                   << xOf((double) last + 1));
        CHECK(std::abs(top->y + 0.5 - yMost) <= kCurveTolerance_px);
        CHECK(std::abs(top->x + 0.5 - std::max(xOf((double) first), area.getX() + 1.0)) <= kCurveTolerance_px);
        // A step curve: the count holds until the next state.
        CHECK(std::abs(end + 0.5 - xOf((double) last + 1)) <= kCurveTolerance_px);
    }

    SECTION("a render shorter than 25 ms after a late strike, lossless, at 44.1 kHz")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0.012:127", "--seconds", "0.02", "--lossless", "--sample-rate",
                                       "44100", "--snare-plot", snares.string() },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        CHECK(run.out.find("(snare plot)") != std::string::npos);
        checkImage(20, 2);
        CHECK(entries(dir.out()) == std::vector<std::string> { "drum.wav", "snares.png" });
    }

    // No wire point touches: the count's line lies on the axis's 0, the panel's bottom edge
    // (which the frame covers), so no curve pixel shows above it.
    auto checkNoContact = [&] {
        const auto image = loadImage(snares);
        REQUIRE(image.isValid());
        const auto area = snaresim::render::SnarePlot::contactArea();
        const auto top = extremePixel(image, area, isBlueCurve, true);
        INFO("contact count's highest pixel: " << (top ? top->toString() : juce::String("none")));
        CHECK((! top.has_value() || top->y + 0.5 >= area.getBottom() - kCurveTolerance_px));
    };

    SECTION("snares thrown off: the carry head alone")
    {
        renderOk(dir, wav, with(kQuick, { "--set", "snares_engaged=0", "--snare-plot", snares.string() }));
        checkImage(10, 1);
        checkNoContact();
    }

    SECTION("no strike inside the render")
    {
        const auto run = runRenderer({ "-o", wav.string(), "--hit", "0.5:100", "--seconds", "0.01", "--set", "bandwidth=7839.5127",
                                       "--snare-plot", snares.string(), "--json" },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        CHECK(number(parseJson(run.out), "strikes") == 0.0);
        requirePicture(snares, 1200, 700);
        checkNoContact();
        // Nothing moves: the carry head's line runs flat along the middle of the top panel (a
        // range of +-0.001 mm around 0 when the data do not spread).
        const auto image = loadImage(snares);
        const auto area = snaresim::render::SnarePlot::wireArea();
        const auto top = extremePixel(image, area, isBlueCurve, true);
        const auto bottom = extremePixel(image, area, isBlueCurve, false);
        REQUIRE(top.has_value());
        REQUIRE(bottom.has_value());
        INFO("carry head's line from row " << top->y << " to " << bottom->y << ", the middle at " << area.getCentreY());
        CHECK(std::abs(top->y + 0.5 - area.getCentreY()) <= kCurveTolerance_px);
        CHECK(std::abs(bottom->y + 0.5 - area.getCentreY()) <= kCurveTolerance_px);
        CHECK(top->x <= area.getX() + 2.0f);
        CHECK(rightmostInRow(image, area, top->y, isBlueCurve) >= area.getRight() - 3.0f);
    }
}

TEST_CASE("presets: --preset FILE plays as the factory preset its file copies, and --set applies after it", "[renderer]")
{
    TempDir dir;
    fs::create_directories(dir.in());
    const auto file = dir.in() / "funk copy.snarepreset";
    {
        snaresim::ParameterSet funk;
        REQUIRE(snaresim::applyPreset("Tight Funk", funk));
        std::ofstream(file) << snaresim::formatPresetFile("Funk copy", funk);
    }
    renderOk(dir, dir.out() / "named.wav", with(kQuick, { "--preset", "Tight Funk" }));
    renderOk(dir, dir.out() / "file.wav", with(kQuick, { "--preset", file.string() }));
    renderOk(dir, dir.out() / "default.wav", kQuick);
    const auto named = readWav(dir.out() / "named.wav");
    const auto fromFile = readWav(dir.out() / "file.wav");
    const auto defaults = readWav(dir.out() / "default.wav");
    REQUIRE(named.opened);
    REQUIRE(fromFile.opened);
    REQUIRE(defaults.opened);
    CHECK(named.samples == fromFile.samples);
    CHECK(clearlyDifferent(named.samples, defaults.samples));

    // --set still applies after the file
    renderOk(dir, dir.out() / "file-set.wav", with(kQuick, { "--preset", file.string(), "--set", "batter_tension=3050" }));
    CHECK(clearlyDifferent(readWav(dir.out() / "file-set.wav").samples, named.samples));
}
