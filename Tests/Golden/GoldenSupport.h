#pragma once
// What the golden tests share: where the references are, whether they are being regenerated,
// the deterministic path they need, and the difference of a render from its reference.

#include "Report.h"
#include "VectorTarget.h"

#include <catch2/catch.hpp>
#include <juce_audio_formats/juce_audio_formats.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace golden
{

// SNARESIM_UPDATE_GOLDENS=1: the references are written, not compared.
inline bool updating()
{
    const char* v = std::getenv("SNARESIM_UPDATE_GOLDENS");
    return v != nullptr && std::string(v) == "1";
}

struct Difference
{
    long differing = 0;
    double maxAbs = 0.0;
    double dbBelowSignal = INFINITY; // of the RMS difference, relative to the reference's RMS
};

inline Difference compare(const std::vector<std::vector<float>>& reference, const std::vector<std::vector<float>>& now)
{
    Difference d;
    double signal = 0.0, error = 0.0;
    for (size_t ch = 0; ch < reference.size(); ++ch)
        for (size_t i = 0; i < reference[ch].size(); ++i)
        {
            const double r = reference[ch][i], x = now[ch][i];
            signal += r * r;
            error += (x - r) * (x - r);
            if (x != r)
                ++d.differing;
            d.maxAbs = std::max(d.maxAbs, std::abs(x - r));
        }
    if (error > 0.0)
        d.dbBelowSignal = 10.0 * std::log10(signal / error);
    return d;
}

// A render that differs is printed (the test fails); one that is identical only while reporting.
inline void report(const std::string& name, const Difference& d)
{
    if (d.differing == 0)
        snaresim::test::report() << "golden " << name << ": identical\n";
    else
        std::cout << "golden " << name << ": " << d.differing << " samples differ, largest by " << d.maxAbs << ", difference "
                  << d.dbBelowSignal << " dB below the signal\n";
}

inline void writeFloatWav(const std::filesystem::path& file, const std::vector<float>& samples, double sampleRate)
{
    std::filesystem::remove(file);
    juce::WavAudioFormat format;
    std::unique_ptr<juce::OutputStream> stream = std::make_unique<juce::FileOutputStream>(juce::File(file.string()));
    std::unique_ptr<juce::AudioFormatWriter> writer(format.createWriterFor(stream.get(), sampleRate, 1, 32, {}, 0));
    REQUIRE(writer != nullptr);
    stream.release();
    const float* channels[] = { samples.data() };
    REQUIRE(writer->writeFromFloatArrays(channels, 1, (int) samples.size()));
}

inline const std::filesystem::path goldenDir { SNARESIM_GOLDEN_DIR };

// The goldens are made and compared on the deterministic path only: ctest sets it for this
// executable (Tests/Golden/CMakeLists.txt); run by hand, it needs the same environment.
inline void requireDeterministicPath()
{
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    INFO("the golden tests run with SNARESIM_VECTOR_TARGET=baseline and GLIBC_TUNABLES=" SNARESIM_GOLDEN_TUNABLES
         " (ctest sets both); here the vector target is "
         << snaresim::vectorTargetName(snaresim::vectorTarget()) << " and GLIBC_TUNABLES is "
         << (tunables != nullptr ? tunables : "unset"));
    REQUIRE(snaresim::vectorTarget() == snaresim::VectorTarget::baseline);
    REQUIRE(tunables != nullptr);
    REQUIRE(std::string(tunables) == SNARESIM_GOLDEN_TUNABLES);
}

} // namespace golden
