#pragma once
// The editor's dark look: palette, fonts scaled with the window, rotary knobs, linear sliders,
// switch-style toggles and value boxes. One instance per editor (it carries the UI scale).

#include <juce_gui_basics/juce_gui_basics.h>

namespace snaresim::ui
{

namespace Palette
{
inline const juce::Colour background { 0xff15171c };
inline const juce::Colour header { 0xff1b1e24 };
inline const juce::Colour panel { 0xff1f2229 };
inline const juce::Colour panelOutline { 0xff2d313a };
inline const juce::Colour well { 0xff121418 }; // recessed areas: slider tracks, meter, value boxes
inline const juce::Colour track { 0xff343946 };
inline const juce::Colour text { 0xffe7e9ee };
inline const juce::Colour textDim { 0xff9ba2ae };
inline const juce::Colour textFaint { 0xff6b7280 };
inline const juce::Colour accent { 0xffeea63a }; // amber: values, knobs, switches
inline const juce::Colour accentDim { 0xff8a6424 };
inline const juce::Colour good { 0xff5cc27a };
inline const juce::Colour warning { 0xffff5d4f };
inline const juce::Colour caution { 0xffe8c23a };
} // namespace Palette

class EditorLookAndFeel final : public juce::LookAndFeel_V4
{
public:
    // Component property (on a Slider) holding the pixel height of its value box's font at
    // scale 1; the look multiplies it by the UI scale.
    static inline const juce::Identifier valueFontProperty { "snaresimValueFontPx" };

    EditorLookAndFeel();

    void setUiScale(float newScale) noexcept { uiScale = newScale; }
    float getUiScale() const noexcept { return uiScale; }

    // A font of `px` pixels at scale 1.
    juce::Font font(float px, bool bold = false) const;

    // Scaled length: `px` at scale 1.
    float px(float lengthAtScale1) const noexcept { return lengthAtScale1 * uiScale; }
    int pxi(float lengthAtScale1) const noexcept { return juce::roundToInt(lengthAtScale1 * uiScale); }

    // Height of a panel's title strip.
    int panelTitleHeight() const noexcept { return pxi(26.0f); }

    // A panel: rounded background, outline and an upper-case title in its title strip.
    void drawPanel(juce::Graphics&, juce::Rectangle<int> bounds, const juce::String& title) const;

    void drawRotarySlider(juce::Graphics&, int x, int y, int width, int height, float sliderPos, float rotaryStartAngle,
                          float rotaryEndAngle, juce::Slider&) override;

    void drawLinearSlider(juce::Graphics&, int x, int y, int width, int height, float sliderPos, float minSliderPos, float maxSliderPos,
                          juce::Slider::SliderStyle, juce::Slider&) override;

    void drawToggleButton(juce::Graphics&, juce::ToggleButton&, bool highlighted, bool down) override;

    juce::Label* createSliderTextBox(juce::Slider&) override;
    juce::Font getLabelFont(juce::Label&) override;
    juce::Font getComboBoxFont(juce::ComboBox&) override;
    juce::Font getPopupMenuFont() override;
    juce::Font getTextButtonFont(juce::TextButton&, int buttonHeight) override;
    void positionComboBoxText(juce::ComboBox&, juce::Label&) override;

    juce::Rectangle<int> getTooltipBounds(const juce::String& tipText, juce::Point<int> screenPos,
                                          juce::Rectangle<int> parentArea) override;
    void drawTooltip(juce::Graphics&, const juce::String& text, int width, int height) override;

private:
    float uiScale = 1.0f;
};

} // namespace snaresim::ui
