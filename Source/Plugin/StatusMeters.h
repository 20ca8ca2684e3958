#pragma once
// The engine's health at a glance: a CPU meter (load as a percentage of the audio deadline,
// with the peak held) and small status readouts (solver fallbacks, non-finite resets, the
// largest Newton iteration count). They repaint only when what they show changes.

#include "EditorLookAndFeel.h"

#include <juce_gui_basics/juce_gui_basics.h>

namespace snaresim::ui
{

class CpuMeter final : public juce::Component, public juce::SettableTooltipClient
{
public:
    explicit CpuMeter(EditorLookAndFeel&);

    // Loads as fractions of the audio deadline (1 = the whole block period).
    void setLoad(float load, float peak);

    void paint(juce::Graphics&) override;

private:
    EditorLookAndFeel& look;
    int shownPercent = -1, shownPeakPercent = -1;
    float load = 0.0f, peak = 0.0f;
};

class StatusReadout final : public juce::Component, public juce::SettableTooltipClient
{
public:
    StatusReadout(EditorLookAndFeel&, juce::String caption, juce::String tooltip);

    void setValue(long long value, bool warn);

    void paint(juce::Graphics&) override;

    // Width that fits the caption.
    int getPreferredWidth() const;

private:
    EditorLookAndFeel& look;
    juce::String caption;
    long long value = -1;
    bool warning = false;
    bool valueKnown = false;
};

} // namespace snaresim::ui
