// The whole-strike distance (Source/Renderer/StrikeFingerprint.h) and snaresim-render's
// --distance / --ref: the figures of the reference implementation on the recorded snare drums of
// Debian's hydrogen-drumkits (when installed), synthetic strikes whose fingerprints are known,
// and bad input through the built renderer (exit 2, one line, nothing written).
//
// The pinned figures were computed by the reference (strike_distance.py, numpy) on the same
// files; the C++ agrees with it to about 1e-13 dB, the tests hold it to 0.1 dB.

#include "RendererTestSupport.h"

#include "AudioFileReader.h"
#include "StrikeFeatures.h"
#include "StrikeFingerprint.h"

#include <catch2/catch.hpp>
#include <juce_audio_formats/juce_audio_formats.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <numbers>
#include <random>

using namespace rendertest;
using snaresim::render::StrikeFingerprint;

namespace
{

const fs::path kKits = "/usr/share/hydrogen/data/drumkits";
constexpr double kAgreement_dB = 0.1;

// A mix of decaying sines (Hz, amplitude) and a decaying noise burst, after delay_s of silence.
std::vector<double> strike(double rate, double seconds, const std::vector<std::pair<double, double>>& sines, double dbPerSecond,
                           double delay_s = 0.0, double noise = 0.0)
{
    const double a = dbPerSecond / (20.0 * std::log10(std::numbers::e));
    std::vector<double> x((std::size_t)(seconds * rate), 0.0);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> gauss;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        const double t = (double) i / rate - delay_s;
        if (t < 0.0)
            continue;
        for (const auto& [f, amplitude] : sines)
            x[i] += amplitude * std::exp(-a * t) * std::sin(2.0 * std::numbers::pi * f * t);
        if (noise > 0.0)
            x[i] += noise * std::exp(-4.0 * a * t) * gauss(rng);
    }
    return x;
}

StrikeFingerprint fingerprintOf(const std::vector<double>& x, double rate) { return snaresim::render::strikeFingerprint(x, rate); }

StrikeFingerprint fingerprintOf(const fs::path& file)
{
    const auto audio = snaresim::render::readMonoAudio(file);
    return snaresim::render::strikeFingerprint(audio.samples, audio.sampleRate_Hz);
}

double distance(const StrikeFingerprint& a, const StrikeFingerprint& b) { return snaresim::render::strikeDistance_dB(a, b); }

// 24-bit WAV or AIFF through JUCE's writers, a channel per signal.
void writeAudio(const fs::path& file, const std::vector<std::vector<double>>& channels, double rate)
{
    std::unique_ptr<juce::AudioFormat> format;
    if (file.extension() == ".aiff")
        format = std::make_unique<juce::AiffAudioFormat>();
    else
        format = std::make_unique<juce::WavAudioFormat>();
    auto stream = std::make_unique<juce::FileOutputStream>(juce::File(file.string()));
    REQUIRE(stream->openedOk());
    std::unique_ptr<juce::AudioFormatWriter> writer(format->createWriterFor(stream.release(), rate, (unsigned) channels.size(), 24, {}, 0));
    REQUIRE(writer);
    std::vector<std::vector<float>> floats;
    std::vector<const float*> pointers;
    for (const auto& channel : channels)
        floats.emplace_back(channel.begin(), channel.end());
    for (const auto& channel : floats)
        pointers.push_back(channel.data());
    REQUIRE(writer->writeFromFloatArrays(pointers.data(), (int) pointers.size(), (int) floats.front().size()));
}

fs::path writeStrike(const TempDir& dir, const std::string& name, const std::vector<double>& x, double rate = 48000.0)
{
    const auto file = dir.in() / name;
    writeAudio(file, { x }, rate);
    return file;
}

// A snare-like strike: two modes, a bright noisy attack (below full scale: the files do not clip).
std::vector<double> snareLike(double rate, double f1 = 190.0, double f2 = 330.0)
{
    return strike(rate, 0.8, { { f1, 0.25 }, { f2, 0.15 } }, 40.0, 0.02, 0.08);
}

bool kitsInstalled()
{
    for (const auto* kit : { "ForzeeStereo", "ColomboAcousticDrumkit", "BJA_Pacific", "Millo-Drums_v.1" })
        if (! fs::is_directory(kKits / kit))
            return false;
    return true;
}

} // namespace

TEST_CASE("strike distance: the reference's figures on the recorded snare drums", "[renderer][distance]")
{
    if (! kitsInstalled())
    {
        WARN("hydrogen-drumkits is not installed (" << kKits << "): skipped");
        return;
    }

    // strike_distance.py's distance of each pair, dB.
    const struct
    {
        const char* a;
        const char* b;
        double distance_dB;
    } pairs[] {
        { "ForzeeStereo/Snare-0.wav", "ForzeeStereo/Snare-1.wav", 2.8126 },
        { "ForzeeStereo/Snare-2.wav", "ForzeeStereo/SnareOff-2.wav", 12.3510 },
        { "ColomboAcousticDrumkit/snare-opaque-normal-mic-normal_shot2.flac",
          "ColomboAcousticDrumkit/snare-opaque-normal-mic-normal_shot3.flac", 2.8880 },
        { "ColomboAcousticDrumkit/snare-opaque-2mics_normal-shot1.flac", "ColomboAcousticDrumkit/snare-opaque-normal-mic-rimshot6.flac",
          8.4093 },
        { "BJA_Pacific/SN_01.aiff", "BJA_Pacific/SN3_04.aiff", 9.3650 },
        { "BJA_Pacific/SN3_04.aiff", "ColomboAcousticDrumkit/snare-opaque-normal-mic-normal_shot2.flac", 4.9584 },
        { "BJA_Pacific/SN3_03.aiff", "BJA_Pacific/SN_05.aiff", 10.9371 },
        { "Millo-Drums_v.1/snare1.flac", "Millo-Drums_v.1/snare3.flac", 2.5215 },
        { "Millo-Drums_v.1/snare3.flac", "ColomboAcousticDrumkit/snare-opaque-normal-mic-normal_shot3.flac", 6.1035 },
        { "ForzeeStereo/Snare-0.wav", "BJA_Pacific/SN_06.aiff", 9.6554 },
        { "ForzeeStereo/SnareOff-4.wav", "ColomboAcousticDrumkit/snare-opaque-2mics_normal-shot1.flac", 17.2282 },
        { "ForzeeStereo/SnareOff-0.wav", "Millo-Drums_v.1/snare1.flac", 22.6141 },
    };
    for (const auto& pair : pairs)
    {
        INFO(pair.a << " to " << pair.b);
        CHECK(distance(fingerprintOf(kKits / pair.a), fingerprintOf(kKits / pair.b)) == Approx(pair.distance_dB).margin(kAgreement_dB));
    }

    // A few cells of the fingerprints: 0-30 ms at 1 kHz, 30-100 ms at 2 kHz, 100-300 ms at 315 Hz
    // and at 16 kHz (Forzee's at the floor).
    const struct
    {
        const char* file;
        std::array<double, 4> level_dB;
    } cells[] {
        { "ForzeeStereo/Snare-0.wav", { -14.4990, -27.5317, -42.3012, -60.0000 } },
        { "ColomboAcousticDrumkit/snare-opaque-normal-mic-normal_shot2.flac", { -25.0757, -29.1981, -23.4451, -57.4337 } },
        { "BJA_Pacific/SN3_04.aiff", { -26.2427, -28.8840, -30.3789, -48.7626 } },
        { "Millo-Drums_v.1/snare1.flac", { -28.2941, -21.0603, -19.7411, -53.0850 } },
    };
    for (const auto& [file, level_dB] : cells)
    {
        INFO(file);
        const auto f = fingerprintOf(kKits / file);
        CHECK(f.at(0, 10) == Approx(level_dB[0]).margin(kAgreement_dB));
        CHECK(f.at(1, 13) == Approx(level_dB[1]).margin(kAgreement_dB));
        CHECK(f.at(2, 5) == Approx(level_dB[2]).margin(kAgreement_dB));
        CHECK(f.at(2, 22) == Approx(level_dB[3]).margin(kAgreement_dB));
    }
}

TEST_CASE("strike distance: --distance names the nearest recording with the reference's figures", "[renderer][distance]")
{
    if (! kitsInstalled())
    {
        WARN("hydrogen-drumkits is not installed (" << kKits << "): skipped");
        return;
    }
    TempDir dir;
    const auto run = runRenderer({ "--distance", (kKits / "Millo-Drums_v.1/snare1.flac").string(), "--ref",
                                   (kKits / "ForzeeStereo").string() + ":Snare-*.wav", "--ref",
                                   (kKits / "BJA_Pacific").string() + ":SN3_*.aiff", "--json" },
                                 dir.root() / "capture");
    INFO(run.err);
    REQUIRE(run.exitCode == 0);
    const auto json = parseJson(run.out);
    REQUIRE(json["references"].size() == 9); // Snare-0..4, SN3_01..04
    CHECK(json["references"][0]["kit"].toString() == "ForzeeStereo");
    CHECK(json["references"][5]["kit"].toString() == "BJA_Pacific");
    const auto& strikeJson = json["strikes"][0];
    CHECK(strikeJson["nearest"].toString().toStdString() == (kKits / "BJA_Pacific/SN3_04.aiff").string());
    CHECK(strikeJson["nearest_kit"].toString() == "BJA_Pacific");
    CHECK((double) strikeJson["distance_db"] == Approx(6.9396).margin(kAgreement_dB));
    // strike_distance.py's, in the references' order (sorted within each --ref).
    const double expected[] { 12.7623, 13.3495, 13.5942, 13.9986, 13.4739, 9.2291, 7.5671, 10.1103, 6.9396 };
    REQUIRE(strikeJson["distances_db"].size() == 9);
    for (int i = 0; i < 9; ++i)
        CHECK((double) strikeJson["distances_db"][i] == Approx(expected[i]).margin(kAgreement_dB));
    CHECK(strikeJson["fingerprint_db"].size() == StrikeFingerprint::kCells);
}

TEST_CASE("strike distance: zero to itself, symmetric, blind to level and to the silence before the strike", "[renderer][distance]")
{
    const double rate = 48000.0;
    const auto a = snareLike(rate), b = snareLike(rate, 240.0, 410.0);
    const auto fa = fingerprintOf(a, rate), fb = fingerprintOf(b, rate);

    CHECK(distance(fa, fa) == 0.0);
    CHECK(distance(fa, fingerprintOf(a, rate)) == 0.0);
    CHECK(distance(fa, fb) > 1.0);
    CHECK(distance(fa, fb) == Approx(distance(fb, fa)).margin(1e-12));

    auto quiet = a;
    for (auto& v : quiet)
        v *= 0.003;
    CHECK(distance(fa, fingerprintOf(quiet, rate)) < 1e-9);

    // The onset is found: the same strike after 0.1 s or 0.35 s of silence.
    const auto early = strike(rate, 1.0, { { 700.0, 0.5 } }, 50.0, 0.1, 0.3),
               late = strike(rate, 1.25, { { 700.0, 0.5 } }, 50.0, 0.35, 0.3);
    CHECK(distance(fingerprintOf(early, rate), fingerprintOf(late, rate)) < 1e-9);
    // ... and moved by 5 ms against its own windows, it is another fingerprint.
    auto shifted = a;
    shifted.erase(shifted.begin() + (std::ptrdiff_t)(0.021 * rate), shifted.begin() + (std::ptrdiff_t)(0.026 * rate));
    CHECK(distance(fa, fingerprintOf(shifted, rate)) > 0.05);
}

TEST_CASE("strike distance: a decaying sine at a band's centre puts its energy in that band", "[renderer][distance]")
{
    for (const double rate : { 48000.0, 44100.0 })
        for (const int band : { 3, 10, 16, 22 })
        {
            const double centre = snaresim::render::fingerprintBandCentre_Hz(band);
            INFO(rate << " Hz, band " << band << " (" << centre << " Hz)");
            const auto f = fingerprintOf(strike(rate, 0.5, { { centre, 0.5 } }, 60.0), rate);
            double sum = 0.0;
            for (int w = 0; w < StrikeFingerprint::kWindows; ++w)
                for (int b = 0; b < StrikeFingerprint::kBands; ++b)
                {
                    CHECK(f.at(w, b) >= StrikeFingerprint::kFloor_dB);
                    sum += f.at(w, b) > StrikeFingerprint::kFloor_dB ? std::pow(10.0, f.at(w, b) / 10.0) : 0.0;
                    // The band holds each window's energy: the others 20 dB down; in the 30 ms
                    // window, whose Hann main lobe spans +-67 Hz, its neighbours 10 dB, and below
                    // 1 kHz, where that is as wide as the bands, it is the loudest.
                    const double below = w > 0 ? 20.0 : band < 10 ? 0.0 : std::abs(b - band) == 1 ? 10.0 : 20.0;
                    if (b != band)
                        CHECK(f.at(w, b) < f.at(w, band) - below);
                }
            CHECK(sum == Approx(1.0).margin(1e-3)); // dB of the whole
        }

    // 100 Hz: in the 200 ms window its own band; the bands above the Nyquist frequency are empty.
    const auto low = fingerprintOf(strike(16000.0, 0.5, { { 100.0, 0.5 } }, 60.0), 16000.0);
    for (int b = 1; b < StrikeFingerprint::kBands; ++b)
        CHECK(low.at(2, b) < low.at(2, 0) - 20.0);
    CHECK(low.at(0, 22) == StrikeFingerprint::kFloor_dB);
}

TEST_CASE("strike distance: the RMS of the 69 differences, and empty windows at the floor", "[renderer][distance]")
{
    StrikeFingerprint a, b;
    a.level_dB.fill(-20.0);
    b.level_dB.fill(-21.0);
    CHECK(distance(a, b) == Approx(1.0).epsilon(1e-12));
    b = a;
    b.level_dB[17] += 2.0 * std::sqrt((double) StrikeFingerprint::kCells);
    CHECK(distance(a, b) == Approx(2.0).epsilon(1e-12));

    // A strike 20 ms long: the 30-100 and 100-300 ms windows hold nothing.
    const double rate = 48000.0;
    const auto f = fingerprintOf(strike(rate, 0.020, { { 1000.0, 0.5 } }, 60.0), rate);
    for (int w = 1; w < StrikeFingerprint::kWindows; ++w)
        for (int band = 0; band < StrikeFingerprint::kBands; ++band)
            CHECK(f.at(w, band) == StrikeFingerprint::kFloor_dB);
    CHECK(f.at(0, 10) > -1.0);
}

TEST_CASE("strike distance: no strike in silence, a steady tone, a swell or non-finite samples", "[renderer][distance]")
{
    using snaresim::render::NotAStrike;
    const double rate = 48000.0;
    CHECK_THROWS_AS(fingerprintOf(std::vector<double> {}, rate), NotAStrike);
    CHECK_THROWS_WITH(fingerprintOf(std::vector<double>(48000, 0.0), rate), "silent");
    CHECK_THROWS_WITH(fingerprintOf(strike(rate, 1.0, { { 440.0, 0.5 } }, 0.0), rate), Catch::Contains("no strike"));
    auto swell = strike(rate, 1.0, { { 440.0, 0.5 } }, 0.0);
    for (std::size_t i = 0; i < swell.size(); ++i)
        swell[i] *= (double) i / (double) swell.size();
    CHECK_THROWS_WITH(fingerprintOf(swell, rate), Catch::Contains("no strike"));
    auto broken = snareLike(rate);
    broken[5000] = std::nan("");
    CHECK_THROWS_WITH(fingerprintOf(broken, rate), "non-finite samples");
    // A slow strike, its 100-300 ms about 5 dB below its first 30 ms, is one.
    CHECK_NOTHROW(fingerprintOf(strike(rate, 1.0, { { 440.0, 0.5 } }, 25.0), rate));
}

TEST_CASE("strike distance: --distance reads WAV and AIFF alike, channels averaged, and prints each distance", "[renderer][distance]")
{
    TempDir dir;
    const double rate = 48000.0;
    const auto a = snareLike(rate), b = snareLike(rate, 240.0, 410.0);
    std::vector<double> mean(a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        mean[i] = 0.5 * (a[i] + b[i]);
    writeStrike(dir, "a.wav", a);
    writeStrike(dir, "b.wav", b);
    writeStrike(dir, "mean.wav", mean);
    const auto aiff = writeStrike(dir, "a.aiff", a);
    const auto stereo = dir.in() / "stereo.aiff";
    writeAudio(stereo, { a, b }, rate);
    const auto kit = dir.in().string() + ":*.wav";

    auto measure = [&](const fs::path& file) {
        const auto run = runRenderer({ "--distance", file.string(), "--ref", kit, "--json" }, dir.root() / "capture");
        INFO(run.err);
        REQUIRE(run.exitCode == 0);
        CHECK(run.err.empty());
        return parseJson(run.out);
    };
    // The references: a.wav, b.wav, mean.wav (sorted), kit "in".
    const auto fromAiff = measure(aiff);
    REQUIRE(fromAiff["references"].size() == 3);
    CHECK(fromAiff["references"][0]["kit"].toString() == "in");
    CHECK(fromAiff["strikes"][0]["nearest"].toString().toStdString() == (dir.in() / "a.wav").string());
    CHECK((double) fromAiff["strikes"][0]["distance_db"] < 0.01);
    CHECK((double) fromAiff["strikes"][0]["distances_db"][1] > 1.0);

    const auto fromStereo = measure(stereo);
    CHECK(fromStereo["strikes"][0]["nearest"].toString().toStdString() == (dir.in() / "mean.wav").string());
    CHECK((double) fromStereo["strikes"][0]["distance_db"] < 0.01);
    CHECK((double) fromStereo["strikes"][0]["distances_db"][0] > 0.5);

    // Text: per strike, its nearest, then one line per recording; two strikes in order.
    const auto run =
        runRenderer({ "--distance", aiff.string(), "--distance", (dir.in() / "b.wav").string(), "--ref", kit }, dir.root() / "capture");
    REQUIRE(run.exitCode == 0);
    const auto text = lines(run.out);
    REQUIRE(text.size() == 8);
    CHECK(text[0] == aiff.string() + ": nearest in/a.wav at 0.00 dB (of 3 recordings)");
    CHECK(text[1] == "    0.00 dB  in/a.wav");
    CHECK(text[2].ends_with(" dB  in/b.wav"));
    CHECK(text[4] == (dir.in() / "b.wav").string() + ": nearest in/b.wav at 0.00 dB (of 3 recordings)");
}

TEST_CASE("strike distance: a render with --ref measures the WAV it writes", "[renderer][distance]")
{
    TempDir dir;
    writeStrike(dir, "a.wav", snareLike(48000.0));
    writeStrike(dir, "b.wav", snareLike(44100.0, 240.0, 410.0), 44100.0);
    const auto kit = dir.in().string() + ":*.wav";
    const auto wav = (dir.out() / "strike.wav").string();

    const auto render = runRenderer({ "-o", wav, "--hit", "0.01:100", "--seconds", "0.4", "--ref", kit, "--json" }, dir.root() / "capture");
    INFO(render.err);
    REQUIRE(render.exitCode == 0);
    const auto json = parseJson(render.out);
    CHECK(json["output"].toString().toStdString() == wav);
    const auto& rendered = json["distance"]["strikes"][0];
    CHECK(rendered["file"].toString().toStdString() == wav);
    CHECK(json["distance"]["references"].size() == 2);

    const auto measured = runRenderer({ "--distance", wav, "--ref", kit, "--json" }, dir.root() / "capture");
    REQUIRE(measured.exitCode == 0);
    const auto measuredJson = parseJson(measured.out);
    const auto& again = measuredJson["strikes"][0];
    CHECK((double) rendered["distance_db"] == Approx((double) again["distance_db"]).margin(1e-9));
    CHECK((double) rendered["distances_db"][1] == Approx((double) again["distances_db"][1]).margin(1e-9));
    CHECK(rendered["nearest"] == again["nearest"]);

    const auto summary = runRenderer({ "-o", wav, "--hit", "0:100", "--seconds", "0.4", "--ref", kit }, dir.root() / "capture");
    REQUIRE(summary.exitCode == 0);
    CHECK(summary.out.find("wrote " + wav) != std::string::npos);
    CHECK(summary.out.find("the rendered strike " + wav + ": nearest in/") != std::string::npos);
}

TEST_CASE("strike distance: bad input exits 2 with one line and writes nothing", "[renderer][distance][errors]")
{
    TempDir dir;
    const double rate = 48000.0;
    writeStrike(dir, "a.wav", snareLike(rate));
    const auto good = (dir.in() / "a.wav").string();
    const auto kit = dir.in().string() + ":a.wav";
    const auto text = dir.in() / "text.wav";
    std::ofstream(text) << "not a sound file\n";
    const auto silent = writeStrike(dir, "silent.wav", std::vector<double>(48000, 0.0));
    const auto steady = writeStrike(dir, "steady.wav", strike(rate, 1.0, { { 440.0, 0.5 } }, 0.0));

    requireRejected(dir, { "--distance", (dir.in() / "missing.wav").string(), "--ref", kit }, "no such file");
    requireRejected(dir, { "--distance", text.string(), "--ref", kit }, "not a WAV, AIFF or FLAC file");
    requireRejected(dir, { "--distance", silent.string(), "--ref", kit }, "silent.wav: silent");
    requireRejected(dir, { "--distance", steady.string(), "--ref", kit }, "steady.wav: no strike");
    requireRejected(dir, { "--distance", good, "--ref", dir.in().string() + ":*.flac" }, "matches no file");
    requireRejected(dir, { "--distance", good, "--ref", (dir.root() / "no-such-kit").string() + ":*.wav" }, "matches no file");
    requireRejected(dir, { "--distance", good, "--ref", dir.in().string() + ":s*.wav" }, "silent.wav");
    requireRejected(dir, { "--distance", good, "--ref", dir.in().string() }, "is not KITDIR:GLOB");
    requireRejected(dir, { "--distance", good }, "missing --ref");
    requireRejected(dir, { "--distance", good, "--ref", kit, "-o", (dir.out() / "x.wav").string() }, "-o cannot be used with --distance");
    requireRejected(dir, { "--distance", good, "--ref", kit, "--preset", "Piccolo" }, "--preset cannot be used with --distance");
    requireRejected(dir, { "--bench", "--ref", kit }, "--ref cannot be used with --bench");

    // A render whose references or strike cannot be measured writes no WAV.
    const auto wav = (dir.out() / "strike.wav").string();
    requireRejected(dir, { "-o", wav, "--hit", "0:100", "--seconds", "0.3", "--ref", dir.in().string() + ":*.flac" }, "matches no file");
    requireRejected(dir, { "-o", wav, "--hit", "1:100", "--seconds", "0.3", "--ref", kit }, "the rendered strike " + wav + ": silent");
    CHECK(entries(dir.out()).empty());
}
