// What a careless or hostile host may hand the processor: states that are random bytes,
// truncated, from the first version, from another plug-in, or empty; and floods of MIDI.
// With SNARESIM_TEST_REPORT set, the first two print how many cases they tried.

#include <catch2/catch.hpp>

#include "PluginState.h"
#include "ProcessorTestHelpers.h"
#include "Report.h"

#include <chrono>
#include <iostream>
#include <random>

using namespace snaresim::testing;
using snaresim::ParamId;

namespace
{
// Every parameter of the processor in range and on its step, as the engine reads it.
bool parametersSane(SnareSimAudioProcessor& proc)
{
    const auto values = proc.currentParameters();
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const double v = values.get(spec.id);
        if (! std::isfinite(v) || v < spec.minValue || v > spec.maxValue)
            return false;
        if (spec.kind != snaresim::ParamKind::continuous && v != std::round(v))
            return false;
    }
    return true;
}

std::vector<float> normalisedValues(SnareSimAudioProcessor& proc)
{
    std::vector<float> v;
    for (auto* p : proc.getParameters())
        v.push_back(p->getValue());
    return v;
}

// A plain value of parameter i as the host sees it (0..1).
float normalisedOf(SnareSimAudioProcessor& proc, size_t i, double value)
{
    auto* p = dynamic_cast<juce::RangedAudioParameter*>(proc.getParameters()[(int) i]);
    return p != nullptr ? p->convertTo0to1((float) value) : (float) value;
}

juce::MemoryBlock xmlState(const juce::XmlElement& xml)
{
    juce::MemoryBlock block;
    juce::AudioProcessor::copyXmlToBinary(xml, block);
    return block;
}
} // namespace

TEST_CASE("hostile states: random bytes, truncated, version 1, another plug-in's, empty", "[processor][state][hostile]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    set(proc, ParamId::snareTension, 55.0);
    prepare(proc, 48000.0, 256);

    juce::MemoryBlock good;
    proc.getStateInformation(good);
    const auto before = normalisedValues(proc);
    std::mt19937 random(11);
    int tried = 0, ignored = 0;

    // Not a SnareSim state: ignored, the parameters stay as they were.
    auto expectIgnored = [&](const void* data, int size, const char* what) {
        INFO(what << " (" << size << " bytes)");
        proc.setStateInformation(data, size);
        CHECK(normalisedValues(proc) == before);
        ++tried;
        ++ignored;
    };

    // Random bytes of every length up to 4 kB, and random bytes behind JUCE's binary XML
    // header (a valid magic number and a size that lies).
    for (int i = 0; i < 500; ++i)
    {
        std::vector<char> bytes((size_t) (random() % 4097));
        for (auto& b : bytes)
            b = (char) (random() & 0xff);
        if (i % 2 == 1 && bytes.size() >= 8)
            std::copy_n(static_cast<const char*>(good.getData()), 8, bytes.begin());
        expectIgnored(bytes.data(), (int) bytes.size(), "random bytes");
    }

    // Every truncation of a good state: what can still be read is restored, the rest takes
    // its default, or what an older state implies where the version is cut off
    // (snaresim::impliedParameters), or, when nothing can be read, the state is ignored.
    int truncatedRead = 0;
    const auto defaults = [&] {
        std::vector<float> v;
        for (auto* p : proc.getParameters())
            v.push_back(p->getDefaultValue());
        return v;
    }();
    for (size_t length = 0; length < good.getSize(); ++length)
    {
        proc.setStateInformation(good.getData(), (int) length);
        const auto now = normalisedValues(proc);
        bool changed = false;
        for (size_t i = 0; i < now.size(); ++i)
        {
            INFO("a state truncated to " << length << " bytes, parameter " << i);
            bool implied = false;
            for (const auto& p : snaresim::impliedParameters())
                implied = implied || ((size_t) p.id == i && now[i] == Approx(normalisedOf(proc, i, p.value)).margin(1.0e-6));
            CHECK((now[i] == before[i] || now[i] == Approx(defaults[i]).margin(1.0e-6) || implied));
            changed = changed || now[i] != before[i];
        }
        truncatedRead += changed ? 1 : 0;
        ++tried;
        // Back to the good state for the next one.
        proc.setStateInformation(good.getData(), (int) good.getSize());
    }

    // Empty.
    expectIgnored(nullptr, 0, "no data");
    expectIgnored(good.getData(), 0, "zero bytes");
    expectIgnored(nullptr, 100, "a null pointer with a size");

    // Other plug-ins' states: another JUCE plug-in's tree, plain XML text, a VST2-style chunk.
    {
        juce::XmlElement other("PARAMETERS");
        other.createNewChildElement("PARAM")->setAttribute("id", "gain");
        const auto block = xmlState(other);
        expectIgnored(block.getData(), (int) block.getSize(), "another plug-in's JUCE state");

        const juce::String text("<?xml version=\"1.0\"?><SnareSimState><PARAM id=\"damping\" value=\"3\"/></SnareSimState>");
        expectIgnored(text.toRawUTF8(), (int) text.getNumBytesAsUTF8(), "XML text without JUCE's binary header");

        const char chunk[] = "CcnK\0\0\0\0FxCk\0\0\0\1Snr1";
        expectIgnored(chunk, (int) sizeof(chunk), "a VST2 chunk");
    }

    // A SnareSim state whose text is not UTF-8 (JUCE's XML reader can run past the end of such
    // text): not read at all, though its first parameter is well formed.
    for (const std::string bad : { std::string("\xff"), std::string(33, '\xb8') + std::string(104, '\xff'), std::string("\xc3") })
    {
        const std::string text =
            "<SnareSimState stateVersion=\"2\"><PARAM id=\"snare_tension\" value=\"60\"/><PARAM id=\"damping\" value=\"3" + bad +
            "\"/></SnareSimState>";
        juce::MemoryBlock block(good.getData(), 4); // the magic number
        const auto length = juce::ByteOrder::swapIfBigEndian((juce::uint32) text.size());
        block.append(&length, 4);
        block.append(text.data(), text.size());
        expectIgnored(block.getData(), (int) block.getSize(), "a state whose text is not UTF-8");
    }

    // SnareSim states that cannot be read in part: defaults for what is missing or unreadable,
    // in range for what is out of it. Version 0 and 1 (renamed IDs) and version 2.
    int partial = 0;
    for (const int version : { 0, 1, 2, 99 })
        for (int i = 0; i < 50; ++i)
        {
            juce::XmlElement xml(snaresim::plugin::PluginState::treeType);
            if (version > 0)
                xml.setAttribute(snaresim::plugin::PluginState::versionAttribute, version);

            for (const auto& spec : snaresim::parameterSpecs())
            {
                if (random() % 3 == 0)
                    continue; // missing: default
                auto* p = xml.createNewChildElement(random() % 10 == 0 ? "SOMETHING" : "PARAM");
                p->setAttribute("id", juce::String(std::string(spec.key)));
                switch (random() % 5)
                {
                    case 0: p->setAttribute("value", "not a number"); break;
                    case 1: p->setAttribute("value", "nan"); break;
                    case 2: p->setAttribute("value", (double) (random() % 2000000) - 1.0e6); break;
                    case 3: break; // no value attribute
                    default: p->setAttribute("value", spec.minValue + (spec.maxValue - spec.minValue) * (double) (random() % 1000) / 999.0);
                }
            }
            if (version == 1)
                xml.createNewChildElement("PARAM")->setAttribute("id", "batter_decay");

            const auto block = xmlState(xml);
            proc.setStateInformation(block.getData(), (int) block.getSize());
            CHECK(parametersSane(proc));
            ++tried;
            ++partial;
        }

    // A SnareSim state that names nothing: every parameter at its default; without a version
    // (version 0), what such an old state implies instead (snaresim::impliedParameters).
    for (const bool versioned : { true, false })
    {
        juce::XmlElement empty(snaresim::plugin::PluginState::treeType);
        if (versioned)
            empty.setAttribute(snaresim::plugin::PluginState::versionAttribute, snaresim::kStateVersion);
        const auto block = xmlState(empty);
        proc.setStateInformation(block.getData(), (int) block.getSize());
        ++tried;
        for (size_t i = 0; i < proc.getParameters().size(); ++i)
        {
            auto* p = proc.getParameters()[(int) i];
            INFO(p->getName(64) << (versioned ? ", today's version" : ", version 0"));
            double expected = p->getDefaultValue();
            if (! versioned)
                for (const auto& implied : snaresim::impliedParameters())
                    if ((size_t) implied.id == i)
                    {
                        expected = normalisedOf(proc, i, implied.value); // the first that applies
                        break;
                    }
            CHECK(p->getValue() == Approx(expected).margin(1.0e-6));
        }
    }

    // And the good state still restores, and plays.
    proc.setStateInformation(good.getData(), (int) good.getSize());
    CHECK(normalisedValues(proc) == before);
    const auto r = render(proc, 256, 9600, { { 0, note(120) } });
    CHECK(r.allFinite);
    CHECK(r.peak > 0.0f);

    snaresim::test::report() << "hostile states: " << tried << " tried (" << ignored << " not SnareSim states, all ignored; "
                             << good.getSize() << " truncations of a good state, " << truncatedRead
                             << " of them read in part (defaults for the rest of each), the others ignored; " << partial
                             << " partly unreadable SnareSim states, all restored in range; one empty tree restored to defaults)\n";
}

TEST_CASE("MIDI floods: 1000 notes in a block, every note and velocity, running status, SysEx, all-notes-off", "[processor][midi][hostile]")
{
    SnareSimAudioProcessor proc;
    prepare(proc, 48000.0, 64); // the real-time defaults

    juce::AudioBuffer<float> buffer(2, 64);
    juce::MidiBuffer midi;
    std::mt19937 random(17);
    double worstBlock_ms = 0.0;
    long blocks = 0, events = 0;
    bool finite = true;
    float peak = 0.0f;

    auto run = [&] {
        buffer.clear();
        const auto start = std::chrono::steady_clock::now();
        proc.processBlock(buffer, midi);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        worstBlock_ms = std::max(worstBlock_ms, ms);
        events += midi.getNumEvents();
        ++blocks;
        for (int ch = 0; ch < buffer.getNumChannels(); ++ch)
            for (int i = 0; i < buffer.getNumSamples(); ++i)
            {
                const float s = buffer.getSample(ch, i);
                finite = finite && std::isfinite(s);
                peak = std::max(peak, std::abs(s));
            }
        midi.clear();
    };

    // 1000 note-ons in one 64-sample block, ten times over.
    for (int b = 0; b < 10; ++b)
    {
        for (int i = 0; i < 1000; ++i)
            midi.addEvent(juce::MidiMessage::noteOn(1 + (int) (random() % 16), (int) (random() % 128), (juce::uint8)(1 + random() % 127)),
                          (int) (random() % 64));
        run();
    }

    // Every note at every velocity (velocity 0 is a note-off), 128 events a block.
    for (int noteNumber = 0; noteNumber < 128; ++noteNumber)
    {
        for (int velocity = 0; velocity < 128; ++velocity)
            midi.addEvent(juce::MidiMessage::noteOn(10, noteNumber, (juce::uint8) velocity), velocity / 2);
        run();
    }

    // Running status: one status byte, then data pairs, decoded as a host's MIDI parser does.
    {
        std::vector<juce::uint8> stream { 0x99 };
        for (int i = 0; i < 300; ++i)
        {
            stream.push_back((juce::uint8)(random() % 128));
            stream.push_back((juce::uint8)(random() % 128));
        }
        int position = 0;
        juce::uint8 lastStatus = 0;
        while (position < (int) stream.size())
        {
            int used = 0;
            juce::MidiMessage m(stream.data() + position, (int) stream.size() - position, used, lastStatus, 0.0);
            if (used <= 0)
                break;
            lastStatus = m.getRawData()[0];
            midi.addEvent(m, position % 64);
            position += used;
        }
        run();
    }

    // SysEx, large and small, among notes; controllers, pitch bend, program changes, clock.
    {
        std::vector<juce::uint8> big(65536);
        for (auto& b : big)
            b = (juce::uint8)(random() % 128);
        midi.addEvent(juce::MidiMessage::createSysExMessage(big.data(), (int) big.size()), 0);
        midi.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127), 1);
        const juce::uint8 small[] = { 0x7e, 0x7f, 0x09, 0x01 };
        midi.addEvent(juce::MidiMessage::createSysExMessage(small, 4), 2);
        for (int i = 0; i < 200; ++i)
        {
            switch (i % 5)
            {
                case 0: midi.addEvent(juce::MidiMessage::controllerEvent(1, (int) (random() % 128), (int) (random() % 128)), i % 64); break;
                case 1: midi.addEvent(juce::MidiMessage::pitchWheel(1, (int) (random() % 16384)), i % 64); break;
                case 2: midi.addEvent(juce::MidiMessage::programChange(1, (int) (random() % 128)), i % 64); break;
                case 3: midi.addEvent(juce::MidiMessage::midiClock(), i % 64); break;
                default: midi.addEvent(juce::MidiMessage::aftertouchChange(1, 38, (int) (random() % 128)), i % 64);
            }
        }
        run();
    }

    // A fortissimo roll with all-notes-off and all-sound-off in its middle.
    for (int b = 0; b < 750; ++b)
    {
        if (b % 45 == 0)
            midi.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127), (int) (random() % 64));
        if (b == 300)
            midi.addEvent(juce::MidiMessage::allNotesOff(10), 10);
        if (b == 500)
            midi.addEvent(juce::MidiMessage::allSoundOff(10), 20);
        run();
    }

    CHECK(finite);
    CHECK(peak > 0.0f);
    CHECK(peak < 128.0f); // loose: a flood of fortissimo strikes on the default mix stays within 42 dB of full scale
    CHECK(proc.getNonFiniteResets() == 0);

    snaresim::test::report() << "MIDI floods: " << events << " events in " << blocks << " blocks of 64 samples at 48 kHz; worst block "
                             << worstBlock_ms << " ms (budget 1.333 ms), peak " << peak << ", non-finite resets "
                             << proc.getNonFiniteResets() << "\n";
}

TEST_CASE("a block with no channels or no samples is taken in stride", "[processor][hostile]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    prepare(proc, 48000.0, 64);

    juce::MidiBuffer midi;
    midi.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127), 0);
    juce::AudioBuffer<float> none(0, 64), empty(2, 0);
    proc.processBlock(none, midi);
    proc.processBlock(empty, midi);

    // And it plays on.
    const auto r = render(proc, 64, 4800, { { 0, note(127) } });
    CHECK(r.allFinite);
    CHECK(r.peak > 0.0f);
}
