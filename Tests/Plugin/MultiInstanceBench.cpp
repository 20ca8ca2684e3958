// Several instances of the built VST3 in one host process, each playing the fortissimo roll,
// all on one core: what a session with more than one snare asks of a machine.
//
//   snaresim_multi_instance_bench [--instances N] [--quality Q (coarseness 1-4)] [--sample-rate HZ] [--block N]
//                                 [--repeats N] [--short]
//
// Loads the bundle N times (default 4) through JUCE's VST3 host, pins the process to one CPU and
// plays the renderer's roll (16 strikes from 0.1 s, every 60 ms, velocity 127, 1.5 s) through
// every instance, block by block in turn, as a host's audio thread does. Each host block (all
// instances) is timed; each block's figure is its fastest over the repeats (the renderer's
// --bench method). Prints one JSON line: the total real-time factor (audio seconds over the
// seconds all instances took), the worst host block against its budget, the slowest repeat.
// Exit 1 when the plug-in does not load or plays a non-finite sample; never on a time.

#include "PluginHostHarness.h"

#include "Benchmark.h" // the renderer's roll
#include "DrumConfig.h"
#include "Parameters.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sched.h>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Options
{
    int instances = 4;
    double quality = -1.0; // the plug-in's default unless given
    double sampleRate = 48000.0;
    int block = 64;
    int repeats = 3;
    bool shortRun = false;
};

[[noreturn]] void usage(const char* why)
{
    std::fprintf(
        stderr,
        "snaresim_multi_instance_bench: %s\n"
        "usage: snaresim_multi_instance_bench [--instances N] [--quality Q] [--sample-rate HZ] [--block N] [--repeats N] [--short]\n",
        why);
    std::exit(2);
}

Options parse(int argc, char** argv)
{
    Options o;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        const auto value = [&]() -> double {
            if (i + 1 >= argc)
                usage((a + " needs a value").c_str());
            char* end = nullptr;
            const double v = std::strtod(argv[++i], &end);
            if (end == argv[i] || *end != '\0' || ! std::isfinite(v))
                usage((a + ": not a number: " + argv[i]).c_str());
            return v;
        };
        if (a == "--instances")
            o.instances = (int) value();
        else if (a == "--quality")
            o.quality = value();
        else if (a == "--sample-rate")
            o.sampleRate = value();
        else if (a == "--block")
            o.block = (int) value();
        else if (a == "--repeats")
            o.repeats = (int) value();
        else if (a == "--short")
            o.shortRun = true;
        else
            usage(("unknown option " + a).c_str());
    }
    if (o.instances < 1 || o.instances > 64)
        usage("--instances must be 1 to 64");
    if (o.block < 1 || o.block > 8192)
        usage("--block must be 1 to 8192");
    if (o.repeats < 1 || o.repeats > 100)
        usage("--repeats must be 1 to 100");
    if (! (o.sampleRate >= 8000.0 && o.sampleRate <= 384000.0))
        usage("--sample-rate must be 8000 to 384000");
    if (o.quality != -1.0 && ! (o.quality >= 1.0 && o.quality <= 4.0))
        usage("--quality must be 1 to 4");
    return o;
}

// The host's value of a switch, found by its name.
void setSwitch(juce::AudioPluginInstance& plugin, snaresim::ParamId id, bool on)
{
    const auto& spec = snaresim::spec(id);
    if (auto* p = snaresim::testhost::findParameter(plugin, juce::String(std::string(spec.name))))
        p->setValue(on ? 1.0f : 0.0f);
}

// Quality as the grids' coarseness q (1 to 4): its bandwidth (qualityBandwidth_Hz) as the host's
// normalised value of the logarithmic parameter (VST3 passes the plug-in's own 0..1 range).
void setQuality(juce::AudioPluginInstance& plugin, double q)
{
    const auto& spec = snaresim::spec(snaresim::ParamId::bandwidth);
    auto* p = snaresim::testhost::findParameter(plugin, juce::String(std::string(spec.name)));
    if (p == nullptr)
    {
        std::fprintf(stderr, "snaresim_multi_instance_bench: the plug-in has no parameter \"%s\"\n", std::string(spec.name).c_str());
        std::exit(1);
    }
    const double f = std::clamp(snaresim::qualityBandwidth_Hz(q), spec.minValue, spec.maxValue);
    p->setValue((float) (std::log(f / spec.minValue) / std::log(spec.maxValue / spec.minValue)));
}
} // namespace

int main(int argc, char** argv)
{
    const Options opt = parse(argc, argv);
    using namespace snaresim::render;
    const double seconds = opt.shortRun ? 0.4 : kRollSeconds; // the roll (its first strikes when short)
    const int repeats = opt.shortRun ? 1 : opt.repeats;

    // One core: the first this process may use.
    int cpu = -1;
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) == 0)
        for (int c = 0; c < CPU_SETSIZE && cpu < 0; ++c)
            if (CPU_ISSET(c, &allowed))
                cpu = c;
    if (cpu >= 0)
    {
        cpu_set_t one;
        CPU_ZERO(&one);
        CPU_SET(cpu, &one);
        if (sched_setaffinity(0, sizeof one, &one) != 0)
            cpu = -1;
    }

    const juce::ScopedJuceInitialiser_GUI juceInitialiser;
    std::error_code ec;
    const auto bundle = fs::weakly_canonical(fs::path(SNARESIM_TEST_VST3_BUNDLE), ec);
    juce::VST3PluginFormat vst3;
    std::vector<std::unique_ptr<juce::AudioPluginInstance>> plugins;
    for (int i = 0; i < opt.instances; ++i)
    {
        auto loaded = snaresim::testhost::loadPlugin(vst3, juce::String((ec ? fs::path(SNARESIM_TEST_VST3_BUNDLE) : bundle).string()),
                                                     opt.sampleRate, opt.block);
        if (loaded.instance == nullptr)
        {
            std::fprintf(stderr, "snaresim_multi_instance_bench: cannot load the VST3: %s\n", loaded.error.toRawUTF8());
            return 1;
        }
        plugins.push_back(std::move(loaded.instance));
    }

    const int numSamples = (int) std::lround(seconds * opt.sampleRate);
    const int numBlocks = (numSamples + opt.block - 1) / opt.block;
    std::vector<int> strikeAt;
    for (int s = 0; s < kRollStrikes; ++s)
        if (const int at = (int) std::lround((kRollStart_s + kRollInterval_s * s) * opt.sampleRate); at < numSamples)
            strikeAt.push_back(at);

    int channels = 1;
    for (auto& p : plugins)
    {
        p->enableAllBuses();
        channels = std::max(channels, p->getTotalNumOutputChannels());
        // the drum as chosen, never a lower Quality because this machine is measured slow
        setSwitch(*p, snaresim::ParamId::keepUp, false);
        if (opt.quality > 0.0)
            setQuality(*p, opt.quality);
        // delivered with a block, then the next prepareToPlay builds the grid from them
        snaresim::testhost::RenderRequest settle;
        settle.sampleRate = opt.sampleRate;
        settle.maxBlockSize = opt.block;
        settle.numSamples = opt.block;
        snaresim::testhost::render(*p, settle);
    }

    juce::AudioBuffer<float> buffer(channels, opt.block);
    juce::MidiBuffer midi;
    std::vector<Clock::duration> fastest((size_t) numBlocks, Clock::duration::max());
    Clock::duration slowestRun {};
    long nonFinite = 0;
    for (int run = 0; run < repeats; ++run)
    {
        for (auto& p : plugins)
        {
            p->setRateAndBufferSizeDetails(opt.sampleRate, opt.block);
            p->prepareToPlay(opt.sampleRate, opt.block); // a new drum: every run plays the same blocks
        }
        Clock::duration runTime {};
        for (int b = 0; b < numBlocks; ++b)
        {
            const int start = b * opt.block, count = std::min(opt.block, numSamples - start);
            const auto t0 = Clock::now();
            for (auto& p : plugins)
            {
                buffer.setSize(channels, count, false, false, true);
                buffer.clear();
                midi.clear();
                for (const int at : strikeAt)
                    if (at >= start && at < start + count)
                        midi.addEvent(juce::MidiMessage::noteOn(10, kBenchNote, (juce::uint8) kBenchVelocity), at - start);
                p->processBlock(buffer, midi);
                for (int ch = 0; ch < buffer.getNumChannels(); ++ch)
                    for (int i = 0; i < count; ++i)
                        nonFinite += std::isfinite(buffer.getSample(ch, i)) ? 0 : 1;
            }
            const auto dt = Clock::now() - t0;
            fastest[(size_t) b] = std::min(fastest[(size_t) b], dt);
            runTime += dt;
        }
        slowestRun = std::max(slowestRun, runTime);
        for (auto& p : plugins)
            p->releaseResources();
    }

    Clock::duration total {}, worst {};
    for (const auto t : fastest)
    {
        total += t;
        worst = std::max(worst, t);
    }
    const double totalSeconds = std::chrono::duration<double>(total).count();
    const double budget = opt.block / opt.sampleRate;
    const double worstSeconds = std::chrono::duration<double>(worst).count();
    std::printf("{\"instances\": %d, \"cpu\": %d, \"sample_rate\": %g, \"block_size\": %d, \"quality\": %s, \"seconds\": %g, "
                "\"repeats\": %d, \"short\": %s, \"realtime_factor_total\": %.6g, \"realtime_factor_per_instance\": %.6g, "
                "\"worst_host_block_ms\": %.6g, \"block_budget_ms\": %.6g, \"worst_host_block_share\": %.6g, "
                "\"realtime_factor_total_slowest_run\": %.6g, \"nonfinite_samples\": %ld}\n",
                opt.instances, cpu, opt.sampleRate, opt.block, opt.quality > 0.0 ? std::to_string(opt.quality).c_str() : "null",
                (double) numSamples / opt.sampleRate, repeats, opt.shortRun ? "true" : "false",
                totalSeconds > 0.0 ? seconds / totalSeconds : 0.0, totalSeconds > 0.0 ? opt.instances * seconds / totalSeconds : 0.0,
                1e3 * worstSeconds, 1e3 * budget, worstSeconds / budget,
                slowestRun.count() > 0 ? seconds / std::chrono::duration<double>(slowestRun).count() : 0.0, nonFinite);
    plugins.clear();
    return nonFinite == 0 ? 0 : 1;
}
