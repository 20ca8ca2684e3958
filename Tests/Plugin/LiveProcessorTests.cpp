// The processor's live behaviour, in-process: MIDI handling, live parameters, background
// model swaps, programs, old states, the editor's feeds (snapshots, meters), the output guard
// and threads.

#include <catch2/catch.hpp>

#include "Drum.h"
#include "PluginState.h"
#include "PresetFileActions.h"
#include "Presets.h"
#include "ProcessorTestHelpers.h"

#include <atomic>
#include <chrono>
#include <functional>
#include <iostream>
#include <limits>
#include <random>
#include <thread>

using namespace snaresim::testing;
using snaresim::ParamId;

namespace
{
// Processes silent blocks (letting the background thread work) until the processor has
// installed `swaps` models in all, or the time is up.
bool waitForModelSwaps(SnareSimAudioProcessor& proc, int swaps, int blockSize = 256, double timeoutSeconds = 30.0)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    while (proc.getModelSwapCount() < swaps)
    {
        if (std::chrono::steady_clock::now() > until)
            return false;
        render(proc, blockSize, blockSize);
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return true;
}

// A bit more than the crossfade.
constexpr int fadeSamples = 2048;
} // namespace

TEST_CASE("a note inside a block starts on its own sample", "[processor][midi]")
{
    // The same note at absolute sample 300, rendered in blocks of 64 and of 1000: identical.
    auto renderWith = [](int blockSize) {
        SnareSimAudioProcessor proc;
        fastSettings(proc);
        prepare(proc, 48000.0, blockSize);
        return render(proc, blockSize, 3000, { { 300, note(100) } });
    };

    const auto a = renderWith(64);
    const auto b = renderWith(1000);
    REQUIRE(a.samples.size() == b.samples.size());
    CHECK(a.samples == b.samples);
    CHECK(a.peakFrom(0) > 1.0e-4f);
    for (int i = 0; i < 300; ++i)
        REQUIRE(a.samples[(size_t) i] == 0.0f);
    CHECK(a.peakFrom(300) > 0.0f);
    // Exactly the engine's drum with the note played before the step of sample 300.
    SnareSimAudioProcessor settings;
    fastSettings(settings);
    CHECK(a.samples == engineRender(settings.currentParameters(), 48000.0, 3000, { { 300, 38, 100 } }));
}

TEST_CASE("note-offs and all-notes-off leave the drum ringing, and all-sound-off silences it", "[processor][midi]")
{
    auto renderWith = [](std::vector<Event> extra) {
        SnareSimAudioProcessor proc;
        fastSettings(proc);
        prepare(proc, 48000.0, 256);
        extra.push_back({ 0, note(110) });
        return render(proc, 256, 4800, extra);
    };

    const auto plain = renderWith({});
    const auto offs = renderWith({ { 100, juce::MidiMessage::noteOff(10, 38) },
                                   { 500, juce::MidiMessage::allNotesOff(10) },
                                   { 700, juce::MidiMessage::controllerEvent(10, 121, 0) } });
    CHECK(offs.samples == plain.samples);

    const auto silenced = renderWith({ { 1000, juce::MidiMessage::allSoundOff(10) } });
    CHECK(silenced.peak > 1.0e-4f);
    CHECK(silenced.peakFrom(1000) == 0.0f);

    // A note after all-sound-off plays again.
    const auto again = renderWith({ { 1000, juce::MidiMessage::allSoundOff(10) }, { 2000, note(100) } });
    CHECK(again.peakFrom(2000) > 1.0e-4f);
}

TEST_CASE("notes never reset the drum: a roll builds on the ringing head", "[processor][midi]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    const auto single = render(proc, 256, 4800, { { 0, note(100) } });

    SnareSimAudioProcessor rollProc;
    fastSettings(rollProc);
    prepare(rollProc, 48000.0, 256);
    // Five strikes 10 ms apart, more than the four mallets.
    const auto roll =
        render(rollProc, 256, 4800, { { 0, note(100) }, { 480, note(100) }, { 960, note(100) }, { 1440, note(100) }, { 1920, note(100) } });
    CHECK(roll.allFinite);
    // Until the second strike the roll is the single note.
    for (int i = 0; i < 480; ++i)
        REQUIRE(roll.samples[(size_t) i] == single.samples[(size_t) i]);
    CHECK(rms(roll.samples, 480) > rms(single.samples, 480));
}

TEST_CASE("continuous parameters apply live and smoothly while the drum rings", "[processor][live]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    const int swaps = proc.getModelSwapCount();

    render(proc, 256, 2400, { { 0, note(110) } });
    const double sigma0Before = proc.getDrum()->config().batter.sigma0_per_s;
    const double tensionBefore = proc.getDrum()->config().batter.tension_N_per_m;

    set(proc, ParamId::damping, 80.0);
    set(proc, ParamId::batterTension, 5000.0);

    // A third of the way through the 30 ms linear ramp (480 of 1440 samples) the damping is a
    // third of the way to its target, and sigma0 follows from it; after the ramp, at the targets.
    render(proc, 32, 480);
    const double sigma0Mid = proc.getDrum()->config().batter.sigma0_per_s;
    CHECK(sigma0Mid > sigma0Before);
    snaresim::ParameterSet third = proc.currentParameters();
    const double dampingBefore = spec(ParamId::damping).defaultValue;
    third.set(ParamId::damping, dampingBefore + (third.get(ParamId::damping) - dampingBefore) * 480.0 / 1440.0);
    CHECK(sigma0Mid == Approx(snaresim::mapParameters(third, 48000.0).batter.sigma0_per_s).epsilon(1.0e-9));

    render(proc, 256, 2048);
    const auto target = snaresim::mapParameters(proc.currentParameters(), 48000.0);
    CHECK(proc.getDrum()->config().batter.sigma0_per_s == Approx(target.batter.sigma0_per_s));
    CHECK(sigma0Mid < target.batter.sigma0_per_s);
    CHECK(proc.getDrum()->config().batter.tension_N_per_m == Approx(5000.0));
    CHECK(proc.getDrum()->config().batter.tension_N_per_m != tensionBefore);

    // No new model was needed.
    CHECK(proc.getModelSwapCount() == swaps);

    // Toggles apply at once.
    set(proc, ParamId::carryFollows, 1.0);
    render(proc, 256, 256);
    CHECK(proc.getDrum()->config().carry.tension_N_per_m == Approx(std::clamp(5000.0 * 2060.0 / 3050.0, 800.0, 5000.0)));

    // The air model is another model (ChangeNeeds::newModel): built in the background.
    set(proc, ParamId::airModel, 0.0);
    REQUIRE(waitForModelSwaps(proc, swaps + 1));
    CHECK(proc.getDrum()->config().cavity.model == snaresim::AirModel::none);
    CHECK(proc.getDrum()->config().carry.tension_N_per_m == Approx(std::clamp(5000.0 * 2060.0 / 3050.0, 800.0, 5000.0)));
}

TEST_CASE("damping raised while ringing shortens the ring", "[processor][live]")
{
    auto tail = [](bool muffle) {
        SnareSimAudioProcessor proc;
        fastSettings(proc);
        prepare(proc, 48000.0, 256);
        const auto r = render(proc, 256, 24000, { { 0, note(110) } }, [&](int start) {
            if (muffle && start == 4864)
                set(proc, ParamId::damping, 100.0);
        });
        return rms(r.samples, 16000, 24000);
    };

    CHECK(tail(true) < 0.5 * tail(false));
}

TEST_CASE("snare_count and Quality rebuild the model in the background and crossfade", "[processor][model]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    const int swaps = proc.getModelSwapCount();
    REQUIRE(proc.getDrum()->config().snares.count == 5);

    const auto strike = render(proc, 256, 2400, { { 0, note(110) } });

    set(proc, ParamId::snareCount, 8.0);
    set(proc, ParamId::bandwidth, 6000.0);
    std::vector<float> during;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (proc.getModelSwapCount() == swaps && std::chrono::steady_clock::now() < until)
    {
        const auto r = render(proc, 256, 256);
        during.insert(during.end(), r.samples.begin(), r.samples.end());
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    REQUIRE(proc.getModelSwapCount() == swaps + 1);

    const auto fade = render(proc, 32, fadeSamples);
    CHECK(fade.allFinite);
    // The old drum fades out over ~20 ms: no jump larger than the strike made, from the ring
    // before the change through the crossfade.
    during.insert(during.end(), fade.samples.begin(), fade.samples.end());
    float maxStep = 0.0f;
    for (size_t i = 1; i < during.size(); ++i)
        maxStep = std::max(maxStep, std::abs(during[i] - during[i - 1]));
    CHECK(maxStep <= strike.maxStep);
    CHECK(rms(during, 0, 256) > 1.0e-4); // it was ringing when the new model came
    CHECK(proc.getDrum()->config().snares.count == 8);
    CHECK(proc.getDrum()->config().batter.gridCoarseness == Approx(snaresim::gridCoarsenessFor(6000.0)));
    CHECK_FALSE(proc.usedFallbackParameters());

    // The new model plays: silent since it came, it sounds as a new drum of 8 wires at
    // Quality 6 kHz would.
    const auto after = render(proc, 256, 4800, { { 0, note(110) } });
    CHECK(after.allFinite);
    CHECK(after.peak > 1.0e-4f);
    CHECK(proc.getModelSwapCount() == swaps + 1);
    CHECK(after.samples == engineRender(proc.currentParameters(), 48000.0, 4800, { { 0, 38, 110 } }));
}

TEST_CASE("a new sample rate in prepareToPlay rebuilds the drum at that rate", "[processor][model]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    for (const double rate : { 22050.0, 44100.0, 48000.0, 96000.0, 192000.0, 48000.0 })
    {
        INFO("sample rate " << rate);
        prepare(proc, rate, 512);
        REQUIRE(proc.getDrum() != nullptr);
        CHECK(proc.getDrum()->sampleRate() == rate);
        const auto r = render(proc, 512, (int) (rate * 0.03), { { 5, note(100) } });
        CHECK(r.allFinite);
        CHECK_FALSE(r.anySubnormal);
        CHECK(r.peak > 1.0e-5f);
        // A new drum at this rate: the engine's, sample for sample.
        CHECK(r.samples == engineRender(proc.currentParameters(), rate, (int) (rate * 0.03), { { 5, 38, 100 } }));
    }

    // Preparing again at the same rate keeps the drum.
    const auto* drum = proc.getDrum();
    const int swaps = proc.getModelSwapCount();
    prepare(proc, 48000.0, 64);
    CHECK(proc.getDrum() == drum);
    CHECK(proc.getModelSwapCount() == swaps);
}

TEST_CASE("snares off / on notes hold until the snares_engaged parameter changes", "[processor][midi]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    REQUIRE(proc.getDrum()->snaresEngaged());

    render(proc, 256, 512, { { 10, note(100, 33) } }); // snares off
    CHECK_FALSE(proc.getDrum()->snaresEngaged());

    // Live parameter changes and strikes do not put them back.
    set(proc, ParamId::damping, 50.0);
    render(proc, 256, 4096, { { 10, note(100, 38) } });
    CHECK_FALSE(proc.getDrum()->snaresEngaged());

    render(proc, 256, 512, { { 10, note(100, 34) } }); // snares on
    CHECK(proc.getDrum()->snaresEngaged());
    render(proc, 256, 512, { { 10, note(100, 33) } });
    CHECK_FALSE(proc.getDrum()->snaresEngaged());

    // The parameter changing wins: 1 -> 0 keeps them off, 0 -> 1 puts them on.
    set(proc, ParamId::snaresEngaged, 0.0);
    render(proc, 256, 256);
    CHECK_FALSE(proc.getDrum()->snaresEngaged());
    set(proc, ParamId::snaresEngaged, 1.0);
    render(proc, 256, 256);
    CHECK(proc.getDrum()->snaresEngaged());
}

TEST_CASE("the factory presets are the programs", "[processor][programs]")
{
    SnareSimAudioProcessor proc;
    const auto presets = snaresim::factoryPresets();
    REQUIRE(proc.getNumPrograms() == 10);
    REQUIRE(presets.size() == 10);
    CHECK(proc.getProgramName(-1).isEmpty());
    CHECK(proc.getProgramName(10).isEmpty());

    for (int i = 0; i < proc.getNumPrograms(); ++i)
    {
        const auto& preset = presets[(size_t) i];
        INFO("program " << i << " " << std::string(preset.name));
        CHECK(proc.getProgramName(i) == juce::String(std::string(preset.name)));

        // Move everything away from the defaults first: the program sets every parameter.
        for (auto* p : proc.getParameters())
            p->setValueNotifyingHost(0.77f);

        proc.setCurrentProgram(i);
        CHECK(proc.getCurrentProgram() == i);

        snaresim::ParameterSet expected;
        REQUIRE(snaresim::applyPreset(preset.name, expected));
        const auto actual = proc.currentParameters();
        for (const auto& spec : snaresim::parameterSpecs())
        {
            INFO("parameter " << spec.key);
            CHECK(actual.get(spec.id) == Approx(expected.get(spec.id)).epsilon(1e-5).margin(1e-9));
        }
    }

    proc.setCurrentProgram(42);                                   // ignored
    CHECK(proc.getCurrentProgram() == proc.getNumPrograms() - 1); // the last one set
}

TEST_CASE("preset files load into every parameter, save what the host holds, and bad files change nothing", "[processor][programs]")
{
    SnareSimAudioProcessor proc;
    const auto dir = juce::File::createTempFile("snaresim-presets");
    REQUIRE(dir.createDirectory());

    // a file with a few values: those are set, every other parameter returns to its default
    for (auto* p : proc.getParameters())
        p->setValueNotifyingHost(0.77f);
    const auto file = dir.getChildFile("mine.snarepreset");
    REQUIRE(file.replaceWithText("name = Mine\nbatter_tension = 4200 N/m\nsnares_engaged = off\nshell_depth = 100 mm\n"));
    CHECK(snaresim::ui::loadPresetFile(proc, file).isEmpty());
    snaresim::ParameterSet expected;
    expected.set(ParamId::batterTension, 4200.0);
    expected.set(ParamId::snaresEngaged, 0.0);
    expected.set(ParamId::shellDepth, 0.1);
    const auto loaded = proc.parameterValues();
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        CHECK(loaded.get(spec.id) == Approx(expected.get(spec.id)).epsilon(1e-5).margin(1e-9));
    }

    // saved and loaded back into another processor: the same values
    const auto saved = dir.getChildFile("saved.snarepreset");
    proc.setCurrentProgram(3);
    CHECK(snaresim::ui::savePresetFile(proc, saved).isEmpty());
    CHECK(saved.loadFileAsString().contains("name = saved"));
    SnareSimAudioProcessor other;
    CHECK(snaresim::ui::loadPresetFile(other, saved).isEmpty());
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        CHECK(other.parameterValues().get(spec.id) == proc.parameterValues().get(spec.id));
    }

    // bad files: an error naming the file (and the line), no parameter changed
    const auto before = other.parameterValues();
    const auto bad = dir.getChildFile("bad.snarepreset");
    REQUIRE(bad.replaceWithText("name = Bad\ndamping = 10\nbatter_tension = 1e9\n"));
    const auto error = snaresim::ui::loadPresetFile(other, bad);
    CHECK(error.contains("bad.snarepreset"));
    CHECK(error.contains("line 3"));
    CHECK(snaresim::ui::loadPresetFile(other, dir.getChildFile("missing.snarepreset")).isNotEmpty());
    const auto binary = dir.getChildFile("binary.snarepreset");
    REQUIRE(binary.replaceWithData("RIFF\0\0\0\0WAVE", 12));
    CHECK(snaresim::ui::loadPresetFile(other, binary).isNotEmpty());
    for (const auto& spec : snaresim::parameterSpecs())
        CHECK(other.parameterValues().get(spec.id) == before.get(spec.id));

    // an unwritable place: an error, nothing written
    CHECK(snaresim::ui::savePresetFile(proc, dir.getChildFile("no/such/folder/x.snarepreset")).isNotEmpty());
    dir.deleteRecursively();
}

TEST_CASE("a preset file written by snaresim-render --match loads into every parameter", "[processor][programs]")
{
    // A strike of another drum, matched over the default parameters with a small budget: the
    // file holds the match's full-precision values and a comment line before the preset's own.
    const auto dir = juce::File::createTempFile("snaresim-match");
    REQUIRE(dir.createDirectory());
    const auto recording = dir.getChildFile("strike.wav");
    const auto preset = dir.getChildFile("match.snarepreset");
    auto run = [](const juce::StringArray& args) {
        juce::ChildProcess child;
        REQUIRE(child.start(args, juce::ChildProcess::wantStdOut));
        const auto out = child.readAllProcessOutput();
        REQUIRE(child.waitForProcessToFinish(120000));
        REQUIRE(child.getExitCode() == 0);
        return out;
    };
    run({ SNARESIM_RENDER_EXE, "-o", recording.getFullPathName(), "--hit", "0:90", "--seconds", "0.6", "--set", "batter_tension=3900",
          "--set", "damping=40" });
    const auto json = juce::JSON::parse(run(
        { SNARESIM_RENDER_EXE, "--match", recording.getFullPathName(), "-o", preset.getFullPathName(), "--match-budget", "12", "--json" }));
    REQUIRE(preset.loadFileAsString().startsWith("# Matched to strike.wav"));

    SnareSimAudioProcessor proc;
    CHECK(snaresim::ui::loadPresetFile(proc, preset).isEmpty());
    const auto loaded = proc.parameterValues();
    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        const double expected = json["parameters"][juce::Identifier(juce::String(std::string(spec.key)))];
        CHECK(loaded.get(spec.id) == Approx(expected).epsilon(1e-5).margin(1e-9));
    }
    dir.deleteRecursively();
}

TEST_CASE("a version-1 state loads with its values mapped", "[processor][state]")
{
    CHECK(snaresim::dampingFromT60(4.0) == Approx(0.0).margin(1e-12));
    CHECK(snaresim::dampingFromT60(0.15) == Approx(100.0));
    CHECK(snaresim::dampingFromT60(10.0) == 0.0);
    CHECK(snaresim::dampingFromT60(0.1) == 100.0);
    CHECK(snaresim::dampingFromT60(std::numeric_limits<double>::quiet_NaN()) == snaresim::spec(ParamId::damping).defaultValue);

    for (const int version : { 1, 0 })
    {
        INFO("state version " << version);
        SnareSimAudioProcessor proc;
        // Values the state does not mention go back to their defaults.
        set(proc, ParamId::snareTension, 77.0);
        set(proc, ParamId::micRoom, 0.9);

        juce::XmlElement v1("SnareSimState");
        if (version > 0)
            v1.setAttribute("stateVersion", version);
        auto add = [&v1](const char* id, const juce::String& value) {
            auto* p = v1.createNewChildElement("PARAM");
            p->setAttribute("id", id);
            p->setAttribute("value", value);
        };
        add("batter_tension", "4200");
        add("batter_decay", "1.5");
        add("batter_high_damping", "0.002");
        add("listen_position", "0.7");
        add("grid_coarseness", "2");
        add("output_gain", "99");       // out of range: clamped
        add("snare_count", "nonsense"); // not a number: 0, clamped to 1
        add("mallet_mass", "nan");      // not finite: default
        add("no_such_parameter", "12");
        v1.createNewChildElement("SOMETHING_ELSE")->setAttribute("id", "damping");

        juce::MemoryBlock state;
        juce::AudioProcessor::copyXmlToBinary(v1, state);
        proc.setStateInformation(state.getData(), (int) state.getSize());

        const auto p = proc.currentParameters();
        CHECK(p.get(ParamId::batterTension) == Approx(4200.0));
        CHECK(p.get(ParamId::damping) == Approx(100.0 * std::log(1.5 / 4.0) / std::log(0.15 / 4.0)).epsilon(1e-5));
        CHECK(p.get(ParamId::highDamping) == Approx(0.002).epsilon(1e-5));
        CHECK(p.get(ParamId::micTopPosition) == Approx(0.7).epsilon(1e-6));
        CHECK(p.get(ParamId::bandwidth) == Approx(snaresim::qualityBandwidth_Hz(2.0))); // Quality 2 was coarseness 2 (a float here)
        CHECK(snaresim::gridCoarsenessFor(p.get(ParamId::bandwidth)) == 2.0);
        CHECK(p.get(ParamId::outputGain) == Approx(12.0));
        CHECK(p.get(ParamId::snareCount) == 1.0);
        CHECK(p.get(ParamId::malletMass) == Approx(0.028));
        CHECK(p.get(ParamId::snareTension) == Approx(20.0)); // not held: the default of then (impliedParameters)
        CHECK(p.get(ParamId::micRoom) == Approx(snaresim::spec(ParamId::micRoom).defaultValue));

        // And it plays, as the engine's drum with those values.
        prepare(proc, 48000.0, 256);
        const auto r = render(proc, 256, 1024, { { 0, note(100) } });
        CHECK(r.allFinite);
        CHECK(r.peak > 0.0f);
        CHECK(r.samples == engineRender(proc.currentParameters(), 48000.0, 1024, { { 0, 38, 100 } }));
    }

    // A version-2 state does not rename: an old key in it is unknown.
    SnareSimAudioProcessor proc;
    juce::XmlElement v2("SnareSimState");
    v2.setAttribute("stateVersion", 2);
    auto* p = v2.createNewChildElement("PARAM");
    p->setAttribute("id", "batter_decay");
    p->setAttribute("value", 0.2);
    juce::MemoryBlock state;
    juce::AudioProcessor::copyXmlToBinary(v2, state);
    proc.setStateInformation(state.getData(), (int) state.getSize());
    // the damping that version implies where a state holds none (75 %), not the old key's
    CHECK(proc.currentParameters().get(ParamId::damping) == Approx(75.0));
    CHECK(snaresim::dampingFromT60(0.2) != Approx(75.0));
}

TEST_CASE("an older state keeps its drum: no outside air where it held none, the near field with it, that version's defaults",
          "[processor][state]")
{
    auto load = [](int version, std::initializer_list<std::pair<const char*, const char*>> params) {
        auto proc = std::make_unique<SnareSimAudioProcessor>();
        juce::XmlElement xml("SnareSimState");
        xml.setAttribute("stateVersion", version);
        for (const auto& [id, value] : params)
        {
            auto* p = xml.createNewChildElement("PARAM");
            p->setAttribute("id", id);
            p->setAttribute("value", value);
        }
        juce::MemoryBlock state;
        juce::AudioProcessor::copyXmlToBinary(xml, state);
        proc->setStateInformation(state.getData(), (int) state.getSize());
        return proc->currentParameters();
    };
    // Versions 0 to 2 had no outside air key: their drum had none. What a state of then does not
    // hold takes that version's default where it has changed since (the batter in single, the
    // losses of then).
    const auto v2 = load(2, { { "damping", "40" } });
    CHECK(v2.get(ParamId::outsideAir) == 0.0);
    CHECK(v2.get(ParamId::damping) == Approx(40.0));
    CHECK(v2.get(ParamId::headPrecision) == 1.0);
    CHECK(v2.get(ParamId::highDamping) == Approx(2.1e-4));
    CHECK(load(3, {}).get(ParamId::damping) == Approx(75.0));
    // A version-3 state with the outside air on had its near field too; off, the near field is inert.
    const auto v3 = load(3, { { "outside_air", "1" } });
    CHECK(v3.get(ParamId::outsideAir) == 1.0);
    CHECK(v3.get(ParamId::nearField) == 1.0);
    CHECK(load(3, { { "outside_air", "0" } }).get(ParamId::outsideAir) == 0.0);
    // What a state says wins over what is implied.
    CHECK(load(3, { { "outside_air", "1" }, { "near_field", "0" } }).get(ParamId::nearField) == 0.0);
    // Version 4 had the batter in double, damping 44 %, high damping 4e-4 m^2/s and 20 N wires.
    const auto v4 = load(4, {});
    CHECK(v4.get(ParamId::headPrecision) == 0.0);
    CHECK(v4.get(ParamId::damping) == Approx(44.0));
    CHECK(v4.get(ParamId::highDamping) == Approx(4e-4));
    CHECK(v4.get(ParamId::snareTension) == Approx(20.0));
    CHECK(v4.get(ParamId::outsideAir) == 1.0);
    CHECK(load(2, {}).get(ParamId::damping) == Approx(75.0)); // the oldest default wins
    // Today's states imply nothing: a missing key takes today's default.
    const auto today = load(snaresim::kStateVersion, {});
    CHECK(today.get(ParamId::outsideAir) == snaresim::spec(ParamId::outsideAir).defaultValue);
    CHECK(today.get(ParamId::nearField) == snaresim::spec(ParamId::nearField).defaultValue);
    CHECK(today.get(ParamId::headPrecision) == snaresim::spec(ParamId::headPrecision).defaultValue);
    CHECK(snaresim::spec(ParamId::outsideAir).defaultValue == 1.0);
    CHECK(snaresim::spec(ParamId::nearField).defaultValue == 0.0);
}

TEST_CASE("garbage states never crash", "[processor][state]")
{
    SnareSimAudioProcessor proc;
    std::mt19937 random(3);
    juce::MemoryBlock good;
    proc.getStateInformation(good);

    for (int i = 0; i < 200; ++i)
    {
        juce::MemoryBlock bad(good);
        for (int k = 0; k < 1 + i % 20; ++k)
            bad[(size_t) (random() % bad.getSize())] = (char) (random() % 256);
        if (i % 7 == 0)
            bad.setSize((size_t) (random() % bad.getSize()));
        proc.setStateInformation(bad.getData(), (int) bad.getSize());
    }

    for (const auto& spec : snaresim::parameterSpecs())
    {
        const double v = proc.currentParameters().get(spec.id);
        CHECK(std::isfinite(v));
        CHECK(v >= spec.minValue);
        CHECK(v <= spec.maxValue);
    }
}

TEST_CASE("snapshots reach the editor through the triple buffer", "[processor][editor]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    snaresim::DrumSnapshot snapshot;
    CHECK_FALSE(proc.pullSnapshot(snapshot));

    prepare(proc, 48000.0, 256);
    render(proc, 256, 2000, { { 0, note(120) } });
    REQUIRE(proc.pullSnapshot(snapshot));
    // One every round(48000 / 30) = 1600 samples, counted in sub-blocks of 32 (1600 = 50 x 32):
    // the first is the drum after its first 1600 samples, as the engine's drum then shows it.
    CHECK(snapshot.samplesRendered == 1600);
    snaresim::Drum drum(snaresim::makeDrumConfig(proc.currentParameters(), 48000.0));
    drum.playNote(38, 120);
    for (int n = 0; n < 1600; ++n)
        drum.step();
    snaresim::DrumSnapshot expected;
    drum.fillSnapshot(expected);
    CHECK(snapshot.peakDisplacement > 0.0f);
    CHECK(snapshot.peakDisplacement == expected.peakDisplacement);
    CHECK(snapshot.batter == expected.batter);
    CHECK(snapshot.wire == expected.wire);
    CHECK(snapshot.numWires == 5);
    CHECK_FALSE(proc.pullSnapshot(snapshot)); // nothing new

    // About 30 per second of audio; the newest wins.
    render(proc, 256, 48000 / 5);
    REQUIRE(proc.pullSnapshot(snapshot));
    CHECK(snapshot.samplesRendered >= 2000 + 48000 / 5 - 1700);
    CHECK(snapshot.samplesRendered <= 2000 + 48000 / 5);
}

TEST_CASE("the meters and counters are published", "[processor][editor]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    CHECK(proc.getNonFiniteResets() == 0);

    render(proc, 256, 9600, { { 0, note(127) } });
    CHECK(proc.getCpuLoad() > 0.0f);
    CHECK(proc.getPeakCpuLoad() >= proc.getCpuLoad() * 0.5f);
    CHECK(std::isfinite(proc.getCpuLoad()));
    // The solver's counts are the drum's: the same strike on the engine's drum.
    snaresim::Drum drum(snaresim::makeDrumConfig(proc.currentParameters(), 48000.0));
    drum.playNote(38, 127);
    for (int n = 0; n < 9600; ++n)
        drum.step();
    CHECK(proc.getMaxNewtonIterations() > 0);
    CHECK(proc.getMaxNewtonIterations() == drum.solverStats().maxIterations);
    CHECK(proc.getSolverFallbacks() == 0); // a fortissimo strike converges within the caps
    CHECK(proc.getNonFiniteResets() == 0);

    // The counts survive a model swap: the old drum's count stays (the new one is not struck,
    // and the old one's mallet is long back in the player's hand).
    const int iterations = proc.getMaxNewtonIterations();
    const int swaps = proc.getModelSwapCount();
    set(proc, ParamId::snareCount, 6.0);
    REQUIRE(waitForModelSwaps(proc, swaps + 1));
    render(proc, 256, fadeSamples);
    CHECK(proc.getMaxNewtonIterations() == iterations);
}

TEST_CASE("the output is finite and free of subnormals whatever the host sends", "[processor][guard]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 128);

    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::array<float, 7> absurd { nan, inf, -inf, 1.0e30f, -1.0e30f, 1.0e-40f, 0.0f };
    std::mt19937 random(5);
    auto& state = proc.getValueTreeState();

    // NaN in the buffer (as input) and absurd values straight into the parameters' atomics
    // (the grid ones left alone, so that this stays fast).
    const auto r = render(
        proc, 128, 48000 / 2, { { 0, note(127) }, { 6000, note(127, 40) }, { 12000, note(1, 37) }, { 18000, note(127, 33) } },
        [&](int) {
            for (const auto& spec : snaresim::parameterSpecs())
                if (! spec.rebuildsModel())
                    state.getRawParameterValue(juce::String(std::string(spec.key)))->store(absurd[random() % absurd.size()]);
        },
        nan);
    CHECK(r.allFinite);
    CHECK_FALSE(r.anySubnormal);
    CHECK(r.channelsIdentical);

    // Normalised values out of 0..1 through the parameter objects.
    for (auto* p : proc.getParameters())
        p->setValue(random() % 2 == 0 ? -5.0f : 7.0f);
    const auto r2 = render(proc, 128, 4800, { { 0, note(127) } }, {}, inf);
    CHECK(r2.allFinite);
    CHECK_FALSE(r2.anySubnormal);
}

TEST_CASE("parameters, programs, state and the editor from the message thread while the audio thread plays", "[processor][threads]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 128);
    juce::MemoryBlock fastState;
    proc.getStateInformation(fastState);

    std::atomic<bool> quit { false };
    std::atomic<long> blocks { 0 }, bad { 0 }, sounding { 0 };
    std::thread audio([&] {
        juce::AudioBuffer<float> buffer(2, 128);
        juce::MidiBuffer midi;
        std::mt19937 random(9);
        while (! quit)
        {
            midi.clear();
            if (blocks % 10 == 0)
                midi.addEvent(note(30 + (int) (random() % 98), 33 + (int) (random() % 8)), (int) (random() % 128));
            proc.processBlock(buffer, midi);
            for (int ch = 0; ch < 2; ++ch)
                for (int i = 0; i < 128; ++i)
                {
                    const float x = buffer.getSample(ch, i);
                    if (! std::isfinite(x))
                        ++bad;
                    else if (x != 0.0f)
                        ++sounding;
                }
            ++blocks;
        }
    });

    std::mt19937 random(13);
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1500);
    int round = 0;
    snaresim::DrumSnapshot snapshot;
    while (std::chrono::steady_clock::now() < until || blocks < 100)
    {
        switch (round++ % 4)
        {
            case 0:
                for (const auto& spec : snaresim::parameterSpecs())
                    if (! spec.rebuildsModel())
                        parameter(proc, spec.id).setValueNotifyingHost((float) (random() % 1001) / 1000.0f);
                break;
            case 1:
                proc.setCurrentProgram((int) (random() % 9));
                fastSettings(proc);
                break;
            case 2: proc.setStateInformation(fastState.getData(), (int) fastState.getSize()); break;
            default:
            {
                std::unique_ptr<juce::AudioProcessorEditor> editor(proc.createEditorIfNeeded());
                CHECK(editor != nullptr);
                editor.reset();
                break;
            }
        }
        proc.pullSnapshot(snapshot);
        juce::ignoreUnused(proc.getCpuLoad(), proc.getSolverFallbacks());
        std::this_thread::sleep_for(std::chrono::milliseconds(3));
    }

    quit = true;
    audio.join();
    CHECK(bad == 0);
    CHECK(sounding > 0); // the strikes were heard through it all
}

namespace
{
using State = snaresim::KeepUpCheck::State;

// Renders silent blocks until the air box's keep-up measurement has a verdict, or the time is up.
snaresim::KeepUpCheck::Verdict waitForVerdict(SnareSimAudioProcessor& proc, int blockSize, double timeoutSeconds = 120.0)
{
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
    for (;;)
    {
        const auto verdict = proc.airBoxVerdict();
        if ((verdict.state != State::measuring && verdict.state != State::none) || std::chrono::steady_clock::now() > until)
            return verdict;
        render(proc, blockSize, blockSize);
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
}

double airModelOf(const SnareSimAudioProcessor& proc) { return (double) proc.getDrum()->config().cavity.model; }
} // namespace

TEST_CASE("a host's offline render plays the air box when 'Air box when bouncing' is on, the air model when off", "[processor][airbox]")
{
    using snaresim::AirModel;
    struct Case
    {
        double offlineAirBox, airModel, plays;
    };
    for (const auto c : { Case { 1.0, (double) AirModel::cavity, (double) AirModel::airbox },
                          Case { 1.0, (double) AirModel::none, (double) AirModel::airbox },
                          Case { 0.0, (double) AirModel::cavity, (double) AirModel::cavity },
                          Case { 0.0, (double) AirModel::airbox, (double) AirModel::airbox } })
    {
        INFO("offline_airbox " << c.offlineAirBox << ", air_model " << c.airModel);
        SnareSimAudioProcessor proc;
        fastSettings(proc);
        CHECK(parameter(proc, ParamId::offlineAirBox).getValue() == 1.0f); // on by default
        set(proc, ParamId::offlineAirBox, c.offlineAirBox);
        set(proc, ParamId::airModel, c.airModel);

        // As a VST3 host bounces: offline first (setupProcessing), then prepareToPlay.
        proc.setNonRealtime(true);
        prepare(proc, 48000.0, 256);
        REQUIRE(proc.getDrum() != nullptr);
        CHECK(airModelOf(proc) == c.plays);
        const auto params = proc.currentParameters();
        CHECK(params.get(ParamId::airModel) == c.plays);
        CHECK_FALSE(proc.airBoxHeldBack());
        CHECK(proc.airBoxNotice() == (c.plays == (double) AirModel::airbox ? "Air box: the host renders offline, the air box plays" : ""));

        // Exactly what a drum built with those parameters plays.
        auto expected = params;
        expected.set(ParamId::airModel, c.plays);
        const auto r = render(proc, 256, 1536, { { 0, note(100) } });
        CHECK(r.allFinite);
        CHECK(r.peak > 1.0e-4f);
        CHECK(r.samples == engineRender(expected, 48000.0, 1536, { { 0, 38, 100 } }));
        CHECK(proc.airBoxMeasurements() == 0); // offline nothing is measured
    }
}

TEST_CASE("a host that goes offline while playing gets the bounce's drum before its first sample", "[processor][airbox]")
{
    // As an LV2 host says so: in the audio callback (the freewheeling port), after prepareToPlay.
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 256);
    render(proc, 256, 512);
    REQUIRE(airModelOf(proc) == (double) snaresim::AirModel::cavity);
    const int swaps = proc.getModelSwapCount();

    proc.setNonRealtime(true);
    const auto r = render(proc, 256, 1536, { { 0, note(100) } });
    CHECK(proc.getModelSwapCount() == swaps + 1);
    CHECK(airModelOf(proc) == (double) snaresim::AirModel::airbox);
    CHECK(r.samples == engineRender(proc.currentParameters(), 48000.0, 1536, { { 0, 38, 100 } }));

    // Back in real time the cavity comes back, built in the background; until it is there the
    // air-box drum is silent (real time never plays what cannot keep up).
    proc.setNonRealtime(false);
    const auto back = render(proc, 256, 256, { { 0, note(100) } });
    CHECK((back.peak == 0.0f || airModelOf(proc) == (double) snaresim::AirModel::cavity));
    REQUIRE(waitForModelSwaps(proc, swaps + 2, 256, 120.0));
    CHECK(airModelOf(proc) == (double) snaresim::AirModel::cavity);
    const auto cavity = render(proc, 256, 1024, { { 0, note(100) } });
    CHECK(cavity.peak > 1.0e-4f);
}

TEST_CASE("in real time the air box plays only where it keeps up: here the cavity plays and the editor says what it needs",
          "[processor][airbox]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    // A machine on which the air box needs 6.2 times real time (the AVX2 machine's order,
    // BENCHMARKS.md, "The air box in real time"), so the verdict is the same on any machine; the
    // measurement renders the drum it is given for 20 ms of its time, as the real probe renders.
    proc.setAirBoxMeasurement([](snaresim::DrumSession&, int size, const std::function<bool()>& cancelled) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        snaresim::KeepUpFigures f;
        f.blockSize = size;
        f.audioSeconds = cancelled && cancelled() ? 0.0 : 0.1;
        f.load = 6.2;
        f.worstBlockShare = 7.5;
        return f;
    });
    const int blockSize = 256;
    prepare(proc, 48000.0, blockSize);
    const int swaps = proc.getModelSwapCount();
    CHECK(proc.airBoxNotice() == "");
    CHECK(proc.airBoxVerdict().state == State::none);

    set(proc, ParamId::airModel, (double) snaresim::AirModel::airbox);
    render(proc, blockSize, blockSize);
    // Measured off the audio thread; meanwhile the cavity plays, and the editor says so.
    CHECK(proc.airBoxHeldBack());
    CHECK(proc.currentParameters().get(ParamId::airModel) == (double) snaresim::AirModel::cavity);
    CHECK(airModelOf(proc) == (double) snaresim::AirModel::cavity);
    const auto measuring = proc.airBoxNotice();
    CHECK((measuring == "Air box: measuring whether it keeps up here; the cavity plays meanwhile" || measuring.contains("x real time")));

    const auto verdict = waitForVerdict(proc, blockSize);
    REQUIRE(verdict.state == State::tooSlow);
    CHECK(verdict.figures.load == 6.2);
    CHECK(verdict.figures.blockSize == blockSize);
    CHECK(verdict.figures.audioSeconds > 0.0);
    CHECK(proc.airBoxHeldBack());
    const auto notice = proc.airBoxNotice();
    CHECK(notice.startsWith("Air box: needs "));
    CHECK(notice.endsWith("x real time here; the cavity plays live, bounces use the air box"));
    const double load = verdict.figures.load;
    CHECK(notice.contains("needs " + (load < 10.0 ? juce::String(load, 1) : juce::String(juce::roundToInt(load))) + "x real time"));

    // The cavity plays: the same drum as before, no model was built for the air box (at rest
    // after its silence, at that phase of its simulated steps).
    snaresim::DrumSnapshot atRest;
    proc.getDrum()->fillSnapshot(atRest);
    const auto r = render(proc, blockSize, 2048, { { 0, note(100) } });
    CHECK(proc.getModelSwapCount() == swaps);
    CHECK(airModelOf(proc) == (double) snaresim::AirModel::cavity);
    CHECK(r.samples == engineRender(proc.currentParameters(), 48000.0, 2048, { { 0, 38, 100 } }, atRest.samplesRendered % 96));

    // The verdict is remembered: the same air box is not measured again, another block size is.
    const int measured = proc.airBoxMeasurements();
    CHECK(measured >= 1);
    set(proc, ParamId::airModel, (double) snaresim::AirModel::cavity);
    render(proc, blockSize, 4 * blockSize);
    CHECK(proc.airBoxNotice() == "");
    set(proc, ParamId::airModel, (double) snaresim::AirModel::airbox);
    CHECK(proc.airBoxVerdict().state == State::tooSlow);
    CHECK(proc.airBoxMeasurements() == measured);

    prepare(proc, 48000.0, 1024);
    CHECK(proc.airBoxVerdict().state == State::measuring);
    const auto second = waitForVerdict(proc, 1024);
    CHECK(second.state == State::tooSlow);
    CHECK(second.figures.blockSize == 1024);
    CHECK(proc.airBoxMeasurements() == measured + 1);
    CHECK(airModelOf(proc) == (double) snaresim::AirModel::cavity);
}

TEST_CASE("'Air box when bouncing' round-trips through the state, and a state without it turns it on", "[processor][airbox][state]")
{
    SnareSimAudioProcessor proc;
    set(proc, ParamId::offlineAirBox, 0.0);
    CHECK(proc.currentParameters().get(ParamId::offlineAirBox) == 0.0);
    juce::MemoryBlock state;
    proc.getStateInformation(state);

    SnareSimAudioProcessor restored;
    restored.setStateInformation(state.getData(), (int) state.getSize());
    CHECK(restored.currentParameters().get(ParamId::offlineAirBox) == 0.0);
    CHECK(parameter(restored, ParamId::offlineAirBox).getValue() == 0.0f);

    // A state saved before the parameter existed: it takes its default, on.
    const auto xml = juce::AudioProcessor::getXmlFromBinary(state.getData(), (int) state.getSize());
    REQUIRE(xml != nullptr);
    juce::XmlElement older(*xml);
    for (auto* child = older.getFirstChildElement(); child != nullptr;)
    {
        auto* next = child->getNextElement();
        if (child->getStringAttribute("id") == "offline_airbox")
            older.removeChildElement(child, true);
        child = next;
    }
    juce::MemoryBlock olderState;
    juce::AudioProcessor::copyXmlToBinary(older, olderState);
    restored.setStateInformation(olderState.getData(), (int) olderState.getSize());
    CHECK(restored.currentParameters().get(ParamId::offlineAirBox) == 1.0);
}
