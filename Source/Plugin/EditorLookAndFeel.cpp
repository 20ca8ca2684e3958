#include "EditorLookAndFeel.h"

namespace snaresim::ui
{

namespace
{
constexpr float tooltipFontPx = 13.0f;
constexpr float tooltipMaxWidthPx = 420.0f;
constexpr float tooltipPaddingPx = 8.0f;

juce::TextLayout layoutTooltip(const juce::String& text, const juce::Font& font, float maxWidth)
{
    juce::AttributedString s;
    s.setJustification(juce::Justification::topLeft);
    s.append(text, font, Palette::text);

    juce::TextLayout layout;
    layout.createLayoutWithBalancedLineLengths(s, maxWidth);
    return layout;
}
} // namespace

EditorLookAndFeel::EditorLookAndFeel()
{
    using namespace juce;

    auto scheme = getDarkColourScheme();
    scheme.setUIColour(ColourScheme::windowBackground, Palette::background);
    scheme.setUIColour(ColourScheme::widgetBackground, Palette::well);
    scheme.setUIColour(ColourScheme::menuBackground, Palette::panel);
    scheme.setUIColour(ColourScheme::outline, Palette::panelOutline);
    scheme.setUIColour(ColourScheme::defaultText, Palette::text);
    scheme.setUIColour(ColourScheme::defaultFill, Palette::accent);
    scheme.setUIColour(ColourScheme::highlightedText, Palette::background);
    scheme.setUIColour(ColourScheme::highlightedFill, Palette::accent);
    scheme.setUIColour(ColourScheme::menuText, Palette::text);
    setColourScheme(scheme);

    setColour(ResizableWindow::backgroundColourId, Palette::background);
    setColour(Label::textColourId, Palette::text);

    setColour(Slider::textBoxTextColourId, Palette::text);
    setColour(Slider::textBoxBackgroundColourId, Colours::transparentBlack);
    setColour(Slider::textBoxOutlineColourId, Colours::transparentBlack);
    setColour(Slider::textBoxHighlightColourId, Palette::accent.withAlpha(0.4f));
    setColour(Slider::rotarySliderFillColourId, Palette::accent);
    setColour(Slider::rotarySliderOutlineColourId, Palette::track);
    setColour(Slider::trackColourId, Palette::accent);
    setColour(Slider::backgroundColourId, Palette::track);
    setColour(Slider::thumbColourId, Palette::text);

    setColour(TextEditor::backgroundColourId, Palette::well);
    setColour(TextEditor::textColourId, Palette::text);
    setColour(TextEditor::highlightColourId, Palette::accent.withAlpha(0.4f));
    setColour(TextEditor::highlightedTextColourId, Palette::text);
    setColour(TextEditor::outlineColourId, Palette::panelOutline);
    setColour(TextEditor::focusedOutlineColourId, Palette::accent);
    setColour(CaretComponent::caretColourId, Palette::accent);

    setColour(ComboBox::backgroundColourId, Palette::well);
    setColour(ComboBox::outlineColourId, Palette::panelOutline);
    setColour(ComboBox::textColourId, Palette::text);
    setColour(ComboBox::arrowColourId, Palette::accent);
    setColour(ComboBox::focusedOutlineColourId, Palette::accent);

    setColour(PopupMenu::backgroundColourId, Palette::panel);
    setColour(PopupMenu::textColourId, Palette::text);
    setColour(PopupMenu::highlightedBackgroundColourId, Palette::accent.withAlpha(0.85f));
    setColour(PopupMenu::highlightedTextColourId, Palette::background);

    setColour(ToggleButton::textColourId, Palette::text);
    setColour(ToggleButton::tickColourId, Palette::accent);

    setColour(TooltipWindow::backgroundColourId, Palette::header);
    setColour(TooltipWindow::outlineColourId, Palette::panelOutline);
    setColour(TooltipWindow::textColourId, Palette::text);
}

juce::Font EditorLookAndFeel::font(float px, bool bold) const
{
    return juce::Font(px * uiScale, bold ? juce::Font::bold : juce::Font::plain);
}

void EditorLookAndFeel::drawPanel(juce::Graphics& g, juce::Rectangle<int> bounds, const juce::String& title) const
{
    const auto area = bounds.toFloat().reduced(0.5f);
    const float corner = px(6.0f);

    g.setColour(Palette::panel);
    g.fillRoundedRectangle(area, corner);
    g.setColour(Palette::panelOutline);
    g.drawRoundedRectangle(area, corner, 1.0f);

    if (title.isNotEmpty())
    {
        auto titleFont = font(11.0f, true);
        titleFont.setExtraKerningFactor(0.08f);
        g.setFont(titleFont);
        g.setColour(Palette::textDim);
        g.drawText(title.toUpperCase(), bounds.withHeight(panelTitleHeight()).withTrimmedLeft(pxi(12.0f)).withTrimmedRight(pxi(12.0f)),
                   juce::Justification::centredLeft, true);
    }
}

void EditorLookAndFeel::drawRotarySlider(juce::Graphics& g, int x, int y, int width, int height, float sliderPos, float rotaryStartAngle,
                                         float rotaryEndAngle, juce::Slider& slider)
{
    using namespace juce;

    const auto bounds = Rectangle<int>(x, y, width, height).toFloat();
    const float diameter = jmin(bounds.getWidth(), bounds.getHeight());
    if (diameter < 8.0f)
        return;

    const auto centre = bounds.getCentre();
    const float radius = diameter * 0.5f;
    const float arcThickness = jmax(3.0f, radius * 0.12f);
    const float arcRadius = radius - arcThickness * 0.5f;
    const float angle = rotaryStartAngle + sliderPos * (rotaryEndAngle - rotaryStartAngle);
    const bool enabled = slider.isEnabled();

    // Track and value arcs.
    Path track;
    track.addCentredArc(centre.x, centre.y, arcRadius, arcRadius, 0.0f, rotaryStartAngle, rotaryEndAngle, true);
    g.setColour(Palette::track);
    g.strokePath(track, PathStrokeType(arcThickness, PathStrokeType::curved, PathStrokeType::rounded));

    if (sliderPos > 0.0f)
    {
        Path value;
        value.addCentredArc(centre.x, centre.y, arcRadius, arcRadius, 0.0f, rotaryStartAngle, angle, true);
        g.setColour(enabled ? Palette::accent : Palette::accentDim);
        g.strokePath(value, PathStrokeType(arcThickness, PathStrokeType::curved, PathStrokeType::rounded));
    }

    // The knob body: a slightly lit disc inside the arc.
    const float bodyRadius = arcRadius - arcThickness * 1.1f;
    if (bodyRadius > 4.0f)
    {
        const auto body = Rectangle<float>(bodyRadius * 2.0f, bodyRadius * 2.0f).withCentre(centre);
        g.setGradientFill(ColourGradient(Colour(0xff3a3f4b), centre.x, body.getY(), Colour(0xff262a32), centre.x, body.getBottom(), false));
        g.fillEllipse(body);
        g.setColour(Colour(0xff14161a));
        g.drawEllipse(body, 1.0f);

        // Pointer.
        const float inner = bodyRadius * 0.35f, outer = bodyRadius * 0.88f;
        const auto dir = Point<float>(std::sin(angle), -std::cos(angle));
        g.setColour(enabled ? Palette::text : Palette::textDim);
        g.drawLine({ centre + dir * inner, centre + dir * outer }, jmax(2.0f, bodyRadius * 0.09f));
    }
}

void EditorLookAndFeel::drawLinearSlider(juce::Graphics& g, int x, int y, int width, int height, float sliderPos, float minSliderPos,
                                         float maxSliderPos, juce::Slider::SliderStyle style, juce::Slider& slider)
{
    using namespace juce;

    if (style != Slider::LinearHorizontal)
    {
        LookAndFeel_V4::drawLinearSlider(g, x, y, width, height, sliderPos, minSliderPos, maxSliderPos, style, slider);
        return;
    }

    const auto bounds = Rectangle<int>(x, y, width, height).toFloat();
    const float trackHeight = jlimit(3.0f, 6.0f, bounds.getHeight() * 0.22f);
    const float cy = bounds.getCentreY();
    const auto trackArea = Rectangle<float>(bounds.getX(), cy - trackHeight * 0.5f, bounds.getWidth(), trackHeight);

    g.setColour(Palette::track);
    g.fillRoundedRectangle(trackArea, trackHeight * 0.5f);

    const float fillEnd = jlimit(bounds.getX(), bounds.getRight(), sliderPos);
    g.setColour(slider.isEnabled() ? Palette::accent : Palette::accentDim);
    g.fillRoundedRectangle(trackArea.withRight(fillEnd), trackHeight * 0.5f);

    const float thumb = jlimit(8.0f, 14.0f, bounds.getHeight() * 0.6f);
    const auto thumbArea = Rectangle<float>(thumb, thumb).withCentre({ fillEnd, cy });
    g.setColour(Palette::text);
    g.fillEllipse(thumbArea);
    g.setColour(Palette::background);
    g.drawEllipse(thumbArea, 1.0f);
}

void EditorLookAndFeel::drawToggleButton(juce::Graphics& g, juce::ToggleButton& button, bool highlighted, bool)
{
    using namespace juce;

    // A pill switch on the left, "On" / "Off" next to it.
    const auto bounds = button.getLocalBounds().toFloat();
    const float h = jmin(bounds.getHeight() * 0.75f, 18.0f * uiScale);
    const float w = h * 1.9f;
    const auto pill = Rectangle<float>(bounds.getX() + 2.0f, bounds.getCentreY() - h * 0.5f, w, h);
    const bool on = button.getToggleState();

    g.setColour(on ? Palette::accent : Palette::track);
    g.fillRoundedRectangle(pill, h * 0.5f);
    if (highlighted)
    {
        g.setColour(Palette::text.withAlpha(0.35f));
        g.drawRoundedRectangle(pill, h * 0.5f, 1.0f);
    }

    const float knob = h - 4.0f;
    const float knobX = on ? pill.getRight() - knob - 2.0f : pill.getX() + 2.0f;
    g.setColour(on ? Palette::background : Palette::textDim);
    g.fillEllipse(knobX, pill.getY() + 2.0f, knob, knob);

    g.setColour(on ? Palette::text : Palette::textDim);
    g.setFont(font(12.5f));
    g.drawFittedText(on ? "On" : "Off", button.getLocalBounds().withTrimmedLeft(roundToInt(w + 10.0f)), Justification::centredLeft, 1);
}

juce::Label* EditorLookAndFeel::createSliderTextBox(juce::Slider& slider)
{
    auto* label = LookAndFeel_V4::createSliderTextBox(slider);
    label->setColour(juce::Label::textColourId, Palette::text);
    label->setColour(juce::Label::backgroundColourId, juce::Colours::transparentBlack);
    label->setColour(juce::Label::outlineColourId, juce::Colours::transparentBlack);
    label->setColour(juce::Label::outlineWhenEditingColourId, Palette::accent);
    label->setColour(juce::Label::backgroundWhenEditingColourId, Palette::well);
    label->setMinimumHorizontalScale(0.75f);
    return label;
}

juce::Font EditorLookAndFeel::getLabelFont(juce::Label& label)
{
    if (auto* slider = dynamic_cast<juce::Slider*>(label.getParentComponent()))
    {
        const auto& v = slider->getProperties()[valueFontProperty];
        if (! v.isVoid())
            return font((float) v);
    }

    return label.getFont();
}

juce::Font EditorLookAndFeel::getComboBoxFont(juce::ComboBox&) { return font(13.0f); }

juce::Font EditorLookAndFeel::getPopupMenuFont() { return font(14.0f); }

juce::Font EditorLookAndFeel::getTextButtonFont(juce::TextButton&, int buttonHeight)
{
    return juce::Font(juce::jmin(14.0f * uiScale, (float) buttonHeight * 0.6f));
}

void EditorLookAndFeel::positionComboBoxText(juce::ComboBox& box, juce::Label& label)
{
    label.setBounds(1, 1, box.getWidth() - box.getHeight(), box.getHeight() - 2);
    label.setFont(getComboBoxFont(box));
}

juce::Rectangle<int> EditorLookAndFeel::getTooltipBounds(const juce::String& tipText, juce::Point<int> screenPos,
                                                         juce::Rectangle<int> parentArea)
{
    const auto layout = layoutTooltip(tipText, font(tooltipFontPx), tooltipMaxWidthPx * uiScale);
    const float pad = tooltipPaddingPx * uiScale;
    const int w = (int) std::ceil(layout.getWidth() + pad * 2.0f);
    const int h = (int) std::ceil(layout.getHeight() + pad * 2.0f);

    return juce::Rectangle<int>(screenPos.x > parentArea.getCentreX() ? screenPos.x - (w + 12) : screenPos.x + 24,
                                screenPos.y > parentArea.getCentreY() ? screenPos.y - (h + 6) : screenPos.y + 6, w, h)
        .constrainedWithin(parentArea);
}

void EditorLookAndFeel::drawTooltip(juce::Graphics& g, const juce::String& text, int width, int height)
{
    const auto bounds = juce::Rectangle<int>(width, height).toFloat();
    g.setColour(findColour(juce::TooltipWindow::backgroundColourId));
    g.fillRoundedRectangle(bounds, 5.0f);
    g.setColour(findColour(juce::TooltipWindow::outlineColourId));
    g.drawRoundedRectangle(bounds.reduced(0.5f), 5.0f, 1.0f);

    const float pad = tooltipPaddingPx * uiScale;
    layoutTooltip(text, font(tooltipFontPx), tooltipMaxWidthPx * uiScale).draw(g, bounds.reduced(pad));
}

} // namespace snaresim::ui
