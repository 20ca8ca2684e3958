#pragma once
// How the editor shows a parameter's value: derived from the parameter table (range, unit,
// kind, scale), so a new parameter gets a sensible display without editor changes.
//   "3050 N/m", "30.0 N", "25 %", "140 mm" (for m), "28.0 g" (for kg), "1.0e8 N/m^α".

#include "Parameters.h"

#include <juce_core/juce_core.h>

namespace snaresim::ui
{

struct ParameterDisplay
{
    double scale = 1.0;        // displayed number = value * scale
    juce::String unit;         // displayed unit (may differ from the table's: mm for m)
    juce::String baseUnit;     // the table's unit, prettified
    int decimals = 0;
    bool scientific = false;

    static ParameterDisplay forSpec (const ParameterSpec& spec);

    juce::String toText (double value) const;

    // Parses what a user typed: a number, optionally followed by the displayed unit or the
    // table's own unit ("140", "140 mm", "0.14 m").
    double fromText (const juce::String& text) const;
};

// "N/m^alpha" -> "N/m^α", "m^2/s" -> "m²/s".
juce::String prettyUnit (std::string_view unit);

// A group key of the table ("heads") as a panel title ("Heads & shell").
juce::String groupTitle (std::string_view group);

} // namespace snaresim::ui
