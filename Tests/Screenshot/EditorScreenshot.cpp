// snaresim_editor_screenshot: renders the SnareSim editor to a PNG.
//
//   snaresim_editor_screenshot OUT.png [--size WIDTHxHEIGHT] [--program INDEX] [--ms MILLISECONDS]
//                              [--set ID=VALUE ...] [--check]
//
// Creates the processor, prepares it at 48 kHz, plays two strikes through processBlock so the
// drum rings and a snapshot exists, opens the editor (default size unless --size), lets it pull
// the snapshot and the meters, and writes createComponentSnapshot as PNG. --set sets a parameter
// (after --program) as the renderer's --set reads it; with the air model set to the air box it
// waits for the measurement of whether the air box keeps up here, so the editor shows its verdict.
//
// With --check it then also checks the editor (a control per parameter of the table, of the
// right kind and attached; the preset selector; the value texts of the three main controls;
// the layout at the size limits) and exits 1 when something is wrong: the CTest smoke test of
// the editor.
//
// It needs no X server: JUCE renders components into images without a window (on a machine
// with a display it connects to it, harmlessly).

#include "ParameterText.h"
#include "Parameters.h"
#include "PluginEditor.h"
#include "PluginProcessor.h"

#include <juce_audio_processors/juce_audio_processors.h>
#include <juce_gui_basics/juce_gui_basics.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

namespace
{
constexpr double sampleRate = 48000.0;
constexpr int blockSize = 256;

int usage(const juce::String& message)
{
    std::fprintf(stderr,
                 "snaresim_editor_screenshot: %s\n"
                 "usage: snaresim_editor_screenshot OUT.png [--size WIDTHxHEIGHT] [--program INDEX] "
                 "[--ms MILLISECONDS] [--set ID=VALUE ...] [--check]\n",
                 message.toRawUTF8());
    return 2;
}

// Plays `notes` (sample position, note, velocity) while rendering `totalSamples` samples.
void play(juce::AudioProcessor& processor, int totalSamples, std::initializer_list<std::tuple<int, int, int>> notes)
{
    juce::AudioBuffer<float> buffer(2, blockSize);
    juce::MidiBuffer midi;

    for (int start = 0; start < totalSamples; start += blockSize)
    {
        const int n = juce::jmin(blockSize, totalSamples - start);
        buffer.setSize(2, n, false, false, true);
        buffer.clear();
        midi.clear();

        for (const auto& [at, note, velocity] : notes)
            if (at >= start && at < start + n)
                midi.addEvent(juce::MidiMessage::noteOn(10, note, (juce::uint8) velocity), at - start);

        processor.processBlock(buffer, midi);
    }
}

bool writePng(const juce::Image& image, const juce::File& output)
{
    output.getParentDirectory().createDirectory();
    const auto temp = output.getSiblingFile(output.getFileName() + ".tmp");
    bool written = false;
    {
        juce::FileOutputStream stream(temp);
        if (stream.openedOk())
        {
            stream.setPosition(0);
            stream.truncate();
            juce::PNGImageFormat png;
            written = png.writeImageToStream(image, stream);
            stream.flush();
            written = written && stream.getStatus().wasOk();
        }
    }

    if (written && temp.moveFileTo(output))
        return true;

    temp.deleteFile();
    return false;
}

//==============================================================================
// --check

struct Checker
{
    int failures = 0;

    void expect(bool condition, const juce::String& what)
    {
        if (! condition)
        {
            ++failures;
            std::fprintf(stderr, "check failed: %s\n", what.toRawUTF8());
        }
    }
};

void collect(juce::Component& root, std::vector<juce::Component*>& out)
{
    for (auto* child : root.getChildren())
    {
        out.push_back(child);
        collect(*child, out);
    }
}

template <typename ComponentType>
ComponentType* findTitled(juce::Component& root, const juce::String& title)
{
    std::vector<juce::Component*> all;
    collect(root, all);
    for (auto* c : all)
        if (auto* typed = dynamic_cast<ComponentType*>(c); typed != nullptr && c->getTitle() == title)
            return typed;
    return nullptr;
}

juce::String toJuce(std::string_view s) { return juce::String(juce::CharPointer_UTF8(std::string(s).c_str())); }

float rawValue(SnareSimAudioProcessor& processor, std::string_view key)
{
    auto* raw = processor.getValueTreeState().getRawParameterValue(toJuce(key));
    return raw != nullptr ? raw->load() : std::nanf("");
}

void checkLayout(Checker& check, SnareSimAudioProcessorEditor& editor, int width, int height)
{
    editor.setSize(width, height);
    const auto label = juce::String(width) + "x" + juce::String(height);
    check.expect(editor.getWidth() == width && editor.getHeight() == height, "the editor takes the size " + label);

    std::vector<juce::Component*> all;
    collect(editor, all);
    for (auto* c : all)
    {
        if (! c->isVisible() || c->getParentComponent() != &editor || dynamic_cast<juce::TooltipWindow*>(c) != nullptr)
            continue;
        check.expect(editor.getLocalBounds().contains(c->getBounds()), "at " + label + ", '" + c->getTitle() + "' lies inside the editor");
    }

    // Every parameter control has room.
    for (const auto& spec : snaresim::parameterSpecs())
        if (auto* c = findTitled<juce::Component>(editor, toJuce(spec.name)))
            check.expect(c->getWidth() >= 20 && c->getHeight() >= 14,
                         "at " + label + ", the control of " + toJuce(spec.key) + " is large enough (" + c->getBounds().toString() + ")");

    // Siblings of the editor (panels, header items) do not overlap.
    std::vector<juce::Component*> top;
    for (auto* c : editor.getChildren())
        if (c->isVisible() && dynamic_cast<juce::TooltipWindow*>(c) == nullptr &&
            dynamic_cast<juce::ResizableCornerComponent*>(c) == nullptr)
            top.push_back(c);
    for (size_t i = 0; i < top.size(); ++i)
        for (size_t j = i + 1; j < top.size(); ++j)
            check.expect(! top[i]->getBounds().intersects(top[j]->getBounds()),
                         "at " + label + ", '" + top[i]->getTitle() + "' and '" + top[j]->getTitle() + "' do not overlap");
}

int runChecks(SnareSimAudioProcessor& processor, SnareSimAudioProcessorEditor& editor, double ringMs)
{
    using snaresim::ParamKind;
    Checker check;

    check.expect(editor.getDrumView().hasShownSnapshot(), "the drum picture shows a snapshot");
    // The strikes at velocities 112 and 100 (18 ms apart) move the batter by 0.3 to 0.5 mm
    // through the first 60 ms (the colour scale is the snapshot's peak displacement); a longer
    // ring (--ms) fades, and then only its floor is asked for.
    const float ringing = 18.0 + ringMs <= 60.0 ? 1.0e-4f : 1.0e-7f;
    check.expect(editor.getDrumView().getColourScale() > ringing,
                 "the snapshot shows the drum ringing (colour scale " + juce::String(editor.getDrumView().getColourScale()) + " m)");

    // One control per parameter of the table, of the kind the table asks for.
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const auto name = toJuce(spec.name);
        switch (spec.kind)
        {
            case ParamKind::toggle:
                check.expect(findTitled<juce::ToggleButton>(editor, name) != nullptr, "a switch for " + toJuce(spec.key));
                break;
            case ParamKind::choice:
            {
                auto* box = findTitled<juce::ComboBox>(editor, name);
                check.expect(box != nullptr, "a combo box for " + toJuce(spec.key));
                if (box != nullptr)
                    check.expect(box->getNumItems() == (int) std::lround(spec.maxValue - spec.minValue) + 1,
                                 "the combo box of " + toJuce(spec.key) + " lists every choice");
                break;
            }
            case ParamKind::continuous:
            case ParamKind::integer:
            default:
            {
                auto* slider = findTitled<juce::Slider>(editor, name);
                check.expect(slider != nullptr, "a slider for " + toJuce(spec.key));
                if (slider != nullptr)
                {
                    check.expect(std::abs(slider->getValue() - rawValue(processor, spec.key)) <=
                                     1.0e-6 * std::max(1.0, std::abs(spec.maxValue)),
                                 "the slider of " + toJuce(spec.key) + " shows the parameter's value");
                    const auto unit = juce::String(juce::CharPointer_UTF8(snaresim::valueFormat(spec).unit.c_str()));
                    check.expect(unit.isEmpty() || slider->getTextFromValue(slider->getValue()).endsWith(" " + unit),
                                 "the value of " + toJuce(spec.key) + " shows its unit");
                }
                break;
            }
        }
    }

    // The three main controls read as their value texts should.
    const auto expectText = [&](std::string_view key, double value, const char* text) {
        const auto& spec = snaresim::spec(*snaresim::findParameter(key));
        auto* slider = findTitled<juce::Slider>(editor, toJuce(spec.name));
        const auto shown = slider != nullptr ? slider->getTextFromValue(value) : juce::String();
        check.expect(shown == juce::String(text), toJuce(key) + " shows \"" + text + "\" (got \"" + shown + "\")");
        if (slider != nullptr)
            check.expect(std::abs(slider->getValueFromText(text) - value) < 1.0e-9 * std::max(1.0, value),
                         toJuce(key) + " reads back \"" + text + "\"");
    };
    expectText("batter_tension", 3050.0, "3050 N/m");
    expectText("snare_tension", 30.0, "30.0 N");
    expectText("damping", 25.0, "25 %");

    // Controls drive their parameters.
    if (auto* slider = findTitled<juce::Slider>(editor, toJuce(snaresim::spec(snaresim::ParamId::batterTension).name)))
    {
        slider->setValue(4000.0, juce::sendNotificationSync);
        check.expect(std::abs(rawValue(processor, "batter_tension") - 4000.0f) < 0.5f, "the membrane knob sets batter_tension");
    }
    if (auto* toggle = findTitled<juce::ToggleButton>(editor, toJuce(snaresim::spec(snaresim::ParamId::snaresEngaged).name)))
    {
        const float before = rawValue(processor, "snares_engaged");
        toggle->setToggleState(before < 0.5f, juce::sendNotificationSync);
        check.expect(rawValue(processor, "snares_engaged") == (before < 0.5f ? 1.0f : 0.0f),
                     "the snares switch sets snares_engaged to the state it shows");
    }
    if (auto* box = findTitled<juce::ComboBox>(editor, toJuce(snaresim::spec(snaresim::ParamId::airModel).name)))
    {
        box->setSelectedItemIndex(0, juce::sendNotificationSync);
        check.expect(rawValue(processor, "air_model") == 0.0f, "the air model box sets air_model");
    }

    // The preset selector lists the programs and selects them.
    if (auto* presets = findTitled<juce::ComboBox>(editor, "Preset"))
    {
        check.expect(presets->getNumItems() == processor.getNumPrograms(), "the preset box lists every program");
        for (int i = 0; i < juce::jmin(presets->getNumItems(), processor.getNumPrograms()); ++i)
            check.expect(presets->getItemText(i) == processor.getProgramName(i), "preset " + juce::String(i) + " is named");

        if (processor.getNumPrograms() > 1)
        {
            presets->setSelectedItemIndex(1, juce::sendNotificationSync);
            check.expect(processor.getCurrentProgram() == 1, "choosing a preset sets the program");
            presets->setSelectedItemIndex(0, juce::sendNotificationSync);
            check.expect(processor.getCurrentProgram() == 0, "choosing the first preset sets it back");
        }
    }
    else
        check.expect(false, "a preset box");

    // The layout holds from the smallest to the largest size.
    check.expect(editor.isResizable(), "the editor is resizable");
    checkLayout(check, editor, SnareSimAudioProcessorEditor::minWidth, SnareSimAudioProcessorEditor::minHeight);
    checkLayout(check, editor, SnareSimAudioProcessorEditor::maxWidth, SnareSimAudioProcessorEditor::maxHeight);
    checkLayout(check, editor, SnareSimAudioProcessorEditor::defaultWidth, SnareSimAudioProcessorEditor::defaultHeight);

    // The editor keeps rendering after all that, back at its default size, and its drum picture
    // still shows the snapshot at full colour: the colour scale is the snapshot's peak, so the
    // heads show the map's end (deep red up, deep blue down) near the peak's raster point.
    const auto image = editor.createComponentSnapshot(editor.getLocalBounds(), true, 1.0f);
    check.expect(image.getWidth() == SnareSimAudioProcessorEditor::defaultWidth &&
                     image.getHeight() == SnareSimAudioProcessorEditor::defaultHeight,
                 "the editor renders at its default size");
    {
        const auto& view = editor.getDrumView();
        const juce::Colour ends[] = { snaresim::ui::DrumView::colourFor(1.0f), snaresim::ui::DrumView::colourFor(-1.0f) };
        auto nearEnd = [&](juce::Colour c) {
            for (const auto end : ends)
                if (std::abs(c.getRed() - end.getRed()) <= 32 && std::abs(c.getGreen() - end.getGreen()) <= 32 &&
                    std::abs(c.getBlue() - end.getBlue()) <= 32)
                    return true;
            return false;
        };
        int fullColour = 0;
        for (const auto disc : { view.getBatterDisc(), view.getCarryDisc() })
        {
            // The inside of the disc (its rim and shadow left out), in the editor's pixels.
            const auto inside = editor.getLocalArea(&view, disc.reduced(disc.getWidth() * 0.08f)).toNearestInt();
            for (int y = inside.getY(); y < inside.getBottom(); ++y)
                for (int x = inside.getX(); x < inside.getRight(); ++x)
                    if (juce::Point<float>((float) x + 0.5f, (float) y + 0.5f).getDistanceFrom(inside.toFloat().getCentre()) <
                            0.5f * (float) inside.getWidth() &&
                        nearEnd(image.getPixelAt(x, y)))
                        ++fullColour;
        }
        check.expect(fullColour > 0, "the drum picture shows the snapshot's peak at full colour (" + juce::String(fullColour) + " pixels)");
    }

    if (check.failures == 0)
        std::printf("editor checks passed\n");
    return check.failures == 0 ? 0 : 1;
}
} // namespace

int main(int argc, char* argv[])
{
    if (argc < 2 || juce::String(argv[1]).startsWith("-"))
        return usage("the first argument is the output PNG file");

    const auto output = juce::File::getCurrentWorkingDirectory().getChildFile(juce::String(argv[1]));
    int width = SnareSimAudioProcessorEditor::defaultWidth;
    int height = SnareSimAudioProcessorEditor::defaultHeight;
    int program = -1;
    double ringMs = 42.0;
    bool check = false;
    std::vector<std::pair<snaresim::ParamId, double>> settings;

    for (int i = 2; i < argc; ++i)
    {
        const juce::String arg(argv[i]);
        if (arg == "--check")
        {
            check = true;
            continue;
        }

        if (i + 1 >= argc)
            return usage("missing a value after " + arg);

        const juce::String value(argv[++i]);
        if (arg == "--size")
        {
            width = value.upToFirstOccurrenceOf("x", false, true).getIntValue();
            height = value.fromFirstOccurrenceOf("x", false, true).getIntValue();
            if (width <= 0 || height <= 0)
                return usage("--size wants WIDTHxHEIGHT");
        }
        else if (arg == "--program")
            program = value.getIntValue();
        else if (arg == "--set")
        {
            const auto key = value.upToFirstOccurrenceOf("=", false, false).toStdString();
            const auto id = snaresim::findParameter(key);
            if (! id.has_value() || ! value.contains("="))
                return usage("--set wants ID=VALUE with an ID of the parameter table, not " + value);
            const auto text = value.fromFirstOccurrenceOf("=", false, false).toStdString();
            const auto v = snaresim::parseValue(snaresim::spec(*id), text, snaresim::BareNumber::schemaUnit);
            if (! v.has_value())
                return usage("--set " + value + ": not a value of " + juce::String(key));
            settings.emplace_back(*id, *v);
        }
        else if (arg == "--ms")
        {
            ringMs = value.getDoubleValue();
            if (! (ringMs > 0.0 && ringMs <= 10000.0))
                return usage("--ms wants 0 < MILLISECONDS <= 10000");
        }
        else
            return usage("unknown option " + arg);
    }

    const juce::ScopedJuceInitialiser_GUI juceInitialiser;

    auto processor = std::make_unique<SnareSimAudioProcessor>();
    if (program >= 0)
    {
        if (program >= processor->getNumPrograms())
            return usage("--program wants 0.." + juce::String(processor->getNumPrograms() - 1));
        processor->setCurrentProgram(program);
    }

    for (const auto& [id, v] : settings)
        if (auto* p = processor->getValueTreeState().getParameter(juce::String(std::string(snaresim::spec(id).key))))
            p->setValueNotifyingHost(p->convertTo0to1((float) v));

    processor->setRateAndBufferSizeDetails(sampleRate, blockSize);
    processor->prepareToPlay(sampleRate, blockSize);

    // The air box's keep-up verdict (measured in the background), so the editor shows it.
    for (int waited = 0; processor->airBoxVerdict().state == snaresim::KeepUpCheck::State::measuring && waited < 600; ++waited)
        juce::Thread::sleep(100);

    // Three seconds of silence first: the CPU meter's peak (which decays over about two
    // seconds) then shows the strikes, not the first cold blocks.
    play(*processor, (int) (3.0 * sampleRate), {});

    // A centre strike, then an off-centre one while it still rings: an asymmetric pattern on
    // both heads, and the snares slapping the carry head.
    const int second = (int) (0.018 * sampleRate);
    const int total = second + (int) (ringMs * 1.0e-3 * sampleRate);
    play(*processor, total, { { 0, 38, 112 }, { second, 40, 100 } });

    int status = 0;
    {
        std::unique_ptr<juce::AudioProcessorEditor> editor(processor->createEditorIfNeeded());
        auto* snareEditor = dynamic_cast<SnareSimAudioProcessorEditor*>(editor.get());
        if (snareEditor == nullptr)
        {
            std::fprintf(stderr, "snaresim_editor_screenshot: the processor did not create the SnareSim editor\n");
            return 1;
        }

        snareEditor->setSize(width, height);
        snareEditor->refreshFromProcessor();

        const auto image = snareEditor->createComponentSnapshot(snareEditor->getLocalBounds(), true, 1.0f);
        if (writePng(image, output))
            std::printf("%s\n", output.getFullPathName().toRawUTF8());
        else
        {
            std::fprintf(stderr, "snaresim_editor_screenshot: cannot write %s\n", output.getFullPathName().toRawUTF8());
            status = 1;
        }

        if (check && status == 0)
            status = runChecks(*processor, *snareEditor, ringMs);
    } // the editor goes before the processor

    processor->releaseResources();
    return status;
}
