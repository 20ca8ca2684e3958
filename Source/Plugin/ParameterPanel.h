#pragma once
// Controls built from the parameter table (snaresim::parameterSpecs()): one ParameterControl
// per parameter (slider for continuous and integer, switch for toggles, combo box for choices,
// each attached to the AudioProcessorValueTreeState), grouped in ParameterPanels by the schema's
// groups; values written and read by the schema's text rule (ParameterText.h). A parameter
// added to the schema appears here without editor changes.

#include "EditorLookAndFeel.h"
#include "Parameters.h"

#include <juce_audio_processors/juce_audio_processors.h>

#include <memory>
#include <vector>

namespace snaresim::ui
{

class ParameterControl final : public juce::Component
{
public:
    enum class Style
    {
        largeKnob, // the three main controls: name above, big knob, value below
        row        // name on the left, slider / switch / combo box and value on the right
    };

    ParameterControl(juce::AudioProcessorValueTreeState&, const ParameterSpec&, Style, EditorLookAndFeel&);
    ~ParameterControl() override;

    const ParameterSpec& getSpec() const noexcept { return spec; }

    void resized() override;

    juce::Slider* getSlider() noexcept { return slider.get(); }

private:
    juce::String makeTooltip() const;

    const ParameterSpec& spec;
    const Style style;
    EditorLookAndFeel& look;

    juce::Label nameLabel;
    std::unique_ptr<juce::Slider> slider;
    std::unique_ptr<juce::ToggleButton> toggle;
    std::unique_ptr<juce::ComboBox> combo;

    std::unique_ptr<juce::AudioProcessorValueTreeState::SliderAttachment> sliderAttachment;
    std::unique_ptr<juce::AudioProcessorValueTreeState::ButtonAttachment> buttonAttachment;
    std::unique_ptr<juce::AudioProcessorValueTreeState::ComboBoxAttachment> comboAttachment;

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR(ParameterControl)
};

// A titled panel of the parameters of one group.
class ParameterPanel final : public juce::Component
{
public:
    ParameterPanel(juce::String groupKey, juce::String title, ParameterControl::Style, EditorLookAndFeel&);

    void addParameter(juce::AudioProcessorValueTreeState&, const ParameterSpec&);

    const juce::String& getGroupKey() const noexcept { return groupKey; }
    int getNumControls() const noexcept { return (int) controls.size(); }
    ParameterControl* getControl(int index) const { return controls[(size_t) index].get(); }

    // Height wanted for rows of `rowHeight` pixels (row style).
    int getPreferredHeight(int rowHeight) const;

    // Row height used by resized() (row style).
    void setRowHeight(int newRowHeight);

    void paint(juce::Graphics&) override;
    void resized() override;

private:
    juce::String groupKey, title;
    ParameterControl::Style style;
    EditorLookAndFeel& look;
    int rowHeight = 26;
    std::vector<std::unique_ptr<ParameterControl>> controls;

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR(ParameterPanel)
};

// One panel per group of the schema (parameterGroups()), in its order, the groups in
// `largeKnobGroups` with large knobs and the rest as rows.
std::vector<std::unique_ptr<ParameterPanel>> makeParameterPanels(juce::AudioProcessorValueTreeState&, EditorLookAndFeel&,
                                                                 const juce::StringArray& largeKnobGroups);

} // namespace snaresim::ui
