#include "StatusMeters.h"

#include <cmath>

namespace snaresim::ui
{

namespace
{
constexpr float captionPx = 10.0f;
constexpr float valuePx = 14.0f;

juce::Font captionFont(const EditorLookAndFeel& look)
{
    auto f = look.font(captionPx, true);
    f.setExtraKerningFactor(0.06f);
    return f;
}

juce::Colour loadColour(float load) { return load >= 0.9f ? Palette::warning : load >= 0.6f ? Palette::caution : Palette::good; }
} // namespace

//==============================================================================
CpuMeter::CpuMeter(EditorLookAndFeel& lookToUse) : look(lookToUse)
{
    setTooltip("Audio thread load: the time spent rendering each block as a percentage of the block's "
               "duration (the deadline). Above 100 % the audio drops out. The thin mark is the peak.");
    setTitle("CPU load");
}

void CpuMeter::setLoad(float newLoad, float newPeak)
{
    load = std::isfinite(newLoad) ? juce::jmax(0.0f, newLoad) : 0.0f;
    peak = std::isfinite(newPeak) ? juce::jmax(load, newPeak) : load;

    const int percent = juce::roundToInt(load * 100.0f);
    const int peakPercent = juce::roundToInt(peak * 100.0f);

    if (percent != shownPercent || peakPercent != shownPeakPercent)
    {
        shownPercent = percent;
        shownPeakPercent = peakPercent;
        repaint();
    }
}

void CpuMeter::paint(juce::Graphics& g)
{
    auto area = getLocalBounds();

    // Caption line: "CPU" on the left, "peak 31 %" on the right.
    auto top = area.removeFromTop(area.getHeight() / 2);
    g.setFont(captionFont(look));
    g.setColour(Palette::textDim);
    g.drawText("CPU", top, juce::Justification::bottomLeft, false);
    g.drawText("peak " + juce::String(juce::jmax(0, shownPeakPercent)) + " %", top, juce::Justification::bottomRight, false);

    // Bar with the load and a peak mark, the percentage to its right.
    area.removeFromTop(look.pxi(3.0f));
    const int textW = look.pxi(46.0f);
    auto text = area.removeFromRight(textW);
    auto bar = area.withTrimmedRight(look.pxi(6.0f)).withSizeKeepingCentre(area.getWidth() - look.pxi(6.0f), look.pxi(10.0f)).toFloat();
    bar.setX((float) area.getX());

    g.setColour(Palette::well);
    g.fillRoundedRectangle(bar, 3.0f);
    g.setColour(Palette::panelOutline);
    g.drawRoundedRectangle(bar, 3.0f, 1.0f);

    const float fill = juce::jlimit(0.0f, 1.0f, load);
    if (fill > 0.0f)
    {
        g.setColour(loadColour(load));
        g.fillRoundedRectangle(bar.withWidth(juce::jmax(3.0f, bar.getWidth() * fill)), 3.0f);
    }

    const float peakX = bar.getX() + bar.getWidth() * juce::jlimit(0.0f, 1.0f, peak);
    g.setColour(loadColour(peak).brighter(0.3f));
    g.fillRect(juce::Rectangle<float>(juce::jmax(2.0f, look.px(2.0f)), bar.getHeight() + 4.0f)
                   .withCentre({ juce::jlimit(bar.getX() + 1.0f, bar.getRight() - 1.0f, peakX), bar.getCentreY() }));

    g.setFont(look.font(valuePx, true));
    g.setColour(load >= 0.9f ? Palette::warning : Palette::text);
    g.drawText(juce::String(juce::jmax(0, shownPercent)) + " %", text, juce::Justification::centredRight, false);
}

//==============================================================================
StatusReadout::StatusReadout(EditorLookAndFeel& lookToUse, juce::String captionToUse, juce::String tooltip)
    : look(lookToUse), caption(std::move(captionToUse))
{
    setTooltip(tooltip);
    setTitle(caption);
}

void StatusReadout::setValue(long long newValue, bool warn)
{
    if (valueKnown && newValue == value && warn == warning)
        return;

    value = newValue;
    warning = warn;
    valueKnown = true;
    repaint();
}

int StatusReadout::getPreferredWidth() const
{
    return juce::roundToInt(captionFont(look).getStringWidthFloat(caption.toUpperCase())) + look.pxi(4.0f);
}

void StatusReadout::paint(juce::Graphics& g)
{
    auto area = getLocalBounds();
    auto top = area.removeFromTop(area.getHeight() / 2);

    g.setFont(captionFont(look));
    g.setColour(Palette::textDim);
    g.drawText(caption.toUpperCase(), top, juce::Justification::bottomLeft, false);

    area.removeFromTop(look.pxi(1.0f));
    g.setFont(look.font(valuePx, true));
    g.setColour(warning ? Palette::warning : Palette::text);
    g.drawText(valueKnown ? juce::String(value) : juce::String("-"), area, juce::Justification::centredLeft, false);
}

} // namespace snaresim::ui
