#include "ParameterPanel.h"

#include "ParameterText.h"

#include <algorithm>
#include <iterator>

namespace snaresim::ui
{

namespace
{
juce::String toJuce(std::string_view s) { return juce::String(juce::CharPointer_UTF8(std::string(s).c_str())); }

// Font sizes at scale 1.
constexpr float largeNamePx = 15.0f;
constexpr float largeValuePx = 19.0f;
constexpr float rowNamePx = 12.5f;
constexpr float rowValuePx = 12.5f;
} // namespace

//==============================================================================
ParameterControl::ParameterControl(juce::AudioProcessorValueTreeState& state, const ParameterSpec& specToUse, Style styleToUse,
                                   EditorLookAndFeel& lookToUse)
    : spec(specToUse), style(styleToUse), look(lookToUse)
{
    const auto id = toJuce(spec.key);
    const auto tooltip = makeTooltip();

    nameLabel.setText(toJuce(spec.name), juce::dontSendNotification);
    nameLabel.setColour(juce::Label::textColourId, style == Style::largeKnob ? Palette::text : Palette::textDim);
    nameLabel.setJustificationType(style == Style::largeKnob ? juce::Justification::centred : juce::Justification::centredLeft);
    nameLabel.setMinimumHorizontalScale(0.92f);
    nameLabel.setBorderSize({});
    nameLabel.setTooltip(tooltip);
    nameLabel.setInterceptsMouseClicks(true, false);
    addAndMakeVisible(nameLabel);

    switch (spec.kind)
    {
        case ParamKind::toggle:
        {
            toggle = std::make_unique<juce::ToggleButton>();
            toggle->setTooltip(tooltip);
            toggle->setTitle(toJuce(spec.name));
            addAndMakeVisible(*toggle);
            buttonAttachment = std::make_unique<juce::AudioProcessorValueTreeState::ButtonAttachment>(state, id, *toggle);
            break;
        }

        case ParamKind::choice:
        {
            combo = std::make_unique<juce::ComboBox>();
            combo->setTooltip(tooltip);
            combo->setTitle(toJuce(spec.name));

            for (int i = 0; i < numChoiceNames(spec); ++i)
                combo->addItem(toJuce(formatValue(spec, i)), i + 1);

            addAndMakeVisible(*combo);
            comboAttachment = std::make_unique<juce::AudioProcessorValueTreeState::ComboBoxAttachment>(state, id, *combo);
            break;
        }

        case ParamKind::continuous:
        case ParamKind::integer:
        default:
        {
            slider = std::make_unique<juce::Slider>();
            slider->setTooltip(tooltip);
            slider->setTitle(toJuce(spec.name));

            if (style == Style::largeKnob)
            {
                slider->setSliderStyle(juce::Slider::RotaryHorizontalVerticalDrag);
                slider->setRotaryParameters(juce::degreesToRadians(-135.0f), juce::degreesToRadians(135.0f), true);
                slider->setTextBoxStyle(juce::Slider::TextBoxBelow, false, 120, 28);
                slider->getProperties().set(EditorLookAndFeel::valueFontProperty, largeValuePx);
            }
            else
            {
                slider->setSliderStyle(juce::Slider::LinearHorizontal);
                slider->setTextBoxStyle(juce::Slider::TextBoxRight, false, 90, 22);
                slider->getProperties().set(EditorLookAndFeel::valueFontProperty, rowValuePx);
            }

            slider->setVelocityBasedMode(false);
            slider->setScrollWheelEnabled(true);
            addAndMakeVisible(*slider);

            sliderAttachment = std::make_unique<juce::AudioProcessorValueTreeState::SliderAttachment>(state, id, *slider);

            // The attachment installs the parameter's float text conversion; show the schema's at double precision.
            const auto& s = spec;
            auto* shown = slider.get();
            slider->textFromValueFunction = [&s](double v) { return toJuce(formatValue(s, v)); };
            slider->valueFromTextFunction = [&s, shown](const juce::String& text) {
                return parseValue(s, text.toStdString(), BareNumber::writtenUnit).value_or(shown->getValue());
            };
            slider->setDoubleClickReturnValue(true, spec.defaultValue);
            slider->updateText();
            break;
        }
    }
}

ParameterControl::~ParameterControl()
{
    // Attachments first: they refer to the components.
    sliderAttachment.reset();
    buttonAttachment.reset();
    comboAttachment.reset();
}

juce::String ParameterControl::makeTooltip() const
{
    auto tip = toJuce(spec.name) + ": " + toJuce(spec.help) + ".";

    if (spec.kind == ParamKind::continuous || spec.kind == ParamKind::integer)
        tip << "\nRange " << toJuce(formatValue(spec, spec.minValue)) << " to " << toJuce(formatValue(spec, spec.maxValue)) << ", default "
            << toJuce(formatValue(spec, spec.defaultValue)) << ". Double-click resets.";

    if (spec.needs == ChangeNeeds::newGrid)
        tip << "\nChanging it builds new grids (the sound crossfades).";
    else if (spec.needs == ChangeNeeds::newModel)
        tip << "\nChanging it builds a new model (the sound crossfades).";

    return tip;
}

void ParameterControl::resized()
{
    auto area = getLocalBounds();

    if (style == Style::largeKnob)
    {
        // Name, knob and value as one block, centred vertically.
        const int nameH = look.pxi(22.0f);
        const int textH = look.pxi(28.0f);
        const int gap = look.pxi(6.0f);
        const int knob = juce::jmax(16, juce::jmin(area.getWidth(), area.getHeight() - nameH - textH - gap));
        auto block = area.withSizeKeepingCentre(area.getWidth(), juce::jmin(area.getHeight(), nameH + gap + knob + textH));

        nameLabel.setFont(look.font(largeNamePx, true));
        nameLabel.setBounds(block.removeFromTop(nameH));
        block.removeFromTop(gap);

        if (slider != nullptr)
        {
            slider->setTextBoxStyle(juce::Slider::TextBoxBelow, false, block.getWidth(), textH);
            slider->setBounds(block);
        }
        else if (toggle != nullptr)
            toggle->setBounds(block.withSizeKeepingCentre(look.pxi(80.0f), look.pxi(26.0f)));
        else if (combo != nullptr)
            combo->setBounds(block.withSizeKeepingCentre(block.getWidth() - look.pxi(8.0f), look.pxi(26.0f)));
        return;
    }

    // Row: name | control.
    const int nameW = juce::roundToInt((float) area.getWidth() * 0.44f);
    nameLabel.setFont(look.font(rowNamePx));
    nameLabel.setBounds(area.removeFromLeft(nameW));
    area.removeFromLeft(look.pxi(6.0f));

    const int controlH = juce::jmin(area.getHeight(), look.pxi(24.0f));

    if (slider != nullptr)
    {
        const int valueW = juce::jlimit(look.pxi(70.0f), look.pxi(100.0f), juce::roundToInt((float) area.getWidth() * 0.48f));
        slider->setTextBoxStyle(juce::Slider::TextBoxRight, false, valueW, controlH);
        slider->setBounds(area.withSizeKeepingCentre(area.getWidth(), controlH));
    }
    else if (toggle != nullptr)
        toggle->setBounds(area.withSizeKeepingCentre(area.getWidth(), controlH));
    else if (combo != nullptr)
        combo->setBounds(area.withSizeKeepingCentre(area.getWidth(), juce::jmin(controlH, look.pxi(22.0f))));
}

//==============================================================================
ParameterPanel::ParameterPanel(juce::String key, juce::String titleToUse, ParameterControl::Style styleToUse, EditorLookAndFeel& lookToUse)
    : groupKey(std::move(key)), title(std::move(titleToUse)), style(styleToUse), look(lookToUse)
{
    setTitle(title);
}

void ParameterPanel::addParameter(juce::AudioProcessorValueTreeState& state, const ParameterSpec& spec)
{
    controls.push_back(std::make_unique<ParameterControl>(state, spec, style, look));
    addAndMakeVisible(*controls.back());
}

int ParameterPanel::getPreferredHeight(int rows) const { return look.panelTitleHeight() + (int) controls.size() * rows + look.pxi(8.0f); }

void ParameterPanel::setRowHeight(int newRowHeight)
{
    if (newRowHeight != rowHeight)
    {
        rowHeight = newRowHeight;
        resized();
    }
}

void ParameterPanel::paint(juce::Graphics& g) { look.drawPanel(g, getLocalBounds(), title); }

void ParameterPanel::resized()
{
    auto area = getLocalBounds();
    area.removeFromTop(look.panelTitleHeight());
    area = area.reduced(look.pxi(12.0f), 0).withTrimmedBottom(look.pxi(8.0f));

    if (controls.empty())
        return;

    if (style == ParameterControl::Style::largeKnob)
    {
        const int cellW = area.getWidth() / (int) controls.size();
        for (auto& c : controls)
            c->setBounds(area.removeFromLeft(cellW).reduced(look.pxi(6.0f), 0));
        return;
    }

    // Rows spread over the panel's height, up to a third taller than asked.
    const int spread = area.getHeight() / (int) controls.size();
    const int h = juce::jlimit(rowHeight, rowHeight * 4 / 3, spread);
    for (auto& c : controls)
        c->setBounds(area.removeFromTop(h));
}

//==============================================================================
std::vector<std::unique_ptr<ParameterPanel>> makeParameterPanels(juce::AudioProcessorValueTreeState& state, EditorLookAndFeel& look,
                                                                 const juce::StringArray& largeKnobGroups)
{
    std::vector<std::unique_ptr<ParameterPanel>> panels;

    // The schema's groups in its order, each with its parameters in table order.
    for (const auto& group : parameterGroups())
    {
        const auto key = toJuce(group.key);
        const auto style = largeKnobGroups.contains(key) ? ParameterControl::Style::largeKnob : ParameterControl::Style::row;
        std::unique_ptr<ParameterPanel> panel;

        for (const auto& spec : parameterSpecs())
        {
            if (spec.group != group.key)
                continue;
            if (panel == nullptr)
                panel = std::make_unique<ParameterPanel>(key, toJuce(group.title), style, look);
            panel->addParameter(state, spec);
        }

        if (panel != nullptr)
            panels.push_back(std::move(panel));
    }

    return panels;
}

} // namespace snaresim::ui
