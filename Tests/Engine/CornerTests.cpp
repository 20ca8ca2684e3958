// The drum at the corners of its parameter space: every parameter at its minimum and at its
// maximum (the others at their defaults), and 120 random combinations, each playing a 0.5 s
// fortissimo roll (velocity 127 every 60 ms, 9 strikes) at 48 kHz; and 15 random combinations
// in the air box, whose rolls last a tenth of that, 50 ms (it is several times slower than
// real time, more with its energy tracked). Each run must give finite, bounded output, an energy that never rises but by what
// the mallets bring (losses on), and a drum that never goes non-finite (what the plug-in's
// non-finite guard would catch and reset).
//
// SNARESIM_CORNER_SECONDS shortens the roll and SNARESIM_CORNER_COMBINATIONS sets the number of
// random combinations, an eighth of them in the air box (the sanitizer build sets both; the test
// prints what it used). The runs share the machine's cores.

#include <catch2/catch.hpp>

#include "Drum.h"
#include "DrumConfig.h"
#include "Parameters.h"
#include "Report.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace snaresim;

namespace
{

constexpr double kSampleRate = 48000.0;
constexpr double kRollInterval_s = 0.06;
// Full scale is 1. A drum that rings at 36 dB above it has blown up, not been struck hard.
constexpr double kOutputBound = 64.0;
// Largest rise of (total - injected) energy in one step, relative to the largest total seen:
// round-off is about 1e-15 per step.
constexpr double kRiseTolerance = 1.0e-12;
// The air box's rolls: a tenth of the others' (50 ms in the release suite)
constexpr double kAirBoxShare = 1.0 / 10.0;
constexpr int kRandomCombinations = 120;

struct Corner
{
    std::string name;
    ParameterSet params;
};

struct Outcome
{
    bool built = false;
    std::string error;
    double peak = 0.0;
    long nonFiniteSamples = 0;
    int nonFiniteStates = 0; // checks of the whole state that found a non-finite value
    double worstRise = 0.0;  // relative to the largest total energy
    double maxTotal_J = 0.0;
};

double rollSeconds()
{
    if (const char* text = std::getenv("SNARESIM_CORNER_SECONDS"))
    {
        const double s = std::atof(text);
        if (s > 0.0)
            return s;
    }
    return 0.5;
}

int randomCombinations()
{
    if (const char* text = std::getenv("SNARESIM_CORNER_COMBINATIONS"))
    {
        const int n = std::atoi(text);
        if (n > 0)
            return n;
    }
    return kRandomCombinations;
}

// An eighth of the random combinations in the air box (at least one).
int airBoxCombinations(int random) { return std::max(1, (random + 7) / 8); }

Outcome playRoll(const ParameterSet& params, double seconds)
{
    Outcome out;
    try
    {
        Drum drum(makeDrumConfig(params, kSampleRate));
        drum.setEnergyTracking(true);
        out.built = true;

        const long samples = std::lround(seconds * kSampleRate);
        const long interval = std::lround(kRollInterval_s * kSampleRate);
        double previous = 0.0;

        for (long n = 0; n < samples; ++n)
        {
            if (n % interval == 0)
            {
                drum.playNote(38, 127);
                // The strike's energy enters through injected_J on the next step.
            }

            const double y = drum.step();
            if (! std::isfinite(y))
                ++out.nonFiniteSamples;
            else
                out.peak = std::max(out.peak, std::abs(y));

            const auto& e = drum.energy();
            const double held = e.total() - e.injected_J;
            out.maxTotal_J = std::max(out.maxTotal_J, e.total());
            if (n > 0 && out.maxTotal_J > 0.0)
                out.worstRise = std::max(out.worstRise, (held - previous) / out.maxTotal_J);
            previous = held;

            if (n % 1024 == 1023 && ! drum.isFinite())
                ++out.nonFiniteStates;
        }
    }
    catch (const std::exception& e)
    {
        out.error = e.what();
    }
    return out;
}

std::vector<Corner> corners(int randomCount)
{
    std::vector<Corner> list;

    for (const auto& spec : parameterSpecs())
        for (const bool atMax : { false, true })
        {
            Corner c;
            c.name = std::string(spec.key) + (atMax ? " at maximum" : " at minimum");
            c.params.set(spec.id, atMax ? spec.maxValue : spec.minValue);
            list.push_back(std::move(c));
        }

    std::mt19937 random(20261123);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const auto randomParameters = [&] {
        ParameterSet p;
        for (const auto& spec : parameterSpecs())
        {
            const double u = unit(random);
            double v = spec.scale == ParamScale::logarithmic ? spec.minValue * std::pow(spec.maxValue / spec.minValue, u)
                                                             : spec.minValue + u * (spec.maxValue - spec.minValue);
            if (spec.kind != ParamKind::continuous)
                v = std::round(v);
            p.setClamped(spec.id, v);
        }
        return p;
    };
    for (int i = 0; i < randomCount; ++i)
    {
        Corner c;
        c.name = "random combination " + std::to_string(i);
        c.params = randomParameters();
        // the real-time models here; the air box's combinations follow
        if (c.params.get(ParamId::airModel) == (double) AirModel::airbox)
            c.params.set(ParamId::airModel, (double) AirModel::cavity);
        list.push_back(std::move(c));
    }
    // The air box with every other parameter anywhere: the heads' grids from finer than the air's
    // to several times coarser (Quality), every shell depth, tension and loss.
    for (int i = 0; i < airBoxCombinations(randomCount); ++i)
    {
        Corner c;
        c.name = "air box, random combination " + std::to_string(i);
        c.params = randomParameters();
        c.params.set(ParamId::airModel, (double) AirModel::airbox);
        list.push_back(std::move(c));
    }
    return list;
}

} // namespace

TEST_CASE("every parameter at its limits and random combinations play a fortissimo roll safely", "[corners][slow]")
{
    const double seconds = rollSeconds();
    const int randomCount = randomCombinations();
    const auto list = corners(randomCount);
    std::vector<Outcome> outcomes(list.size());

    std::atomic<std::size_t> next { 0 };
    auto worker = [&] {
        for (std::size_t i = next++; i < list.size(); i = next++)
            outcomes[i] = playRoll(list[i].params,
                                   list[i].params.get(ParamId::airModel) == (double) AirModel::airbox ? kAirBoxShare * seconds : seconds);
    };
    const unsigned threads = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back(worker);
    for (auto& t : pool)
        t.join();

    long nonFiniteSamples = 0;
    int nonFiniteStates = 0, failedBuilds = 0;
    double peak = 0.0, worstRise = 0.0;
    for (std::size_t i = 0; i < list.size(); ++i)
    {
        const auto& o = outcomes[i];
        INFO(list[i].name << ": peak " << o.peak << ", worst energy rise " << o.worstRise << " of the largest total " << o.maxTotal_J
                          << " J" << (o.error.empty() ? "" : ", error: " + o.error));
        CHECK(o.built);
        CHECK(o.nonFiniteSamples == 0);
        CHECK(o.nonFiniteStates == 0);
        CHECK(o.peak > 0.0);
        CHECK(o.peak < kOutputBound);
        CHECK(o.worstRise <= kRiseTolerance);

        failedBuilds += o.built ? 0 : 1;
        nonFiniteSamples += o.nonFiniteSamples;
        nonFiniteStates += o.nonFiniteStates;
        peak = std::max(peak, o.peak);
        worstRise = std::max(worstRise, o.worstRise);
    }

    snaresim::test::report() << "corners: " << list.size() << " drums (" << 2 * kNumParameters << " at parameter limits, " << randomCount
                             << " random, " << airBoxCombinations(randomCount) << " random in the air box), " << seconds
                             << " s fortissimo roll each (the air box: " << kAirBoxShare * seconds << " s) at " << kSampleRate << " Hz on "
                             << threads << " threads; failed builds " << failedBuilds << ", non-finite samples " << nonFiniteSamples
                             << ", non-finite guard triggers " << nonFiniteStates << ", largest peak " << peak << " (bound " << kOutputBound
                             << "), worst energy rise per step " << worstRise << " of the total (tolerance " << kRiseTolerance << ")\n";
}
