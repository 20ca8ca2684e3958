#pragma once
// The SnareSim editor: the three main controls as large knobs, the other parameters in
// panels by the table's group, a preset selector, the live picture of the drum, a CPU meter and
// the engine's status counters, and the MIDI note map.
//
// Everything parameter-related is built from snaresim::parameterSpecs() and attached to the
// processor's AudioProcessorValueTreeState. A 30 Hz timer pulls the newest DrumSnapshot from
// the processor (pullSnapshot) and reads its meters (atomics); it never locks the audio thread.

#include "DrumSnapshot.h"
#include "DrumView.h"
#include "EditorLookAndFeel.h"
#include "ParameterPanel.h"
#include "StatusMeters.h"

#include <juce_audio_processors/juce_audio_processors.h>

#include <memory>
#include <vector>

class SnareSimAudioProcessor;

class SnareSimAudioProcessorEditor final : public juce::AudioProcessorEditor, private juce::Timer
{
public:
    static constexpr int defaultWidth = 1000;
    static constexpr int defaultHeight = 640;
    static constexpr int minWidth = 880;
    static constexpr int minHeight = 560;
    static constexpr int maxWidth = 2400;
    static constexpr int maxHeight = 1600;
    static constexpr int refreshRateHz = 30;

    explicit SnareSimAudioProcessorEditor(SnareSimAudioProcessor&);
    ~SnareSimAudioProcessorEditor() override;

    // What the timer does: pull the newest snapshot, read the meters, follow the program.
    // Public for tools that render the editor without a running message loop.
    void refreshFromProcessor();

    const snaresim::ui::DrumView& getDrumView() const noexcept { return drumView; }

    void paint(juce::Graphics&) override;
    void resized() override;

private:
    void timerCallback() override;
    void layoutParameterPanels(juce::Rectangle<int> area);
    void refreshPresetList();
    void choosePresetFile(bool save);

    SnareSimAudioProcessor& processor;

    // Declared first: destroyed after every component that uses it.
    snaresim::ui::EditorLookAndFeel look;

    juce::TooltipWindow tooltipWindow { this, 700 };

    juce::Label presetLabel;
    juce::ComboBox presetBox;
    juce::TextButton presetFileButton { "File" };     // Load / Save a preset file
    std::unique_ptr<juce::FileChooser> presetChooser; // the open load / save dialog

    std::vector<std::unique_ptr<snaresim::ui::ParameterPanel>> panels; // panels[0]: the large knobs
    snaresim::ui::ParameterPanel* mainPanel = nullptr;

    snaresim::ui::DrumView drumView;
    snaresim::ui::CpuMeter cpuMeter;
    snaresim::ui::StatusReadout fallbacksReadout, resetsReadout, newtonReadout;

    juce::Label noteMapLabel;

    snaresim::DrumSnapshot snapshot; // reused: filled by pullSnapshot
    juce::Rectangle<int> headerArea;

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR(SnareSimAudioProcessorEditor)
};
