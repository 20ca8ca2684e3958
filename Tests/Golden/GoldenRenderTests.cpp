// Golden renders: fixed scenarios played by the renderer (goldens.txt; the plug-in's processor
// plays its own in GoldenPluginTests.cpp), compared sample by sample with the references in this folder. They run on the
// path every x86-64 processor computes the same (CMakeLists.txt here: the baseline vector
// target and glibc's baseline maths, set by ctest), so a change of code that is not meant to
// change the sound must leave them identical, on any machine; the test states every
// difference in dB below the signal. A one-ulp change of a coefficient fails them (the last
// test here).
//
// Regenerate after an intended change of sound (and say so in the commit):
//   SNARESIM_UPDATE_GOLDENS=1 ctest --test-dir build -L golden

#include <catch2/catch.hpp>

#include "DrumConfig.h"
#include "GoldenSupport.h"
#include "Parameters.h"
#include "RendererTestSupport.h"
#include "Report.h"
#include "VectorTarget.h"

#include <juce_audio_formats/juce_audio_formats.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

using namespace rendertest;
using golden::compare;
using golden::Difference;
using golden::goldenDir;
using golden::report;
using golden::requireDeterministicPath;
using golden::updating;

namespace
{
struct Golden
{
    std::string name;
    std::vector<std::string> args;
};

std::vector<Golden> goldenList()
{
    std::vector<Golden> list;
    std::ifstream in(goldenDir / "goldens.txt");
    std::string line;
    while (std::getline(in, line))
    {
        if (line.empty() || line[0] == '#')
            continue;
        const auto colon = line.find(':');
        REQUIRE(colon != std::string::npos);
        Golden g;
        g.name = line.substr(0, colon);
        std::istringstream words(line.substr(colon + 1));
        for (std::string w; words >> w;)
            g.args.push_back(w);
        list.push_back(std::move(g));
    }
    return list;
}

} // namespace

TEST_CASE("the renderer's golden renders are unchanged", "[golden]")
{
    requireDeterministicPath();
    const auto list = goldenList();
    REQUIRE(list.size() >= 9);
    TempDir dir;

    for (const auto& g : list)
    {
        INFO("golden " << g.name);
        auto args = g.args;
        for (auto& a : args)
            if (a.size() > 4 && a.substr(a.size() - 4) == ".mid")
                a = (goldenDir / a).string();
        const auto output = dir.out() / (g.name + ".wav");
        args.insert(args.begin(), { "-o", output.string() });
        const auto run = runRenderer(args, dir.root());
        INFO(run.err);
        REQUIRE(run.exitCode == 0);

        const auto reference = goldenDir / (g.name + ".wav");
        if (updating())
        {
            fs::copy_file(output, reference, fs::copy_options::overwrite_existing);
            std::cout << "golden " << g.name << ": regenerated\n";
            continue;
        }

        const auto ref = readWav(reference);
        const auto now = readWav(output);
        REQUIRE(ref.opened);
        REQUIRE(now.opened);
        REQUIRE(now.sampleRate == ref.sampleRate);
        REQUIRE(now.channels == ref.channels);
        REQUIRE(now.length == ref.length);
        CHECK(peakOf(ref.samples) > 1.0e-3f);

        const auto d = compare(ref.channelSamples, now.channelSamples);
        report(g.name, d);
        CHECK(d.differing == 0);
    }
}

TEST_CASE("a one-ulp change of one coefficient of the default drum fails the goldens", "[golden]")
{
    // The default golden's strike played in-process as the renderer plays it: the same bits as
    // the reference's mix channel (--mic all: top, bottom, room, mix); then the same with one
    // of the drum's coefficients moved by one unit in the last place, which must not pass.
    requireDeterministicPath();
    if (updating())
        return; // it reads the references being written
    const auto ref = readWav(goldenDir / "default-48k-all-mics.wav");
    REQUIRE(ref.opened);
    REQUIRE(ref.channels == 4);
    REQUIRE(ref.sampleRate == 48000.0);
    const auto& mix = ref.channelSamples[3];
    const auto playWith = [&](auto&& change) {
        auto config = snaresim::makeDrumConfig(snaresim::ParameterSet {}, 48000.0);
        change(config);
        return playInProcess(config, { { 0, 100 } }, (long long) mix.size()).mix;
    };

    const auto same = compare({ mix }, { playWith([](snaresim::DrumConfig&) {}) });
    report("default-48k-all-mics (mix, in-process)", same);
    REQUIRE(same.differing == 0);

    // One unit in the last place of a double, or of a float where the engine computes in float
    // (the default batter: its coefficients are floats, which a double's last bit of the
    // tension does not reach).
    const auto up = [](double& v) { v = std::nextafter(v, INFINITY); };
    const auto upFloat = [](double& v) { v = (double) std::nextafter((float) v, INFINITY); };
    SECTION("the snares' contact stiffness")
    {
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { up(c.snares.stiffness); }) });
        report("snare stiffness + 1 ulp", d);
        CHECK(d.differing > 0);
    }
    SECTION("the wires' tension")
    {
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { up(c.snares.tension_N); }) });
        report("wire tension + 1 ulp", d);
        CHECK(d.differing > 0);
    }
    SECTION("the batter's tension, by one unit of its float coefficients")
    {
        REQUIRE(snaresim::makeDrumConfig(snaresim::ParameterSet {}, 48000.0).batter.precision == snaresim::HeadPrecision::single_precision);
        const auto d = compare({ mix }, { playWith([&](snaresim::DrumConfig& c) { upFloat(c.batter.tension_N_per_m); }) });
        report("batter tension + 1 float ulp", d);
        CHECK(d.differing > 0);
    }
}
