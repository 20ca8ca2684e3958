// snaresim-render --match: bad recordings and options refused (exit 2, one line, no preset
// written), FLAC read as WAV is, the known parameters of a SnareSim strike recovered from a start
// far from them, the written preset file loaded back by --preset, and the whole-strike distance
// printed as --distance measures it.

#include "RendererTestSupport.h"

#include "Match.h"
#include "Parameters.h"
#include "PresetFile.h"

#include <FLAC/stream_encoder.h>
#include <catch2/catch.hpp>
#include <juce_audio_formats/juce_audio_formats.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <thread>

using namespace rendertest;

namespace
{

void writeWav(const fs::path& file, const std::vector<float>& samples, double rate)
{
    juce::WavAudioFormat wav;
    auto stream = std::make_unique<juce::FileOutputStream>(juce::File(file.string()));
    REQUIRE(stream->openedOk());
    std::unique_ptr<juce::AudioFormatWriter> writer(wav.createWriterFor(stream.release(), rate, 1, 24, {}, 0));
    REQUIRE(writer);
    const float* channels[] { samples.data() };
    REQUIRE(writer->writeFromFloatArrays(channels, 1, (int) samples.size()));
}

// 16-bit stereo FLAC (both channels the same) through libFLAC's encoder.
void writeFlac(const fs::path& file, const std::vector<float>& samples, unsigned rate)
{
    auto* encoder = FLAC__stream_encoder_new();
    REQUIRE(encoder);
    FLAC__stream_encoder_set_channels(encoder, 2);
    FLAC__stream_encoder_set_bits_per_sample(encoder, 16);
    FLAC__stream_encoder_set_sample_rate(encoder, rate);
    REQUIRE(FLAC__stream_encoder_init_file(encoder, file.c_str(), nullptr, nullptr) == FLAC__STREAM_ENCODER_INIT_STATUS_OK);
    std::vector<FLAC__int32> interleaved;
    for (const float x : samples)
    {
        const auto v = (FLAC__int32) std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f);
        interleaved.push_back(v);
        interleaved.push_back(v);
    }
    REQUIRE(FLAC__stream_encoder_process_interleaved(encoder, interleaved.data(), (unsigned) samples.size()));
    REQUIRE(FLAC__stream_encoder_finish(encoder));
    FLAC__stream_encoder_delete(encoder);
}

// Two decaying modes and a noisy attack: a strike the features accept.
std::vector<float> syntheticStrike(double rate, double seconds)
{
    std::vector<float> x((std::size_t)(rate * seconds));
    std::uint32_t noise = 1;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        const double t = (double) i / rate;
        noise = noise * 1664525u + 1013904223u;
        const double white = (double) noise / 4294967296.0 - 0.5;
        x[i] = (float) (0.5 * std::exp(-12.0 * t) * std::sin(2.0 * std::numbers::pi * 190.0 * t) +
                        0.3 * std::exp(-20.0 * t) * std::sin(2.0 * std::numbers::pi * 330.0 * t) + 0.4 * std::exp(-40.0 * t) * white);
    }
    return x;
}

fs::path matchInput(const TempDir& dir, const std::string& name, const std::vector<float>& samples, double rate = 48000.0)
{
    const auto file = dir.in() / name;
    writeWav(file, samples, rate);
    return file;
}

double parameterOf(const juce::var& json, const char* key) { return (double) json["parameters"][juce::Identifier(key)]; }

} // namespace

TEST_CASE("match: recordings that are not one strike are refused, no preset written", "[renderer][match][errors]")
{
    TempDir dir;
    const auto preset = (dir.out() / "m.snarepreset").string();
    auto refuse = [&](const fs::path& recording, const std::string& mentions) {
        requireRejected(dir, { "--match", recording.string(), "-o", preset, "--match-budget", "12" }, mentions);
    };

    const auto text = dir.in() / "text.wav";
    std::ofstream(text) << "not a sound file\n";
    refuse(text, "not a WAV, AIFF or FLAC file");
    const auto garbage = dir.in() / "garbage.wav";
    std::ofstream(garbage) << "RIFF\x10\0\0\0WAVEjunkjunk";
    refuse(garbage, "garbage.wav");
    const auto badFlac = dir.in() / "bad.flac";
    std::ofstream(badFlac) << "fLaC and then nothing a decoder wants";
    refuse(badFlac, "bad.flac");
    refuse(dir.in() / "missing.wav", "no such file");

    refuse(matchInput(dir, "silent.wav", std::vector<float>(48000, 0.0f)), "silent");
    auto strike = syntheticStrike(48000.0, 1.0);
    refuse(matchInput(dir, "short.wav", std::vector<float>(strike.begin(), strike.begin() + 2400)), "shorter than 100 ms");
    std::vector<float> steady(48000), swell(48000);
    for (std::size_t i = 0; i < steady.size(); ++i)
    {
        steady[i] = (float) (0.5 * std::sin(2.0 * std::numbers::pi * 440.0 * (double) i / 48000.0));
        swell[i] = (float) std::pow(std::sin(std::numbers::pi * (double) i / 48000.0), 2.0) * steady[i];
    }
    refuse(matchInput(dir, "steady.wav", steady), "no strike");
    refuse(matchInput(dir, "swell.wav", swell), "no strike");
}

TEST_CASE("match: bad options are refused, no preset written", "[renderer][match][errors]")
{
    TempDir dir;
    const auto recording = matchInput(dir, "strike.wav", syntheticStrike(48000.0, 1.0)).string();
    const auto preset = (dir.out() / "m.snarepreset").string();
    auto refuse = [&](std::vector<std::string> more, const std::string& mentions) {
        std::vector<std::string> args { "--match", recording, "-o", preset };
        args.insert(args.end(), more.begin(), more.end());
        requireRejected(dir, args, mentions);
    };
    refuse({ "--match-params", "batter_tension,no_such_param" }, "no_such_param");
    refuse({ "--match-params", "batter_tension,,damping" }, "--match-params");
    refuse({ "--match-params", "damping,damping" }, "twice");
    refuse({ "--match-params", "snares_engaged" }, "snares_engaged");
    refuse({ "--match-params", "output_gain" }, "output_gain");
    refuse({ "--match-budget", "3" }, "--match-budget");
    refuse({ "--hit", "0:100" }, "--hit");
    refuse({ "--set", "air_model=airbox" }, "air box");
    requireRejected(dir, { "--match", recording }, "-o");
    refuse({ "--sample-rate", "44100" }, "--sample-rate");

    // -o naming the recording itself: refused, the recording untouched.
    const auto inOut = matchInput(dir, "self.wav", syntheticStrike(48000.0, 1.0));
    const auto before = readText(inOut);
    requireRejected(dir, { "--match", inOut.string(), "-o", inOut.string(), "--match-budget", "12" }, "the recording itself");
    CHECK(readText(inOut) == before);
    requireRejected(dir, { "-o", preset, "--hit", "0:100", "--match-params", "damping" }, "--match-params");
}

TEST_CASE("match: a FLAC recording reads as the same strike in WAV does", "[renderer][match]")
{
    TempDir dir;
    const auto strike = syntheticStrike(44100.0, 0.8);
    std::vector<float> quantised;
    for (const float x : strike)
        quantised.push_back((float) std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f) / 32768.0f);
    const auto wav = matchInput(dir, "strike.wav", quantised, 44100.0);
    const auto flac = dir.in() / "strike.flac";
    writeFlac(flac, strike, 44100);

    // (JUCE reads 24-bit WAV samples scaled by 1 / (2^23 - 1), libFLAC's by 1 / 2^15: the same
    // strike to float rounding.)
    std::vector<juce::var> features;
    for (const auto& recording : { wav, flac })
    {
        const auto run = runRenderer({ "--match", recording.string(), "-o", (dir.out() / "m.snarepreset").string(), "--match-params",
                                       "damping", "--match-budget", "12", "--json" },
                                     dir.root() / "capture");
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        CHECK((double) json["sample_rate_hz"] == 44100.0);
        features.push_back(json["recording_features"]);
    }
    for (const char* key : { "onset_s", "tail_centroid_hz", "fall_20db_ms", "fall_40db_ms", "lowest_peak_hz" })
    {
        INFO(key);
        CHECK((double) features[0][juce::Identifier(key)] == Approx((double) features[1][juce::Identifier(key)]).epsilon(1e-6));
    }
    CHECK((double) features[0]["band_shares"]["<1k"] == Approx((double) features[1]["band_shares"]["<1k"]).epsilon(1e-6));
}

namespace
{
// The snares are chaotic, so a search's path follows the rounding of the vector path it runs
// on: the two searches below run where every x86-64 processor rounds alike (the golden renders'
// path, docs/VECTOR_TARGETS.md), so their outcome is the one measured, on any machine.
const std::vector<std::string> kOnePath { "SNARESIM_VECTOR_TARGET=baseline", "GLIBC_TUNABLES=" SNARESIM_BASELINE_TUNABLES };
} // namespace

TEST_CASE("match: the membrane and snare tensions of a SnareSim strike recovered from far away", "[renderer][match][slow]")
{
    // Two strikes of the default drum but for the two tensions; each matched from the other end
    // of both ranges. The snares are chaotic: no candidate but the very drum gives a distance of
    // 0, and the tensions come back only as far as the features tell them apart. 150 renders:
    // with 100 the second case ends on the snares' plateau below 30 N (19.7 N, on the avx2 and
    // the baseline paths alike); with 150, 200 and 300 both cases come within 3 % on both paths
    // (on the baseline path, where the test runs: 4199 N/m, 54.9 N and 2205 N/m, 40.1 N).
    struct Case
    {
        double batter, snare;
        const char* startBatter;
        const char* startSnare;
    };
    for (const auto& truth : { Case { 4200.0, 55.0, "1000", "100" }, Case { 2200.0, 40.0, "6000", "10" } })
    {
        TempDir dir;
        const auto recording = (dir.in() / "truth.wav").string();
        const auto made =
            runRenderer({ "-o", recording, "--hit", "0:100", "--seconds", "1", "--set", "batter_tension=" + std::to_string(truth.batter),
                          "--set", "snare_tension=" + std::to_string(truth.snare) },
                        dir.root() / "capture", kOnePath);
        REQUIRE(made.exitCode == 0);

        const auto preset = dir.out() / "match.snarepreset";
        const auto start = std::chrono::steady_clock::now();
        const auto run = runRenderer({ "--match", recording, "-o", preset.string(), "--match-params", "batter_tension,snare_tension",
                                       "--match-budget", "150", "--set", std::string("batter_tension=") + truth.startBatter, "--set",
                                       std::string("snare_tension=") + truth.startSnare, "--json" },
                                     dir.root() / "capture", kOnePath);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        INFO("stderr: " << run.err);
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        const double batter = parameterOf(json, "batter_tension"), snare = parameterOf(json, "snare_tension");
        WARN("truth " << truth.batter << " N/m, " << truth.snare << " N; found " << batter << " N/m, " << snare << " N; distance "
                      << (double) json["distance"] << " in " << (int) json["renders"] << " renders, " << seconds << " s");
        CHECK(std::abs(batter / truth.batter - 1.0) < 0.05);
        CHECK(std::abs(snare / truth.snare - 1.0) < 0.15);
        CHECK((int) json["renders"] <= 150);
        CHECK((double) json["distance"] >= 0.0);

        // The other parameters kept their start values; every ID is reported.
        CHECK(json["parameters"].getDynamicObject()->getProperties().size() == (int) snaresim::kNumParameters);
        CHECK(parameterOf(json, "damping") == snaresim::spec(snaresim::ParamId::damping).defaultValue);

        // The preset file holds the reported values (the JSON's to its 15 digits), and --preset renders from it.
        const auto file = snaresim::readPresetFile(preset);
        const auto params = snaresim::parametersOf(file);
        for (const auto& s : snaresim::parameterSpecs())
        {
            INFO(s.key);
            CHECK(params.get(s.id) == Approx(parameterOf(json, std::string(s.key).c_str())).epsilon(1e-13).margin(1e-300));
        }
        const auto render = runRenderer(
            { "--preset", preset.string(), "--hit", "0:100", "--seconds", "0.2", "-o", (dir.out() / "again.wav").string(), "--json" },
            dir.root() / "capture");
        CHECK(render.exitCode == 0);
        CHECK(entries(dir.out()) == std::vector<std::string> { "again.wav", "match.snarepreset" });
    }
}

TEST_CASE("match: interrupted, it leaves no preset file and an older one intact", "[renderer][match][errors]")
{
    TempDir dir;
    const auto recording = matchInput(dir, "strike.wav", syntheticStrike(48000.0, 1.0)).string();
    const auto target = dir.out() / "m.snarepreset";
    std::ofstream(target) << "name = Older\n";

    const auto capture = dir.root() / "capture";
    const int pid = startRenderer({ "--match", recording, "-o", target.string(), "--match-budget", "100000", "--json" }, capture);
    // Wait until it is searching (its temporary exists beside the old file), then stop it.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (entries(dir.out()).size() < 2 && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    CHECK(entries(dir.out()).size() == 2);
    std::this_thread::sleep_for(std::chrono::milliseconds(300)); // some renders under way
    ::kill(pid, SIGINT);

    const auto run = waitForRenderer(pid, capture);
    INFO("stderr: " << run.err);
    CHECK(run.exitCode == 128 + SIGINT);
    CHECK(lines(run.err).size() == 1);
    CHECK(run.out.empty());
    CHECK(entries(dir.out()) == std::vector<std::string> { "m.snarepreset" });
    CHECK(readText(target) == "name = Older\n");
}

// [slow]: option logic, whose match runs the code of the FLAC and summary tests again (in the
// sanitizer build 100 s).
TEST_CASE("match: the default parameters searched, without the snare ones when the snares are off", "[renderer][match][slow]")
{
    TempDir dir;
    const auto recording = matchInput(dir, "strike.wav", syntheticStrike(48000.0, 1.0)).string();
    for (const bool snaresOff : { false, true })
    {
        std::vector<std::string> args {
            "--match", recording, "-o", (dir.out() / "m.snarepreset").string(), "--match-budget", "12", "--json"
        };
        if (snaresOff)
            args.insert(args.end(), { "--set", "snares_engaged=off" });
        const auto run = runRenderer(args, dir.root() / "capture");
        REQUIRE(run.exitCode == 0);
        const auto json = parseJson(run.out);
        juce::StringArray matched;
        for (const auto& id : *json["matched"].getArray())
            matched.add(id.toString());
        INFO(matched.joinIntoString(","));
        CHECK(matched.size() == (snaresOff ? 13 : 15));
        CHECK(matched.contains("room_time"));
        CHECK(matched.contains("room_volume"));
        CHECK(matched.contains("snare_tension") == ! snaresOff);
        CHECK(matched.contains("snare_count") == ! snaresOff);
        CHECK(matched.contains("velocity"));
        CHECK((int) json["renders"] <= 12);
        CHECK(parameterOf(json, "snares_engaged") == (snaresOff ? 0.0 : 1.0));
    }
}

namespace
{
// The default command with a budget (by default the smallest that starts from the nearest factory
// preset): its JSON.
juce::var matchWithPresetStart(const TempDir& dir, const std::string& recording, const std::string& preset,
                               int budget = snaresim::render::kPresetStartBudget)
{
    const auto run =
        runRenderer({ "--match", recording, "-o", preset, "--match-budget", std::to_string(budget), "--json" }, dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    return parseJson(run.out);
}
} // namespace

TEST_CASE("match: the budget sets how many searches start from the nearest factory presets", "[renderer][match]")
{
    using snaresim::render::presetSearches;
    CHECK(presetSearches(snaresim::render::kPresetStartBudget - 1) == 0); // the defaults, one search
    CHECK(presetSearches(snaresim::render::kPresetStartBudget) == 1);
    CHECK(presetSearches(snaresim::render::kSecondStartBudget - 1) == 1);
    CHECK(presetSearches(snaresim::render::kSecondStartBudget) == 2);
    CHECK(presetSearches(snaresim::render::kDefaultMatchBudget) == 2);
    CHECK(presetSearches(1199) == 2);
    CHECK(presetSearches(1200) == 3);
    CHECK(presetSearches(1600) == 4);
    CHECK(presetSearches(100000) == 250); // capped later by the presets there are
}

TEST_CASE("match: without --preset and --match-params the searches start from the nearest factory presets", "[renderer][match][slow]")
{
    // A strike of Piccolo as the recording: of the factory presets, Piccolo's own strike lies at 0 dB.
    TempDir dir;
    const auto recording = (dir.in() / "piccolo.wav").string();
    REQUIRE(runRenderer({ "-o", recording, "--preset", "Piccolo", "--hit", "0:100", "--seconds", "1" }, dir.root() / "capture").exitCode ==
            0);
    const auto preset = (dir.out() / "m.snarepreset").string();
    // With kSecondStartBudget, two searches: from Piccolo and from the second-nearest preset.
    const auto json = matchWithPresetStart(dir, recording, preset, snaresim::render::kSecondStartBudget);
    REQUIRE(json["start_presets"].size() == 2);
    CHECK(json["start_presets"][0].toString() == "Piccolo");
    CHECK(json["start_presets"][1].toString() != "Piccolo");
    CHECK(json["start_preset"].toString() == "Piccolo"); // the match's
    CHECK((double) json["start_preset_distance_db"] < 0.1);
    CHECK((double) json["strike_distance_db"] < 0.1); // the search keeps the start when nothing beats it
    CHECK((int) json["renders"] <= snaresim::render::kSecondStartBudget);
    CHECK(parameterOf(json, "shell_depth") == Approx(0.076)); // not searched: Piccolo's, not the default 0.14 m

    // With --match-params, or a smaller budget, the search starts from the defaults.
    for (const auto& extra :
         std::vector<std::vector<std::string>> { { "--match-params", "damping", "--match-budget", "60" }, { "--match-budget", "59" } })
    {
        std::vector<std::string> args { "--match", recording, "-o", preset, "--json" };
        args.insert(args.end(), extra.begin(), extra.end());
        const auto other = runRenderer(args, dir.root() / "capture");
        REQUIRE(other.exitCode == 0);
        const auto j = parseJson(other.out);
        CHECK(j["start_preset"].isVoid());
        CHECK(j["start_presets"].size() == 0);
        CHECK(parameterOf(j, "shell_depth") == Approx(0.14));
    }
}

TEST_CASE("match: a strike heard in a room starts from the nearest of a few rooms", "[renderer][match][slow]")
{
    // Piccolo in a room of 350 m^3 with T60 0.3 s (one of the rooms tried) as the recording: the
    // start is Piccolo in that room, 0 dB away; in the free field it would lie dBs away.
    TempDir dir;
    const auto recording = (dir.in() / "room.wav").string();
    REQUIRE(runRenderer({ "-o", recording, "--preset", "Piccolo", "--hit", "0:100", "--seconds", "1", "--set", "room_time=0.3", "--set",
                          "room_volume=350" },
                        dir.root() / "capture")
                .exitCode == 0);
    const auto preset = (dir.out() / "m.snarepreset").string();
    const auto json = matchWithPresetStart(dir, recording, preset);
    CHECK(json["start_preset"].toString() == "Piccolo");
    CHECK(json["start_presets"].size() == 1);               // one search below kSecondStartBudget
    CHECK((double) json["start_preset_distance_db"] > 1.0); // Piccolo in the free field
    CHECK((double) json["strike_distance_db"] < 0.1);
    CHECK(parameterOf(json, "room_time") == Approx(0.3));
    CHECK(parameterOf(json, "room_volume") == Approx(350.0));
    CHECK((int) json["renders"] <= snaresim::render::kPresetStartBudget);

    // The room's parameters not searched: the free field stays.
    const auto without = runRenderer({ "--match", recording, "-o", preset, "--match-budget", "60", "--json", "--preset", "Piccolo",
                                       "--match-params", "damping,velocity" },
                                     dir.root() / "capture");
    REQUIRE(without.exitCode == 0);
    CHECK(parameterOf(parseJson(without.out), "room_time") == 0.0);
}

TEST_CASE("match: the summary, the JSON and the preset file carry the whole-strike distance", "[renderer][match]")
{
    TempDir dir;
    const auto recording = matchInput(dir, "strike.wav", syntheticStrike(48000.0, 1.0)).string();
    const auto preset = dir.out() / "m.snarepreset";
    const std::vector<std::string> args {
        "--match", recording, "-o", preset.string(), "--match-params", "damping", "--match-budget", "12"
    };

    auto withJson = args;
    withJson.push_back("--json");
    const auto run = runRenderer(withJson, dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto json = parseJson(run.out);
    REQUIRE(json.hasProperty("strike_distance_db"));
    const double strike_dB = json["strike_distance_db"];
    CHECK(std::isfinite(strike_dB));
    CHECK(strike_dB > 0.0);
    CHECK(strike_dB < 60.0);
    CHECK((double) json["terms"]["whole"] == Approx(strike_dB / 2.0).epsilon(1e-12)); // the term: dB / 2 dB
    char shown[64];
    std::snprintf(shown, sizeof shown, "whole-strike distance %.2f dB", strike_dB);
    CHECK(lines(readText(preset)).front().find(shown) != std::string::npos);

    const auto text = runRenderer(args, dir.root() / "capture");
    REQUIRE(text.exitCode == 0);
    CHECK(lines(text.out).front().find(shown) != std::string::npos);
    CHECK(text.out.find(" whole ") != std::string::npos); // among the terms
}

TEST_CASE("match: a SnareSim strike matched within 2 dB whole-strike distance, the distance printed as --distance measures it",
          "[renderer][match][slow]")
{
    // A strike of the default drum with four parameters and the velocity changed, matched over
    // them from the defaults with a modest budget: 160 renders come within 1.4 dB on the avx2 and
    // the baseline paths (120 end at 2.05 and 1.85 dB, 200 at 0.94 and 1.58 dB); on the baseline
    // path, where the test runs, at 0.93 dB.
    TempDir dir;
    const auto recording = (dir.in() / "truth.wav").string();
    REQUIRE(runRenderer({ "-o", recording, "--hit", "0:84", "--seconds", "1", "--set", "batter_tension=4200", "--set", "damping=40",
                          "--set", "snare_tension=50", "--set", "strike_position=0.5" },
                        dir.root() / "capture", kOnePath)
                .exitCode == 0);

    const auto preset = dir.out() / "match.snarepreset";
    const auto start = std::chrono::steady_clock::now();
    const auto run = runRenderer({ "--match", recording, "-o", preset.string(), "--match-params",
                                   "batter_tension,damping,snare_tension,strike_position,velocity", "--match-budget", "160", "--json" },
                                 dir.root() / "capture", kOnePath);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto json = parseJson(run.out);
    const double printed_dB = json["strike_distance_db"];
    const int velocity = json["velocity"];
    WARN("whole-strike distance " << printed_dB << " dB at velocity " << velocity << " (distance " << (double) json["distance"] << ") in "
                                  << (int) json["renders"] << " renders, " << seconds << " s");
    CHECK(printed_dB < 2.0);
    CHECK((int) json["renders"] <= 160);

    // The written preset at the reported velocity, rendered and measured by --distance.
    const auto again = dir.out() / "again.wav";
    REQUIRE(runRenderer({ "--preset", preset.string(), "--hit", "0:" + std::to_string(velocity), "--seconds", "1", "-o", again.string() },
                        dir.root() / "capture", kOnePath)
                .exitCode == 0);
    const auto measured = runRenderer({ "--distance", again.string(), "--ref", dir.in().string() + ":truth.wav", "--json" },
                                      dir.root() / "capture", kOnePath);
    INFO("stderr: " << measured.err);
    REQUIRE(measured.exitCode == 0);
    const double measured_dB = parseJson(measured.out)["strikes"][0]["distance_db"];
    CHECK(printed_dB == Approx(measured_dB).margin(0.1));
}

TEST_CASE("match: the same command writes the same preset file, another seed searches elsewhere", "[renderer][match][slow]")
{
    TempDir dir;
    // A SnareSim strike far from the start (damping 95 % against the default 44 %): any seed
    // finds better points than the start, so two seeds end on different ones. From a target the
    // start already suits best, both would keep the start and write the same file.
    const auto recording = (dir.in() / "strike.wav").string();
    REQUIRE(runRenderer({ "-o", recording, "--hit", "0:100", "--seconds", "1", "--set", "damping=95", "--set", "batter_tension=3000" },
                        dir.root() / "capture")
                .exitCode == 0);
    auto presetWith = [&](const std::vector<std::string>& more) {
        std::vector<std::string> args { "--match",
                                        recording,
                                        "-o",
                                        (dir.out() / "m.snarepreset").string(),
                                        "--match-budget",
                                        "16",
                                        "--match-params",
                                        "batter_tension,damping,snare_tension" };
        args.insert(args.end(), more.begin(), more.end());
        REQUIRE(runRenderer(args, dir.root() / "capture").exitCode == 0);
        return readText(dir.out() / "m.snarepreset");
    };
    const auto first = presetWith({});
    CHECK(presetWith({}) == first);
    CHECK(presetWith({ "--match-seed", "20240611" }) == first); // the default
    CHECK(presetWith({ "--match-seed", "7" }) != first);
}
