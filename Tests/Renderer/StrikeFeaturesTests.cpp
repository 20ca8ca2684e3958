// The strike features of --match (Source/Renderer/StrikeFeatures.h) and its spectral envelope,
// on synthetic strikes whose features are known, and against scripts/snare_features.py on the
// same samples (when a python3 with numpy and scipy was found at configure time).
//
// A decaying sine A e^{-a t} sin(2 pi f t) falls 20 log10(e) a dB a second: 20 dB after
// 20 / (8.686 a) s, 40 dB after twice that; its spectrum is one line at f, so its centroid and
// its lowest strong peak are f and its energy lies in f's band. Two sines of equal amplitude
// and decay split the energy in half (to the window's leakage).

#include "MatchDistance.h"
#include "SpectralEnvelope.h"
#include "StrikeFeatures.h"

#include <catch2/catch.hpp>
#include <juce_audio_formats/juce_audio_formats.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace snaresim::render;

namespace
{

std::vector<double> decaying(double rate, double seconds, const std::vector<double>& freqs, double dbPerSecond, double delay_s = 0.0,
                             double noise = 0.0)
{
    const double a = dbPerSecond / (20.0 * std::log10(std::numbers::e));
    std::vector<double> x((std::size_t)(seconds * rate), 0.0);
    std::mt19937_64 rng(1);
    std::normal_distribution<double> gauss;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        const double t = (double) i / rate - delay_s;
        if (t >= 0.0)
            for (const double f : freqs)
                x[i] += 0.4 * std::exp(-a * t) * std::sin(2.0 * std::numbers::pi * f * t);
        if (noise > 0.0)
            x[i] += noise * gauss(rng);
    }
    return x;
}

} // namespace

TEST_CASE("strike features: a decaying sine after quiet noise", "[renderer][match][features]")
{
    // 440 Hz falling 40 dB/s after 0.2 s of noise 100 dB down: -20 dB at 500 ms, -40 dB at 1000 ms.
    const auto x = decaying(48000.0, 1.6, { 440.0 }, 40.0, 0.2, 4e-6);
    const auto f = measureStrike(x, 48000.0);
    CHECK(f.onset_s() == Approx(0.199).margin(0.002));
    REQUIRE(f.tailCentroid_Hz);
    CHECK(*f.tailCentroid_Hz == Approx(440.0).margin(5.0));
    REQUIRE(f.lowestPeak_Hz);
    CHECK(*f.lowestPeak_Hz == Approx(440.0).margin(1.0));
    REQUIRE(f.fall20_ms);
    CHECK(*f.fall20_ms == Approx(500.0).margin(15.0));
    REQUIRE(f.fall40_ms);
    CHECK(*f.fall40_ms == Approx(1000.0).margin(15.0));
    CHECK(f.bandShares[0] > 0.99);
    CHECK(f.bandShares[0] + f.bandShares[1] + f.bandShares[2] + f.bandShares[3] + f.bandShares[4] == Approx(1.0).margin(1e-9));
}

TEST_CASE("strike features: two sines in two bands at 44.1 kHz", "[renderer][match][features]")
{
    // 3 and 7 kHz together, 60 dB/s: half the energy in 2-5 kHz, half in 5-10 kHz, the centroid
    // between them, -20 dB at 333 ms, -40 dB at 667 ms.
    const auto x = decaying(44100.0, 1.0, { 3000.0, 7000.0 }, 60.0);
    const auto f = measureStrike(x, 44100.0);
    CHECK(f.onset == 0);
    CHECK(*f.tailCentroid_Hz == Approx(5000.0).margin(100.0));
    CHECK(*f.lowestPeak_Hz == Approx(3000.0).margin(2.0));
    CHECK(f.bandShares[2] == Approx(0.5).margin(0.02));
    CHECK(f.bandShares[3] == Approx(0.5).margin(0.02));
    CHECK(*f.fall20_ms == Approx(333.3).margin(15.0));
    CHECK(*f.fall40_ms == Approx(666.7).margin(15.0));
}

TEST_CASE("strike features: bad input as the script refuses it", "[renderer][match][features]")
{
    const double rate = 48000.0;
    auto reason = [&](const std::vector<double>& x) {
        try
        {
            (void) measureStrike(x, rate);
        }
        catch (const NotAStrike& e)
        {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(reason(std::vector<double>(48000, 0.0)) == "silent");
    CHECK(reason(decaying(rate, 0.05, { 440.0 }, 40.0)).starts_with("shorter than 100 ms"));
    std::vector<double> steady(48000), swell(48000);
    for (std::size_t i = 0; i < steady.size(); ++i)
    {
        steady[i] = 0.5 * std::sin(2.0 * std::numbers::pi * 440.0 * (double) i / rate);
        swell[i] = std::pow(std::sin(std::numbers::pi * (double) i / 48000.0), 2.0) * steady[i];
    }
    CHECK(reason(steady).starts_with("no strike"));
    CHECK(reason(swell).starts_with("no strike"));
    // A render may ring past its end: only silence is refused then.
    CHECK_NOTHROW(measureStrike(steady, rate, StrikeRules::render));
    CHECK_THROWS_AS(measureStrike(std::vector<double>(4800, 0.0), rate, StrikeRules::render), NotAStrike);
}

TEST_CASE("spectral envelope: level-normalised, in the sine's band, falling with it", "[renderer][match][features]")
{
    const double rate = 48000.0;
    const auto x = decaying(rate, 1.0, { 1000.0 }, 100.0); // 1 dB every 10 ms frame
    auto louder = x;
    for (auto& v : louder)
        v *= 0.01;
    const auto a = spectralEnvelope(x, rate, 0);
    const auto b = spectralEnvelope(louder, rate, 0);
    CHECK(envelopeDistance_dB(a, b) < 1e-6); // the level drops out

    const int band = 10; // centred on 1 kHz
    CHECK(envelopeBandCentre_Hz(band) == Approx(1000.0));
    for (int t = 0; t + 1 < SpectralEnvelope::kFrames; ++t)
    {
        CHECK(a.at(t, band) - a.at(t + 1, band) == Approx(1.0).margin(0.05)); // 100 dB/s: 1 dB a frame
        CHECK(a.at(t, band) > a.at(t, band - 3) + 10.0);                      // an octave down: at the floor, 45 dB below the loudest
    }

    // A strike an eighth of an octave higher is further than the same strike, nearer than an octave.
    const auto higher = spectralEnvelope(decaying(rate, 1.0, { 1090.0 }, 100.0), rate, 0);
    const auto octave = spectralEnvelope(decaying(rate, 1.0, { 2000.0 }, 100.0), rate, 0);
    CHECK(envelopeDistance_dB(a, higher) > 0.5);
    CHECK(envelopeDistance_dB(a, higher) < envelopeDistance_dB(a, octave));
}

TEST_CASE("match distance: zero for the same strike, growing with the difference", "[renderer][match][features]")
{
    const double rate = 48000.0;
    const auto base = strikeSignature(decaying(rate, 0.6, { 200.0, 330.0, 2500.0 }, 60.0, 0.0, 1e-4), rate, StrikeRules::render);
    CHECK(matchDistance(base, base).total == 0.0);
    double last = 0.0;
    for (const double ratio : { 1.02, 1.06, 1.2 })
    {
        const auto other = strikeSignature(decaying(rate, 0.6, { 200.0 * ratio, 330.0 * ratio, 2500.0 * ratio }, 60.0, 0.0, 1e-4), rate,
                                           StrikeRules::render);
        const auto d = matchDistance(base, other);
        CHECK(d.total > last);
        CHECK(d.z[5] == Approx(4.0 * std::tanh(12.0 * std::log2(ratio))).margin(0.05)); // the lowest peak, semitones
        last = d.total;
    }
}

#ifdef SNARESIM_PYTHON
namespace
{
std::string runCommand(const std::string& command)
{
    std::string output;
    if (auto* pipe = ::popen(command.c_str(), "r"))
    {
        char buffer[4096];
        while (const auto n = std::fread(buffer, 1, sizeof buffer, pipe))
            output.append(buffer, n);
        ::pclose(pipe);
    }
    return output;
}

double number(const juce::var& v) { return v.isVoid() ? -1.0 : (double) v; }
} // namespace

TEST_CASE("strike features: the same as scripts/snare_features.py on the same samples", "[renderer][match][features]")
{
    // Three modes, their own decays, noise and a lead-in, 24-bit stereo at 44.1 kHz and float at 48 kHz.
    for (const double rate : { 44100.0, 48000.0 })
    {
        std::vector<double> x((std::size_t)(1.2 * rate), 0.0);
        std::mt19937_64 rng(7);
        std::normal_distribution<double> gauss;
        for (std::size_t i = 0; i < x.size(); ++i)
        {
            const double t = (double) i / rate - 0.05;
            if (t >= 0.0)
                x[i] = 0.5 * std::exp(-9.0 * t) * std::sin(2.0 * std::numbers::pi * 187.0 * t) +
                       0.3 * std::exp(-15.0 * t) * std::sin(2.0 * std::numbers::pi * 341.0 * t) + 0.2 * std::exp(-40.0 * t) * gauss(rng);
            x[i] += 1e-4 * gauss(rng) + 0.01; // a noise floor and a DC offset
        }
        const auto dir = std::filesystem::temp_directory_path() / ("snaresim-features-" + std::to_string((int) rate) + ".wav");
        {
            juce::WavAudioFormat wav;
            auto stream = std::make_unique<juce::FileOutputStream>(juce::File(dir.string()));
            stream->setPosition(0);
            stream->truncate();
            std::unique_ptr<juce::AudioFormatWriter> writer(wav.createWriterFor(stream.release(), rate, 1, 32, {}, 0));
            REQUIRE(writer);
            std::vector<float> samples(x.begin(), x.end());
            const float* channels[] { samples.data() };
            REQUIRE(writer->writeFromFloatArrays(channels, 1, (int) samples.size()));
        }
        // What the script reads is the float file: measure the same floats here.
        std::vector<double> stored;
        for (const double v : x)
            stored.push_back((double) (float) v);
        const auto mine = measureStrike(stored, rate);

        const auto json = runCommand(std::string(SNARESIM_PYTHON) + " " + SNARESIM_FEATURES_SCRIPT + " --json " + dir.string());
        std::filesystem::remove(dir);
        const auto parsed = juce::JSON::parse(juce::String(json));
        REQUIRE(parsed.isArray());
        const auto theirs = parsed[0];
        INFO("rate " << rate << ", script: " << json);
        CHECK(mine.onset_s() == Approx(number(theirs["onset_s"])).margin(1e-9));
        CHECK(*mine.tailCentroid_Hz == Approx(number(theirs["tail_centroid_hz"])).epsilon(1e-6));
        for (std::size_t b = 0; b < kShareBandNames.size(); ++b)
            CHECK(mine.bandShares[b] ==
                  Approx(number(theirs["band_shares"][juce::Identifier(std::string(kShareBandNames[b]))])).margin(1e-9));
        CHECK(*mine.fall20_ms == Approx(number(theirs["fall_20db_ms"])).margin(1e-6));
        CHECK(*mine.fall40_ms == Approx(number(theirs["fall_40db_ms"])).margin(1e-6));
        CHECK(*mine.lowestPeak_Hz == Approx(number(theirs["lowest_peak_hz"])).epsilon(1e-6));
    }
}
#endif
