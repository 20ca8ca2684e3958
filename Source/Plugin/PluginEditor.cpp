#include "PluginEditor.h"

#include "PresetFile.h"
#include "PresetFileActions.h"

#include "Articulations.h"
#include "PluginProcessor.h"

#include <algorithm>
#include <limits>

namespace
{
using namespace snaresim::ui;

juce::String toJuce(std::string_view s) { return juce::String(juce::CharPointer_UTF8(std::string(s).c_str())); }

// "Centre strike (GM acoustic snare)" -> "Centre strike".
juce::String shortName(std::string_view name) { return toJuce(name).upToFirstOccurrenceOf(" (", false, false).trim(); }

juce::String noteMapLine()
{
    juce::StringArray entries;
    for (const auto& a : snaresim::articulations())
        entries.add(juce::String(a.note) + " " + shortName(a.name));

    const juce::String dot(juce::CharPointer_UTF8("  \xc2\xb7  "));
    return "MIDI notes   " + entries.joinIntoString(dot) + dot + "any other note: main strike   |   velocity sets the strike speed";
}

juce::String noteMapTooltip()
{
    juce::String tip("The note map (GM drum map where it fits):\n");
    for (const auto& a : snaresim::articulations())
        tip << "  " << a.note << "  " << toJuce(a.name) << "\n";
    tip << "Any other note strikes at the Strike position control.";
    return tip;
}

// Splits `heights` (in order) into `columns` consecutive runs minimising the tallest run,
// `gap` between items of a run. Returns the index of each run's first item.
std::vector<size_t> partitionColumns(const std::vector<int>& heights, size_t columns, int gap)
{
    const size_t n = heights.size();
    columns = std::clamp<size_t>(columns, 1, std::max<size_t>(n, 1));

    const auto runHeight = [&](size_t from, size_t to) // [from, to)
    {
        int h = 0;
        for (size_t i = from; i < to; ++i)
            h += heights[i] + (i > from ? gap : 0);
        return h;
    };

    // best[c][i]: the smallest tallest-run height for the first i items in c runs.
    constexpr int inf = std::numeric_limits<int>::max();
    std::vector<std::vector<int>> best(columns + 1, std::vector<int>(n + 1, inf));
    std::vector<std::vector<size_t>> split(columns + 1, std::vector<size_t>(n + 1, 0));
    best[0][0] = 0;

    for (size_t c = 1; c <= columns; ++c)
        for (size_t i = c; i <= n; ++i)
            for (size_t j = c - 1; j < i; ++j)
                if (best[c - 1][j] != inf)
                {
                    const int h = std::max(best[c - 1][j], runHeight(j, i));
                    if (h < best[c][i])
                    {
                        best[c][i] = h;
                        split[c][i] = j;
                    }
                }

    std::vector<size_t> starts(columns, 0);
    size_t i = n;
    for (size_t c = columns; c >= 1; --c)
    {
        starts[c - 1] = split[c][i];
        i = split[c][i];
    }
    return starts;
}
} // namespace

//==============================================================================
SnareSimAudioProcessorEditor::SnareSimAudioProcessorEditor(SnareSimAudioProcessor& p)
    : AudioProcessorEditor(p), processor(p), drumView(look), cpuMeter(look),
      fallbacksReadout(look, "Solver fallbacks",
                       "Contact solves (mallet or snares) that reached the Newton iteration cap and used the "
                       "fallback. Turns red above 0: try a coarser quality or a softer mallet."),
      resetsReadout(look, "Non-finite resets", "Times the simulation produced a non-finite value and was reset silently."),
      newtonReadout(look, "Max Newton iter.", "The largest number of Newton iterations any contact solve has needed.")
{
    setLookAndFeel(&look);

    // Preset selector: the processor's programs (the factory presets).
    presetLabel.setText("Preset", juce::dontSendNotification);
    presetLabel.setColour(juce::Label::textColourId, Palette::textDim);
    presetLabel.setJustificationType(juce::Justification::centredRight);
    addAndMakeVisible(presetLabel);

    presetBox.setTooltip("Factory presets: choosing one sets every parameter but Lower Quality when slow.");
    presetBox.setTitle("Preset");
    presetBox.onChange = [this] {
        const int index = presetBox.getSelectedItemIndex();
        if (index >= 0 && index < processor.getNumPrograms())
            processor.setCurrentProgram(index);
    };
    addAndMakeVisible(presetBox);
    refreshPresetList();

    // Preset files (.snarepreset), the format of the factory presets and of snaresim-render --preset FILE.
    presetFileButton.setTooltip(
        "Load a preset file (.snarepreset: sets every parameter but Lower Quality when slow, the defaults for those it does not list), "
        "or save the parameters as one (snaresim-render --preset FILE reads it too).");
    presetFileButton.setTitle("Preset file");
    presetFileButton.onClick = [this] {
        juce::PopupMenu menu;
        menu.addItem("Load preset file...", [this] { choosePresetFile(false); });
        menu.addItem("Save preset file...", [this] { choosePresetFile(true); });
        menu.showMenuAsync(juce::PopupMenu::Options().withTargetComponent(&presetFileButton));
    };
    addAndMakeVisible(presetFileButton);

    // Parameters: the "main" group as large knobs, every other group as rows.
    panels = makeParameterPanels(processor.getValueTreeState(), look, { "main" });
    auto mainIt = std::find_if(panels.begin(), panels.end(), [](const auto& panel) { return panel->getGroupKey() == "main"; });
    if (mainIt != panels.end() && mainIt != panels.begin())
        std::rotate(panels.begin(), mainIt, std::next(mainIt));
    mainPanel = mainIt != panels.end() ? panels.front().get() : nullptr;

    for (auto& panel : panels)
        addAndMakeVisible(*panel);

    addAndMakeVisible(drumView);
    addAndMakeVisible(cpuMeter);
    addAndMakeVisible(fallbacksReadout);
    addAndMakeVisible(resetsReadout);
    addAndMakeVisible(newtonReadout);

    noteMapLabel.setText(noteMapLine(), juce::dontSendNotification);
    noteMapLabel.setTooltip(noteMapTooltip());
    noteMapLabel.setColour(juce::Label::textColourId, Palette::textDim);
    noteMapLabel.setJustificationType(juce::Justification::centredLeft);
    noteMapLabel.setMinimumHorizontalScale(0.7f);
    noteMapLabel.setBorderSize({});
    addAndMakeVisible(noteMapLabel);

    setResizable(true, true);
    setResizeLimits(minWidth, minHeight, maxWidth, maxHeight);
    setSize(defaultWidth, defaultHeight);

    refreshFromProcessor();
    startTimerHz(refreshRateHz);
}

SnareSimAudioProcessorEditor::~SnareSimAudioProcessorEditor()
{
    stopTimer();
    setLookAndFeel(nullptr);
}

//==============================================================================
void SnareSimAudioProcessorEditor::choosePresetFile(bool save)
{
    const auto folder = juce::File::getSpecialLocation(juce::File::userDocumentsDirectory);
    const juce::String pattern = "*" + juce::String(std::string(snaresim::kPresetFileExtension));
    presetChooser = std::make_unique<juce::FileChooser>(save ? "Save preset file" : "Load preset file", folder, pattern);
    const int browserFlags = juce::FileBrowserComponent::canSelectFiles |
                             (save ? juce::FileBrowserComponent::saveMode | juce::FileBrowserComponent::warnAboutOverwriting
                                   : juce::FileBrowserComponent::openMode);
    presetChooser->launchAsync(browserFlags, [this, save](const juce::FileChooser& chooser) {
        auto file = chooser.getResult();
        if (file == juce::File())
            return;
        if (save && ! file.hasFileExtension(juce::String(std::string(snaresim::kPresetFileExtension))))
            file = file.withFileExtension(juce::String(std::string(snaresim::kPresetFileExtension)));
        const auto error = save ? snaresim::ui::savePresetFile(processor, file) : snaresim::ui::loadPresetFile(processor, file);
        if (error.isNotEmpty())
            juce::AlertWindow::showMessageBoxAsync(juce::MessageBoxIconType::WarningIcon, save ? "Preset not saved" : "Preset not loaded",
                                                   error);
    });
}

void SnareSimAudioProcessorEditor::refreshPresetList()
{
    presetBox.clear(juce::dontSendNotification);

    const int numPrograms = processor.getNumPrograms();
    for (int i = 0; i < numPrograms; ++i)
    {
        auto name = processor.getProgramName(i);
        presetBox.addItem(name.isNotEmpty() ? name : "Program " + juce::String(i + 1), i + 1);
    }

    presetBox.setSelectedItemIndex(processor.getCurrentProgram(), juce::dontSendNotification);
}

void SnareSimAudioProcessorEditor::timerCallback() { refreshFromProcessor(); }

void SnareSimAudioProcessorEditor::refreshFromProcessor()
{
    // Lock-free: the snapshot's triple buffer and the processor's atomics.
    if (processor.pullSnapshot(snapshot))
        drumView.update(snapshot);

    cpuMeter.setLoad(processor.getCpuLoad(), processor.getPeakCpuLoad());

    const long fallbacks = processor.getSolverFallbacks();
    const int resets = processor.getNonFiniteResets();
    fallbacksReadout.setValue(fallbacks, fallbacks > 0);
    resetsReadout.setValue(resets, resets > 0);
    newtonReadout.setValue(processor.getMaxNewtonIterations(), false);
    drumView.setNotice(processor.playNotice());

    // Follow program changes made by the host.
    const int program = processor.getCurrentProgram();
    if (program != presetBox.getSelectedItemIndex() && program >= 0 && program < presetBox.getNumItems())
        presetBox.setSelectedItemIndex(program, juce::dontSendNotification);
}

//==============================================================================
void SnareSimAudioProcessorEditor::paint(juce::Graphics& g)
{
    g.fillAll(Palette::background);

    // Header: title and subtitle on the left.
    g.setColour(Palette::header);
    g.fillRect(getLocalBounds().withHeight(headerArea.getBottom() + look.pxi(6.0f)));
    g.setColour(Palette::panelOutline);
    g.fillRect(0, headerArea.getBottom() + look.pxi(6.0f), getWidth(), 1);

    auto titleArea = headerArea.withWidth(look.pxi(190.0f));
    g.setColour(Palette::text);
    g.setFont(look.font(23.0f, true));
    g.drawText("SnareSim", titleArea.removeFromTop(titleArea.getHeight() * 3 / 5), juce::Justification::bottomLeft, false);
    g.setColour(Palette::textDim);
    g.setFont(look.font(11.0f));
    g.drawText("physically simulated snare drum", titleArea, juce::Justification::topLeft, false);

    // Accent mark left of the note map.
    g.setColour(Palette::accent);
    const auto noteArea = noteMapLabel.getBounds();
    g.fillRoundedRectangle(juce::Rectangle<float>((float) noteArea.getX() - look.px(10.0f), (float) noteArea.getCentreY() - look.px(5.0f),
                                                  look.px(3.0f), look.px(10.0f)),
                           1.0f);
}

void SnareSimAudioProcessorEditor::resized()
{
    const float scale =
        juce::jlimit(0.8f, 2.4f, juce::jmin((float) getWidth() / (float) defaultWidth, (float) getHeight() / (float) defaultHeight));
    look.setUiScale(scale);

    const int gap = look.pxi(8.0f);
    auto area = getLocalBounds().reduced(look.pxi(12.0f), look.pxi(8.0f));

    // Header: title | preset ........ CPU meter | readouts.
    headerArea = area.removeFromTop(look.pxi(44.0f));
    area.removeFromTop(look.pxi(16.0f));
    {
        auto header = headerArea;
        header.removeFromLeft(look.pxi(200.0f));

        const int controlH = look.pxi(28.0f);
        presetLabel.setFont(look.font(13.0f));
        presetLabel.setBounds(header.removeFromLeft(look.pxi(52.0f)).withSizeKeepingCentre(look.pxi(52.0f), controlH));
        header.removeFromLeft(look.pxi(8.0f));
        presetBox.setBounds(header.removeFromLeft(look.pxi(176.0f)).withSizeKeepingCentre(look.pxi(176.0f), controlH));
        header.removeFromLeft(look.pxi(6.0f));
        presetFileButton.setBounds(header.removeFromLeft(look.pxi(44.0f)).withSizeKeepingCentre(look.pxi(44.0f), controlH));

        const int readoutH = look.pxi(34.0f);
        for (auto* readout : { &newtonReadout, &resetsReadout, &fallbacksReadout })
        {
            const int w = readout->getPreferredWidth();
            readout->setBounds(header.removeFromRight(w).withSizeKeepingCentre(w, readoutH));
            header.removeFromRight(look.pxi(16.0f));
        }
        // The meter takes what is left, keeping clear of the preset box.
        const int meterW = juce::jlimit(look.pxi(100.0f), look.pxi(190.0f), header.getWidth() - look.pxi(28.0f));
        cpuMeter.setBounds(header.removeFromRight(meterW).withSizeKeepingCentre(meterW, readoutH));
    }

    // Footer: the note map.
    auto footer = area.removeFromBottom(look.pxi(18.0f));
    area.removeFromBottom(look.pxi(8.0f));
    noteMapLabel.setFont(look.font(12.0f));
    noteMapLabel.setBounds(footer.withTrimmedLeft(look.pxi(12.0f)));

    // Top row: the large knobs and the drum picture.
    auto top = area.removeFromTop(juce::roundToInt((float) area.getHeight() * 0.42f));
    area.removeFromTop(gap);

    if (mainPanel != nullptr)
    {
        const int mainW = juce::roundToInt((float) top.getWidth() * 0.45f);
        mainPanel->setBounds(top.removeFromLeft(mainW));
        top.removeFromLeft(gap);
    }
    drumView.setBounds(top);

    layoutParameterPanels(area);
}

void SnareSimAudioProcessorEditor::layoutParameterPanels(juce::Rectangle<int> area)
{
    std::vector<snaresim::ui::ParameterPanel*> rows;
    for (auto& panel : panels)
        if (panel.get() != mainPanel)
            rows.push_back(panel.get());

    if (rows.empty())
        return;

    const int gap = look.pxi(8.0f);
    const size_t columns = (size_t) juce::jlimit(1, (int) rows.size(), area.getWidth() / look.pxi(300.0f));

    // Rows as tall as wanted, less if the tallest column does not fit.
    int rowHeight = look.pxi(26.0f);
    std::vector<size_t> starts;
    for (;;)
    {
        std::vector<int> heights;
        for (auto* panel : rows)
            heights.push_back(panel->getPreferredHeight(rowHeight));

        starts = partitionColumns(heights, columns, gap);

        int tallest = 0;
        for (size_t c = 0; c < starts.size(); ++c)
        {
            const size_t end = c + 1 < starts.size() ? starts[c + 1] : rows.size();
            int h = 0;
            for (size_t i = starts[c]; i < end; ++i)
                h += heights[i] + (i > starts[c] ? gap : 0);
            tallest = std::max(tallest, h);
        }

        if (tallest <= area.getHeight() || rowHeight <= look.pxi(18.0f))
            break;
        --rowHeight;
    }

    const int numColumns = (int) starts.size();
    const int columnW = (area.getWidth() - gap * (numColumns - 1)) / numColumns;

    for (int c = 0; c < numColumns; ++c)
    {
        auto column = area.removeFromLeft(c + 1 < numColumns ? columnW : area.getWidth());
        area.removeFromLeft(gap);

        const size_t end = (size_t) c + 1 < starts.size() ? starts[(size_t) c + 1] : rows.size();
        for (size_t i = starts[(size_t) c]; i < end; ++i)
        {
            auto* panel = rows[i];
            panel->setRowHeight(rowHeight);
            // The last panel of a column fills it, so the columns end together.
            const int h = i + 1 < end ? panel->getPreferredHeight(rowHeight) : column.getHeight();
            panel->setBounds(column.removeFromTop(h));
            column.removeFromTop(gap);
        }
    }
}
