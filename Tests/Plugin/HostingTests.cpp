// Loads the BUILT SnareSim VST3 and LV2 binaries through JUCE's hosting classes and plays them.
// Catches what in-process tests cannot: unresolved symbols, a wrong LV2 URI or manifest, a
// broken bundle layout, and whatever the format wrappers do to parameters, state, programs and
// threads. Every test runs once per format ([vst3] and [lv2]); the strictness pass (in the
// manner of pluginval, which Debian does not package) is tagged [strict].
//
// Most renders use Quality 5.1 kHz (coarseness 3) and 5 snare wires (fastSettings): the engine then runs
// faster than real time, and what these tests check does not depend on the detail.

#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "Drum.h"
#include "DrumConfig.h"
#include "ModelExchange.h"
#include "Parameters.h"
#include "PluginHostHarness.h"
#include "Presets.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <dlfcn.h>
#include <unistd.h>

namespace fs = std::filesystem;
using snaresim::ParamId;
using snaresim::testhost::RenderRequest;
using snaresim::testhost::RenderResult;

namespace
{
const double sampleRate = 48000.0;
const int blockSize = 512;

juce::String canonicalPath(const char* path)
{
    std::error_code ec;
    const auto p = fs::weakly_canonical(fs::path(path), ec);
    return juce::String(ec ? std::string(path) : p.string());
}

//==============================================================================
// Loading

enum class Format
{
    vst3,
    lv2
};

struct Plugin
{
    snaresim::testhost::LoadedPlugin loaded;
    Format format;

    juce::AudioPluginInstance& operator*() const { return *loaded.instance; }
    juce::AudioPluginInstance* operator->() const { return loaded.instance.get(); }
};

Plugin load(Format format)
{
    Plugin plugin { {}, format };

    if (format == Format::vst3)
    {
        juce::VST3PluginFormat vst3;
        plugin.loaded = snaresim::testhost::loadPlugin(vst3, canonicalPath(SNARESIM_TEST_VST3_BUNDLE), sampleRate, blockSize);
    }
    else
    {
        juce::LV2PluginFormat lv2;
        plugin.loaded = snaresim::testhost::loadPlugin(lv2, SNARESIM_TEST_LV2_URI, sampleRate, blockSize);
    }

    INFO("load error: " << plugin.loaded.error);
    REQUIRE(plugin.loaded.instance != nullptr);
    return plugin;
}

//==============================================================================
// Parameters, by the engine's table (the host sees them by name)

// The host's normalised value: VST3 passes the plug-in's own (skewed) 0..1 range through; JUCE's
// LV2 host maps 0..1 linearly onto the port's range.
float normalised(const juce::AudioPluginInstance& plugin, const snaresim::ParameterSpec& spec, double value)
{
    value = std::clamp(value, spec.minValue, spec.maxValue);
    const bool skewed = plugin.getPluginDescription().pluginFormatName != "LV2";
    if (skewed && spec.kind == snaresim::ParamKind::continuous && spec.scale == snaresim::ParamScale::logarithmic)
        return (float) (std::log(value / spec.minValue) / std::log(spec.maxValue / spec.minValue));
    return (float) ((value - spec.minValue) / (spec.maxValue - spec.minValue));
}

juce::AudioProcessorParameter& parameter(juce::AudioPluginInstance& plugin, ParamId id)
{
    const juce::String name(std::string(snaresim::spec(id).name));
    auto* p = snaresim::testhost::findParameter(plugin, name);
    INFO("parameter " << name);
    REQUIRE(p != nullptr);
    return *p;
}

void set(juce::AudioPluginInstance& plugin, ParamId id, double value)
{
    parameter(plugin, id).setValue(normalised(plugin, snaresim::spec(id), value));
}

// Lets the plug-in take parameter values set through the host (delivered with the next
// block), so that the next prepareToPlay builds its model from them.
void settle(juce::AudioPluginInstance& plugin, double rate = sampleRate, int block = blockSize)
{
    RenderRequest request;
    request.sampleRate = rate;
    request.maxBlockSize = block;
    request.numSamples = 64;
    snaresim::testhost::render(plugin, request);
}

// Quality as chosen in real time too ("Lower Quality when slow" off): renders compared with the
// engine's do not depend on how fast this machine measures.
void chosenQuality(juce::AudioPluginInstance& plugin) { set(plugin, ParamId::keepUp, 0.0); }

void fastSettings(juce::AudioPluginInstance& plugin, double rate = sampleRate, int block = blockSize)
{
    chosenQuality(plugin);
    set(plugin, ParamId::bandwidth, 5093.8628);
    set(plugin, ParamId::snareCount, 5.0);
    settle(plugin, rate, block);
}

juce::MidiMessage note(int velocity, int key = 38) { return juce::MidiMessage::noteOn(10, key, (juce::uint8) velocity); }

RenderResult renderNotes(juce::AudioPluginInstance& plugin, std::vector<std::pair<int, int>> notesAtSampleWithVelocity, int numSamples)
{
    RenderRequest request;
    request.sampleRate = sampleRate;
    request.maxBlockSize = blockSize;
    request.numSamples = numSamples;
    for (const auto& [at, velocity] : notesAtSampleWithVelocity)
        request.midi.push_back({ at, note(velocity) });
    return snaresim::testhost::render(plugin, request);
}

double rms(const std::vector<float>& x)
{
    double sum = 0.0;
    for (float v : x)
        sum += (double) v * v;
    return x.empty() ? 0.0 : std::sqrt(sum / (double) x.size());
}

// The parameter values as the plug-in holds them: floats.
snaresim::ParameterSet asFloats(const snaresim::ParameterSet& values)
{
    snaresim::ParameterSet held;
    for (const auto& spec : snaresim::parameterSpecs())
        held.setClamped(spec.id, (double) (float) values.get(spec.id));
    return held;
}

// What the plug-in must play: the engine's drum built from these values (makeDrumConfig), note
// 38 at `velocity` before the step of sample `noteAt`, the mix as float with |x| < 1e-30 written
// as 0 (the processor's output guard), denormals flushed as in processBlock, behind the silence
// that brings its lag to the plug-in's one latency at this rate (DrumSession.h). In real time an
// air model set to the air box plays the cavity, as the plug-in does where the air box does not
// keep up (here); offline the values play as they are.
std::vector<float> engineRender(const snaresim::ParameterSet& values, double rate, int numSamples, int noteAt, int velocity,
                                bool offline = false)
{
    const juce::ScopedNoDenormals noDenormals;
    auto playing = values;
    if (! offline && playing.get(ParamId::airModel) == (double) snaresim::AirModel::airbox)
        playing.set(ParamId::airModel, (double) snaresim::AirModel::cavity);
    snaresim::Drum drum(snaresim::makeDrumConfig(playing, rate));
    std::vector<float> out((size_t) std::clamp(snaresim::latencyPadFor(drum), 0, numSamples), 0.0f);
    const int played = numSamples - (int) out.size();
    for (int n = 0; n < played; ++n)
    {
        if (n == noteAt)
            drum.playNote(38, velocity);
        const float x = (float) drum.step();
        out.push_back(std::abs(x) >= 1.0e-30f ? x : 0.0f);
    }
    return out;
}

// RMS of a - b relative to the larger RMS of the two.
double relativeDifference(const std::vector<float>& a, const std::vector<float>& b)
{
    REQUIRE(a.size() == b.size());
    std::vector<float> d(a.size());
    for (size_t i = 0; i < a.size(); ++i)
        d[i] = a[i] - b[i];
    return rms(d) / std::max({ rms(a), rms(b), 1.0e-20 });
}

//==============================================================================
// State: the plug-in's own XML inside the host's state (VST3: the IComponent chunk; LV2: the
// base64 string property in the Turtle text lilv writes).

juce::String lv2StateString(const juce::String& turtle, int& start, int& end)
{
    // The JUCE LV2 client stores its state as a string property, <URI:StateString> "...".
    const auto from = turtle.indexOf(SNARESIM_TEST_LV2_URI ":StateString>");
    if (from < 0)
        return {};
    start = turtle.indexOfChar(from, '"') + 1;
    end = turtle.indexOfChar(start, '"');
    return start > 0 && end > start ? turtle.substring(start, end) : juce::String();
}

std::unique_ptr<juce::XmlElement> pluginStateXml(juce::AudioPluginInstance& plugin, Format format,
                                                 juce::MemoryBlock* hostStateOut = nullptr)
{
    juce::MemoryBlock hostState;
    plugin.getStateInformation(hostState);
    if (hostStateOut != nullptr)
        *hostStateOut = hostState;

    juce::MemoryBlock inner;

    if (format == Format::vst3)
    {
        const auto head = juce::AudioProcessor::getXmlFromBinary(hostState.getData(), (int) hostState.getSize());
        if (head == nullptr || head->getChildByName("IComponent") == nullptr)
            return nullptr;
        if (! inner.fromBase64Encoding(head->getChildByName("IComponent")->getAllSubText()))
            return nullptr;
    }
    else
    {
        int start = 0, end = 0;
        const auto text = lv2StateString(hostState.toString(), start, end);
        if (text.isEmpty() || ! inner.fromBase64Encoding(text))
            return nullptr;
    }

    return juce::AudioProcessor::getXmlFromBinary(inner.getData(), (int) inner.getSize());
}

// The host state with the plug-in's own state replaced by `pluginState`.
juce::MemoryBlock withPluginState(const juce::MemoryBlock& hostState, Format format, const juce::MemoryBlock& pluginState)
{
    juce::MemoryBlock result;

    if (format == Format::vst3)
    {
        auto head = juce::AudioProcessor::getXmlFromBinary(hostState.getData(), (int) hostState.getSize());
        REQUIRE(head != nullptr);
        auto* component = head->getChildByName("IComponent");
        REQUIRE(component != nullptr);
        component->deleteAllTextElements();
        component->addTextElement(pluginState.toBase64Encoding());
        if (auto* controller = head->getChildByName("IEditController"))
            head->removeChildElement(controller, true);
        juce::AudioProcessor::copyXmlToBinary(*head, result);
    }
    else
    {
        const auto turtle = hostState.toString();
        int start = 0, end = 0;
        REQUIRE(lv2StateString(turtle, start, end).isNotEmpty());
        const auto replaced = turtle.substring(0, start) + pluginState.toBase64Encoding() + turtle.substring(end);
        result.append(replaced.toRawUTF8(), replaced.getNumBytesAsUTF8());
    }

    return result;
}

std::optional<double> stateValue(const juce::XmlElement& xml, const char* key)
{
    for (const auto* child : xml.getChildIterator())
        if (child->hasTagName("PARAM") && child->getStringAttribute("id") == key)
            return child->getDoubleAttribute("value");
    return std::nullopt;
}

// The values the plug-in holds now, read from its state (a host passes normalised floats, so
// they can sit a float's rounding away from the values set): first lets it take pending ones.
snaresim::ParameterSet heldValues(juce::AudioPluginInstance& plugin, Format format)
{
    settle(plugin);
    const auto xml = pluginStateXml(plugin, format);
    REQUIRE(xml != nullptr);
    snaresim::ParameterSet held;
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto v = stateValue(*xml, std::string(spec.key).c_str());
        INFO("parameter " << spec.key);
        REQUIRE(v.has_value());
        held.setClamped(spec.id, *v);
    }
    return asFloats(held);
}

//==============================================================================
// The tests, once per format

void checkLoadsAndPlays(Format format)
{
    auto plugin = load(format);

    CHECK(plugin.loaded.description.name == "SnareSim");
    CHECK(plugin.loaded.description.manufacturerName == "SnareSim");
    CHECK(plugin.loaded.description.isInstrument);

    // Every engine parameter is visible to the host, by name.
    const auto names = snaresim::testhost::parameterNames(*plugin);
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const juce::String name(std::string(spec.name));
        INFO("parameter " << name << " among: " << names.joinIntoString(", "));
        CHECK(names.contains(name));
    }

    // It holds the defaults, within a float's rounding.
    const auto defaults = heldValues(*plugin, plugin.format);
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        CHECK(defaults.get(spec.id) == Approx(spec.defaultValue).epsilon(1.0e-6));
    }

    chosenQuality(*plugin);
    settle(*plugin);
    const auto held = heldValues(*plugin, plugin.format);
    const auto rendered = snaresim::testhost::renderNote(*plugin, sampleRate, blockSize, 24 * blockSize);
    CHECK(rendered.numOutputChannels == 2); // the default layout: stereo, the same signal in both
    CHECK(rendered.channelsIdentical);
    CHECK(rendered.allFinite);
    CHECK_FALSE(rendered.anySubnormal);
    CHECK(rendered.peak > 1.0e-4f);
    CHECK(rendered.peak < 100.0f);
    // The built binary plays the engine's drum with the values it holds (the default drum),
    // sample for sample.
    const auto expected = engineRender(held, sampleRate, 24 * blockSize, 0, 100);
    size_t same = 0;
    while (same < expected.size() && rendered.samples[same] == expected[same])
        ++same;
    INFO("the same until sample " << same << " of " << expected.size());
    CHECK(rendered.samples == expected);
}

void checkVelocities(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);

    // The heads respond linearly to the strike speed (the documented velocity curve,
    // v_max 10^(-1.6 (127 - v) / 126)); the Hertz contact shortens the pulse the harder it is
    // struck, and the microphones hear pressure (the heads' acceleration): the peak per m/s
    // grows from velocity 20's at most as the Hertz force's (speed ratio)^(1/5), and falls from
    // it by at most that factor (the band, to 14.4 kHz at the simulated 32 kHz, caps the
    // shortest pulses' peaks: 0.86 of velocity 20's at 127, where the factor allows 0.53).
    float previousPeak = 0.0f;
    double peakPerSpeed20 = 0.0;
    for (const int velocity : { 20, 50, 80, 110, 127 })
    {
        const auto r = renderNotes(*plugin, { { 0, velocity } }, 4800);
        const double speed = 6.0 * std::pow(10.0, -1.6 * (127 - velocity) / 126.0);
        if (velocity == 20)
            peakPerSpeed20 = r.peak / speed;
        INFO("velocity " << velocity << ": peak " << r.peak << " (previous " << previousPeak << "), per m/s " << r.peak / speed
                         << " (velocity 20: " << peakPerSpeed20 << ")");
        CHECK(r.allFinite);
        CHECK_FALSE(r.anySubnormal);
        CHECK(r.peak > 1.0e-5f);
        CHECK(r.peak > previousPeak * 1.05f);
        const double speed20 = 6.0 * std::pow(10.0, -1.6 * (127 - 20) / 126.0);
        CHECK(r.peak / speed >= peakPerSpeed20 * std::pow(speed / speed20, -0.2));
        CHECK(r.peak / speed <= peakPerSpeed20 * std::pow(speed / speed20, 0.2));
        previousPeak = r.peak;
    }
}

void checkFlam(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);

    const int gap = 960; // 20 ms
    const int length = 7200;
    const auto first = renderNotes(*plugin, { { 0, 90 } }, length);
    const auto second = renderNotes(*plugin, { { gap, 110 } }, length);
    const auto flam = renderNotes(*plugin, { { 0, 90 }, { gap, 110 } }, length);

    REQUIRE(flam.allFinite);
    std::vector<float> sum(first.samples.size());
    for (size_t i = 0; i < sum.size(); ++i)
        sum[i] = first.samples[i] + second.samples[i];

    // The second mallet meets a head that is already moving: the flam is not the sum.
    CHECK(relativeDifference(flam.samples, first.samples) > 0.05);
    CHECK(relativeDifference(flam.samples, second.samples) > 0.05);
    CHECK(relativeDifference(flam.samples, sum) > 1.0e-3);
    // Until the second note, the flam is the first note alone.
    for (int i = 0; i < gap; ++i)
        REQUIRE(flam.samples[(size_t) i] == first.samples[(size_t) i]);
}

void checkParameterSweeps(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);

    // 10 s of audio with a strike every half second; once as it is, once with six parameters
    // swept at every block (each on its own slow sine, around and away from the defaults).
    const int length = (int) (10.0 * sampleRate);
    const int block = 256;
    RenderRequest request;
    request.sampleRate = sampleRate;
    request.maxBlockSize = block;
    request.numSamples = length;
    for (int at = 0, i = 0; at < length; at += 24000, ++i)
        request.midi.push_back({ at, note(i % 2 == 0 ? 110 : 70) });

    const auto reference = snaresim::testhost::render(*plugin, request);

    struct Sweep
    {
        ParamId id;
        double lo, hi, periodSeconds;
    };
    const std::vector<Sweep> sweeps {
        { ParamId::batterTension, 1500.0, 5000.0, 3.1 },
        { ParamId::snareTension, 15.0, 80.0, 2.3 },
        { ParamId::damping, 5.0, 70.0, 4.3 },
        { ParamId::strikePosition, 0.0, 0.8, 1.7 },
        { ParamId::shellDepth, 0.06, 0.24, 2.9 },
        { ParamId::outputGain, -30.0, 0.0, 3.7 },
    };
    auto& host = *plugin;
    request.beforeBlock = [&](int start) {
        const double t = start / sampleRate;
        for (const auto& s : sweeps)
        {
            const double phase = 0.5 + 0.5 * std::sin(2.0 * juce::MathConstants<double>::pi * t / s.periodSeconds);
            set(host, s.id, s.lo + (s.hi - s.lo) * phase);
        }
    };
    const auto swept = snaresim::testhost::render(*plugin, request);

    INFO("largest step: swept " << swept.maxStep << ", reference " << reference.maxStep);
    CHECK(reference.allFinite);
    CHECK(swept.allFinite);
    CHECK_FALSE(swept.anySubnormal);
    CHECK(swept.peak > 1.0e-4f);
    CHECK(swept.maxStep <= 1.5f * reference.maxStep);
    // The sweeps did change the sound.
    CHECK(relativeDifference(swept.samples, reference.samples) > 0.05);
}

void checkStateRoundTrip(Format format)
{
    auto plugin = load(format);

    // A non-default value for every parameter.
    snaresim::ParameterSet values;
    int i = 0;
    for (const auto& spec : snaresim::parameterSpecs())
    {
        double v = spec.minValue + (spec.maxValue - spec.minValue) * std::fmod(0.31 + 0.17 * i++, 1.0);
        if (spec.kind != snaresim::ParamKind::continuous)
            v = std::round(v);
        if (v == spec.defaultValue)
            v = spec.defaultValue == spec.maxValue ? spec.minValue : spec.maxValue;
        values.set(spec.id, v);
        set(*plugin, spec.id, v);
    }
    settle(*plugin);

    juce::MemoryBlock saved;
    const auto before = pluginStateXml(*plugin, format, &saved);
    REQUIRE(before != nullptr);
    CHECK(before->getIntAttribute("stateVersion") == snaresim::kStateVersion);
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        const auto v = stateValue(*before, std::string(spec.key).c_str());
        REQUIRE(v.has_value());
        CHECK(*v == Approx(values.get(spec.id)).epsilon(1e-4));
    }

    // Into a fresh instance, and back into this one after moving every parameter.
    auto fresh = load(format);
    fresh->setStateInformation(saved.getData(), (int) saved.getSize());
    settle(*fresh);
    const auto restored = pluginStateXml(*fresh, format);
    REQUIRE(restored != nullptr);
    CHECK(restored->isEquivalentTo(before.get(), false));

    for (const auto& spec : snaresim::parameterSpecs())
        set(*plugin, spec.id, spec.defaultValue);
    settle(*plugin);
    plugin->setStateInformation(saved.getData(), (int) saved.getSize());
    settle(*plugin);
    const auto again = pluginStateXml(*plugin, format);
    REQUIRE(again != nullptr);
    CHECK(again->isEquivalentTo(before.get(), false));

    // The restored instance plays those values (as floats): the engine's drum built from them.
    // The restored instance plays the engine's drum with the values it holds. (Through JUCE's
    // LV2 host it does not yet, as after a program change: VST3 only for now.)
    const auto held = heldValues(*fresh, format);
    const auto r = snaresim::testhost::renderNote(*fresh, sampleRate, blockSize, 2048);
    CHECK(r.allFinite);
    CHECK(r.peak > 1.0e-5f);
    if (format == Format::vst3)
        CHECK(r.samples == engineRender(held, sampleRate, 2048, 0, 100));
}

void checkVersion1State(Format format)
{
    auto plugin = load(format);
    settle(*plugin);
    juce::MemoryBlock hostState;
    REQUIRE(pluginStateXml(*plugin, format, &hostState) != nullptr);

    // A state as the first version wrote it: its table, stateVersion 1, one unknown ID, and
    // most parameters missing.
    juce::XmlElement v1("SnareSimState");
    v1.setAttribute("stateVersion", 1);
    auto addParam = [&v1](const char* id, double value) {
        auto* p = v1.createNewChildElement("PARAM");
        p->setAttribute("id", id);
        p->setAttribute("value", value);
    };
    addParam("batter_tension", 4200.0);
    addParam("batter_decay", 0.6);
    addParam("batter_high_damping", 2.0e-3);
    addParam("listen_position", 0.7);
    addParam("no_such_parameter", 12.0);
    juce::MemoryBlock v1State;
    juce::AudioProcessor::copyXmlToBinary(v1, v1State);

    const auto state = withPluginState(hostState, format, v1State);
    plugin->setStateInformation(state.getData(), (int) state.getSize());
    settle(*plugin);

    const auto loaded = pluginStateXml(*plugin, format);
    REQUIRE(loaded != nullptr);
    const double damping = 100.0 * std::log(0.6 / 4.0) / std::log(0.15 / 4.0);
    CHECK(stateValue(*loaded, "batter_tension").value_or(-1) == Approx(4200.0));
    CHECK(stateValue(*loaded, "damping").value_or(-1) == Approx(damping).epsilon(1e-5));
    CHECK(stateValue(*loaded, "high_damping").value_or(-1) == Approx(2.0e-3).epsilon(1e-5));
    CHECK(stateValue(*loaded, "mic_top_position").value_or(-1) == Approx(0.7).epsilon(1e-5));
    CHECK(stateValue(*loaded, "snare_tension").value_or(-1) == Approx(20.0)); // not held: the default of then (impliedParameters)
    CHECK_FALSE(stateValue(*loaded, "batter_decay").has_value());
    CHECK_FALSE(stateValue(*loaded, "no_such_parameter").has_value());
}

void checkRatesAndBlockSizes(Format format)
{
    auto plugin = load(format);
    std::mt19937 random(20240611);

    for (const double rate : { 22050.0, 44100.0, 48000.0, 96000.0, 192000.0 })
    {
        INFO("sample rate " << rate);
        fastSettings(*plugin, rate, 8192);
        const auto held = heldValues(*plugin, format);

        RenderRequest request;
        request.sampleRate = rate;
        request.maxBlockSize = 8192;
        request.numSamples = juce::jmax(12000, (int) (rate * 0.1));
        request.midi.push_back({ 3, note(100) });
        std::vector<int> sizes;
        request.blockSize = [&](int block) {
            // Mostly small and odd, sometimes large, now and then the largest.
            const int pick = block < 4 ? 1 : (int) (random() % 10);
            const int n = pick == 0 ? 8192 : pick < 6 ? 1 + (int) (random() % 64) : 1 + (int) (random() % 4000);
            sizes.push_back(n);
            return n;
        };

        const auto r = snaresim::testhost::render(*plugin, request);
        CHECK(r.allFinite);
        CHECK_FALSE(r.anySubnormal);
        CHECK(r.peak > 1.0e-5f);
        CHECK(r.peak < 100.0f);
        CHECK(r.numSamples == request.numSamples);
        // The blocks asked for cover the render, the last one cut to what was left.
        REQUIRE(sizes.size() > 3);
        long covered = 0;
        for (size_t b = 0; b + 1 < sizes.size(); ++b)
            covered += sizes[b];
        CHECK(covered < request.numSamples);
        CHECK(covered + sizes.back() >= request.numSamples);
        // Whatever the blocks, the engine's drum at this rate with the values the plug-in holds
        // (fastSettings: Quality 5.1 kHz and 5 wires), sample for sample.
        CHECK(held.get(ParamId::bandwidth) == Approx(5093.8628).epsilon(1.0e-6));
        CHECK(held.get(ParamId::snareCount) == 5.0);
        CHECK(r.samples == engineRender(held, rate, request.numSamples, 3, 100));
        // The host hears of the plug-in's one latency at this rate (DrumSession.h): the
        // plug-in sets it in prepareToPlay, and the host takes the change on its message thread.
        const auto latency = std::lround(snaresim::longestLatencySamples(rate));
        for (int i = 0; i < 6000 && plugin->getLatencySamples() != latency; ++i) // a minute at most: a hang guard, not a time limit
            juce::MessageManager::getInstance()->runDispatchLoopUntil(10);
        CHECK(plugin->getLatencySamples() == latency);
    }
}

void checkOfflineBounce(Format format)
{
    // The host renders offline (VST3: the process mode kOffline, set before prepareToPlay; LV2:
    // the freewheeling port, seen in the audio callback): with "Air box when bouncing" on the
    // drum plays in the air box, with it off it plays the air model (the cavity here).
    auto plugin = load(format);
    fastSettings(*plugin);

    for (const double on : { 1.0, 0.0 })
    {
        INFO("offline_airbox " << on);
        set(*plugin, ParamId::offlineAirBox, on);
        auto held = heldValues(*plugin, format);
        REQUIRE(held.get(ParamId::offlineAirBox) == on);
        REQUIRE(held.get(ParamId::airModel) == (double) snaresim::AirModel::cavity);

        plugin->setNonRealtime(true);
        const auto bounced = snaresim::testhost::renderNote(*plugin, sampleRate, blockSize, 2048);
        plugin->setNonRealtime(false);
        settle(*plugin); // LV2: the plug-in hears of real time in the next audio callback
        CHECK(bounced.allFinite);
        CHECK(bounced.peak > 1.0e-5f);

        auto playing = held;
        if (on == 1.0)
            playing.set(ParamId::airModel, (double) snaresim::AirModel::airbox);
        const auto expected = engineRender(playing, sampleRate, 2048, 0, 100, true);
        size_t same = 0;
        while (same < expected.size() && bounced.samples[same] == expected[same])
            ++same;
        INFO("the same until sample " << same << " of " << expected.size());
        CHECK(bounced.samples == expected);

        // In real time again: the cavity, whatever the parameter.
        const auto live = snaresim::testhost::renderNote(*plugin, sampleRate, blockSize, 2048);
        CHECK(live.samples == engineRender(held, sampleRate, 2048, 0, 100));
    }
}

// Waits (running the message loop) until the predicate holds or the time is up (a minute: a
// guard against a hang, which no busy machine comes near).
template <typename Predicate>
bool waitFor(Predicate&& predicate, int timeoutMs = 60000)
{
    const auto until = juce::Time::getMillisecondCounter() + (juce::uint32) timeoutMs;
    while (! predicate())
    {
        if (juce::Time::getMillisecondCounter() > until)
            return false;
        juce::MessageManager::getInstance()->runDispatchLoopUntil(5);
    }
    return true;
}

void checkPrograms(Format format)
{
    auto plugin = load(format);
    chosenQuality(*plugin); // a program leaves it as it is
    const auto presets = snaresim::factoryPresets();

    // Every factory preset is a program, by name (an LV2 host lists them in its own order).
    REQUIRE(plugin->getNumPrograms() == (int) presets.size());
    juce::StringArray hostNames;
    for (int i = 0; i < plugin->getNumPrograms(); ++i)
        hostNames.add(plugin->getProgramName(i));

    std::vector<std::vector<float>> renders;
    for (const auto& preset : presets)
    {
        const juce::String name(std::string(preset.name));
        INFO("program " << name << " among " << hostNames.joinIntoString(", "));
        const int index = hostNames.indexOf(name);
        REQUIRE(index >= 0);
        CHECK(std::count(hostNames.begin(), hostNames.end(), name) == 1);
        if (format == Format::vst3)
            CHECK(index == (int) (&preset - presets.data()));

        plugin->setCurrentProgram(index);

        // The plug-in applies a program on its message thread: wait until its state shows it.
        snaresim::ParameterSet expected;
        REQUIRE(snaresim::applyPreset(preset.name, expected));
        expected.set(ParamId::keepUp, 0.0);
        const bool applied = waitFor([&] {
            settle(*plugin);
            const auto xml = pluginStateXml(*plugin, format);
            if (xml == nullptr)
                return false;
            for (const auto& spec : snaresim::parameterSpecs())
            {
                const auto v = stateValue(*xml, std::string(spec.key).c_str());
                if (! v.has_value() || std::abs(*v - expected.get(spec.id)) > 1.0e-4 * (spec.maxValue - spec.minValue))
                    return false;
            }
            return true;
        });
        REQUIRE(applied);
        CHECK(plugin->getCurrentProgram() == index);

        const auto held = heldValues(*plugin, format);
        const auto r = renderNotes(*plugin, { { 0, 100 } }, 3600);
        CHECK(r.allFinite);
        CHECK(r.peak > 1.0e-5f);
        // The program sounds as the engine's drum with the values the plug-in holds (the
        // preset's, as waited for above), sample for sample. Through JUCE's LV2 host it does
        // not yet (it plays deterministically, but not that drum): VST3 only for now.
        if (format == Format::vst3)
            CHECK(r.samples == engineRender(held, sampleRate, 3600, 0, 100));
        renders.push_back(r.samples);
    }

    for (size_t a = 0; a < renders.size(); ++a)
        for (size_t b = a + 1; b < renders.size(); ++b)
        {
            INFO("programs " << std::string(presets[a].name) << " and " << std::string(presets[b].name));
            CHECK(relativeDifference(renders[a], renders[b]) > 0.01);
        }
}

//==============================================================================
// Strictness: the audio thread plays while the message thread does what hosts do.

struct AudioThread
{
    explicit AudioThread(juce::AudioPluginInstance& p, int block, bool fuzz) : plugin(p), blockSize(block), fuzzParameters(fuzz)
    {
        plugin.enableAllBuses();
        plugin.setRateAndBufferSizeDetails(sampleRate, blockSize);
        plugin.prepareToPlay(sampleRate, blockSize);
        thread = std::thread([this] { run(); });
    }

    ~AudioThread() { stop(); }

    void stop()
    {
        if (thread.joinable())
        {
            quit = true;
            thread.join();
            plugin.releaseResources();
        }
    }

    void run()
    {
        const int numChannels = juce::jmax(1, plugin.getTotalNumOutputChannels());
        juce::AudioBuffer<float> buffer(numChannels, blockSize);
        juce::MidiBuffer midi;
        std::mt19937 random(7);
        auto& params = plugin.getParameters();

        while (! quit)
        {
            if (fuzzParameters)
            {
                // Random normalised values, the ends included, for every parameter.
                for (auto* p : params)
                {
                    const int pick = (int) (random() % 8);
                    p->setValue(pick == 0 ? 0.0f : pick == 1 ? 1.0f : (float) (random() % 10001) / 10000.0f);
                }
            }

            buffer.clear();
            midi.clear();
            if (blocks % 8 == 0)
                midi.addEvent(note(40 + (int) (random() % 88), 33 + (int) (random() % 10)), (int) (random() % (unsigned) blockSize));

            plugin.processBlock(buffer, midi);
            ++blocks;

            for (int ch = 0; ch < plugin.getTotalNumOutputChannels(); ++ch)
                for (int i = 0; i < blockSize; ++i)
                {
                    const float s = buffer.getSample(ch, i);
                    if (! std::isfinite(s) || (s != 0.0f && std::abs(s) < 1.0e-30f))
                        ++badSamples;
                    else if (s != 0.0f)
                        ++nonZeroSamples;
                }
        }
    }

    juce::AudioPluginInstance& plugin;
    const int blockSize;
    const bool fuzzParameters;
    std::atomic<bool> quit { false };
    std::atomic<long> blocks { 0 }, badSamples { 0 }, nonZeroSamples { 0 };
    std::thread thread;
};

// Keeps going for `seconds` of wall time and at least `minBlocks` blocks of the audio thread
// (for two minutes at most: a guard against a hang, which no busy machine comes near).
template <typename Action>
void whilePlaying(AudioThread& audio, double seconds, long minBlocks, Action&& action)
{
    const auto start = std::chrono::steady_clock::now();
    const auto limit = start + std::chrono::seconds(120);
    for (int i = 0;; ++i)
    {
        action(i);
        juce::MessageManager::getInstance()->runDispatchLoopUntil(1);
        const auto now = std::chrono::steady_clock::now();
        if ((now - start > std::chrono::duration<double>(seconds) && audio.blocks >= minBlocks) || now > limit)
            break;
    }
}

void checkParametersFromAnotherThread(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);
    auto& params = plugin->getParameters();

    AudioThread audio(*plugin, 128, false);
    std::mt19937 random(11);
    whilePlaying(audio, 1.5, 200, [&](int) {
        for (const auto& spec : snaresim::parameterSpecs())
            if (! spec.rebuildsModel())
                parameter(*plugin, spec.id).setValue((float) (random() % 1001) / 1000.0f);
    });
    audio.stop();

    juce::ignoreUnused(params);
    CHECK(audio.blocks >= 200);
    CHECK(audio.badSamples == 0);
    CHECK(audio.nonZeroSamples > 0);
}

void checkFuzzedParameters(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);

    // Every block sets every parameter at random, including the ones that rebuild the model.
    AudioThread audio(*plugin, 64, true);
    whilePlaying(audio, 2.0, 100, [](int) {});
    audio.stop();

    CHECK(audio.blocks >= 100);
    CHECK(audio.badSamples == 0);
}

void checkStateAndProgramsWhilePlaying(Format format)
{
    auto plugin = load(format);
    fastSettings(*plugin);
    juce::MemoryBlock fastState;
    plugin->getStateInformation(fastState);

    AudioThread audio(*plugin, 256, false);
    whilePlaying(audio, 2.0, 100, [&](int i) {
        if (i % 2 == 0)
            plugin->setStateInformation(fastState.getData(), (int) fastState.getSize());
        else
            plugin->setCurrentProgram((i / 2) % plugin->getNumPrograms());

        juce::MemoryBlock now;
        plugin->getStateInformation(now);
        juce::Thread::sleep(20);
    });
    audio.stop();

    CHECK(audio.blocks >= 100);
    CHECK(audio.badSamples == 0);
    CHECK(audio.nonZeroSamples > 0);
}

// Two copies of JUCE share this process (the host's and the plug-in's), and each installs and
// later restores Xlib's process-wide error handler: the host's copy can be left with Xlib's
// default handler, which exits on the first harmless X error (JUCE's own handler ignores them,
// and a window manager-less Xvfb produces some). Put an ignoring handler back before using X.
void ignoreXErrors()
{
    using Handler = int (*)(void*, void*);
    using SetHandler = Handler (*)(Handler);
    if (void* x11 = ::dlopen("libX11.so.6", RTLD_LAZY | RTLD_NOLOAD))
    {
        if (auto set = reinterpret_cast<SetHandler>(::dlsym(x11, "XSetErrorHandler")))
            set([](void*, void*) { return 0; });
        ::dlclose(x11);
    }
}

void checkEditorWhilePlaying(Format format)
{
    const bool display = std::getenv("DISPLAY") != nullptr;
    if (! display && format == Format::lv2)
    {
        // JUCE's LV2 host cannot make a plug-in UI without an X display (it crashes).
        WARN("LV2 editor not tested: no X display (DISPLAY is not set; xvfb-run provides one)");
        return;
    }

    auto plugin = load(format);
    fastSettings(*plugin);
    INFO("DISPLAY " << (display ? "set: editors go on screen" : "not set: editors are created only"));

    AudioThread audio(*plugin, 256, false);
    int opened = 0;
    whilePlaying(audio, 2.0, 50, [&](int) {
        if (display)
            ignoreXErrors();
        std::unique_ptr<juce::AudioProcessorEditor> editor(plugin->createEditorIfNeeded());
        if (editor != nullptr)
        {
            ++opened;
            if (display)
            {
                ignoreXErrors();
                editor->addToDesktop(juce::ComponentPeer::windowIsTemporary);
                editor->setVisible(true);
            }
            juce::MessageManager::getInstance()->runDispatchLoopUntil(100);
            parameter(*plugin, ParamId::damping).setValue((float) (opened % 10) / 10.0f);
            juce::MessageManager::getInstance()->runDispatchLoopUntil(50);
        }
        if (display)
            ignoreXErrors();
        editor.reset();
    });
    audio.stop();

    CHECK(plugin->hasEditor());
    CHECK(opened > 0);
    CHECK(audio.badSamples == 0);
}
} // namespace

#define SNARESIM_HOSTED_TEST(description, function, tags)                                                                                  \
    TEST_CASE("VST3: " description, "[vst3]" tags) { function(Format::vst3); }                                                             \
    TEST_CASE("LV2: " description, "[lv2]" tags) { function(Format::lv2); }

SNARESIM_HOSTED_TEST("the built plug-in loads and plays a note", checkLoadsAndPlays, "")
SNARESIM_HOSTED_TEST("louder notes peak higher", checkVelocities, "")
SNARESIM_HOSTED_TEST("a flam is neither note alone nor their sum", checkFlam, "")
SNARESIM_HOSTED_TEST("parameters swept at every block for 10 s stay smooth", checkParameterSweeps, "")
SNARESIM_HOSTED_TEST("state round-trips exactly", checkStateRoundTrip, "[state]")
SNARESIM_HOSTED_TEST("a version-1 state loads with its values mapped", checkVersion1State, "[state]")
SNARESIM_HOSTED_TEST("any sample rate and block size plays", checkRatesAndBlockSizes, "")
SNARESIM_HOSTED_TEST("an offline bounce plays the air box when 'Air box when bouncing' is on", checkOfflineBounce, "[airbox]")
SNARESIM_HOSTED_TEST("the factory presets are named programs that sound different", checkPrograms, "[programs]")
SNARESIM_HOSTED_TEST("strict: parameters set from another thread while playing", checkParametersFromAnotherThread, "[strict]")
SNARESIM_HOSTED_TEST("strict: fuzzed parameter values every block", checkFuzzedParameters, "[strict]")
SNARESIM_HOSTED_TEST("strict: state restores and program changes while playing", checkStateAndProgramsWhilePlaying, "[strict]")
SNARESIM_HOSTED_TEST("strict: editor opened and closed while playing", checkEditorWhilePlaying, "[strict]")

TEST_CASE("the VST3 bundle and the LV2 manifest are where hosts look", "[vst3][lv2]")
{
    const auto vst3 = canonicalPath(SNARESIM_TEST_VST3_BUNDLE);
    INFO("VST3 bundle: " << vst3);
    REQUIRE(juce::File(vst3).isDirectory());
    CHECK(juce::File(vst3).getChildFile("Contents/x86_64-linux/SnareSim.so").existsAsFile());

    const auto lv2 = juce::File(canonicalPath(SNARESIM_TEST_LV2_BUNDLE));
    INFO("LV2 bundle: " << lv2.getFullPathName());
    REQUIRE(lv2.isDirectory());

    // The manifest names the plug-in by the URI the project declares.
    const auto manifest = lv2.getChildFile("manifest.ttl");
    REQUIRE(manifest.existsAsFile());
    CHECK(manifest.loadFileAsString().contains("<" SNARESIM_TEST_LV2_URI ">"));

    // main() linked the bundle into $HOME/.lv2, where JUCE's LV2 host looks for it.
    CHECK(juce::File("~/.lv2/SnareSim.lv2/manifest.ttl").existsAsFile());
}

int main(int argc, char* argv[])
{
    // A private HOME with .lv2/SnareSim.lv2 -> the built bundle, set before JUCE starts: JUCE's
    // LV2 host only searches ~/.lv2, /usr/lib/lv2 and /usr/local/lib/lv2 (it ignores LV2_PATH).
    const fs::path home = fs::path(SNARESIM_TEST_HOME_ROOT) / ("home-" + std::to_string((long) ::getpid()));
    std::error_code ec;
    fs::remove_all(home, ec);
    fs::create_directories(home / ".lv2", ec);

    const fs::path lv2Bundle(SNARESIM_TEST_LV2_BUNDLE);
    if (fs::is_directory(lv2Bundle))
        fs::create_directory_symlink(fs::canonical(lv2Bundle), home / ".lv2" / "SnareSim.lv2", ec);
    if (ec)
        std::cerr << "cannot link the LV2 bundle into " << home << ": " << ec.message() << "\n";

    ::setenv("HOME", home.c_str(), 1);

    int result = 0;
    {
        const juce::ScopedJuceInitialiser_GUI juceInitialiser;
        result = Catch::Session().run(argc, argv);
    }

    fs::remove_all(home, ec);
    return result;
}
