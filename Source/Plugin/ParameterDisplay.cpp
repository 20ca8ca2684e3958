#include "ParameterDisplay.h"

#include <cmath>

namespace snaresim::ui
{

juce::String prettyUnit (std::string_view unit)
{
    juce::String u (juce::CharPointer_UTF8 (std::string (unit).c_str()));
    return u.replace ("^alpha", juce::CharPointer_UTF8 ("^\xce\xb1"))   // ^α
        .replace ("^2", juce::CharPointer_UTF8 ("\xc2\xb2"))             // ²
        .replace ("^3", juce::CharPointer_UTF8 ("\xc2\xb3"));            // ³
}

juce::String groupTitle (std::string_view group)
{
    if (group == "main")   return "Tension & damping";
    if (group == "heads")  return "Heads & shell";
    if (group == "snares") return "Snares";
    if (group == "mallet") return "Mallet & playing";
    if (group == "output") return "Microphones & output";
    if (group == "model")  return "Model";
    if (group.empty())     return "Other";

    auto title = juce::String (std::string (group)).replaceCharacter ('_', ' ');
    return title.substring (0, 1).toUpperCase() + title.substring (1);
}

ParameterDisplay ParameterDisplay::forSpec (const ParameterSpec& spec)
{
    ParameterDisplay d;
    d.baseUnit = prettyUnit (spec.unit);
    d.unit = d.baseUnit;

    const double largest = std::max (std::abs (spec.minValue), std::abs (spec.maxValue));

    // Small lengths and masses read better in mm and g.
    if (spec.unit == "m" && largest <= 0.5)
    {
        d.scale = 1000.0;
        d.unit = "mm";
    }
    else if (spec.unit == "kg" && largest <= 1.0)
    {
        d.scale = 1000.0;
        d.unit = "g";
    }

    if (spec.kind == ParamKind::integer || spec.kind == ParamKind::toggle || spec.kind == ParamKind::choice)
    {
        d.decimals = 0;
        return d;
    }

    const bool manyDecades = spec.scale == ParamScale::logarithmic && spec.minValue > 0.0
                             && spec.maxValue / spec.minValue >= 1000.0;
    const double scaledLargest = largest * d.scale;

    if (manyDecades || (scaledLargest > 0.0 && scaledLargest < 0.1) || scaledLargest >= 1.0e6)
    {
        d.scientific = true;
        d.decimals = 1;
        return d;
    }

    const double span = (spec.maxValue - spec.minValue) * d.scale;
    d.decimals = span >= 100.0 ? 0 : span >= 10.0 ? 1 : span >= 0.5 ? 2 : 3;
    return d;
}

juce::String ParameterDisplay::toText (double value) const
{
    const double shown = value * scale;
    juce::String number;

    if (scientific && shown != 0.0)
    {
        int exponent = (int) std::floor (std::log10 (std::abs (shown)));
        double mantissa = shown / std::pow (10.0, exponent);
        // Rounding can carry the mantissa to 10.0.
        if (std::abs (std::round (mantissa * 10.0) / 10.0) >= 10.0)
        {
            mantissa /= 10.0;
            ++exponent;
        }
        number = juce::String (mantissa, decimals) + "e" + juce::String (exponent);
    }
    else
    {
        number = decimals > 0 ? juce::String (shown, decimals) : juce::String (juce::roundToInt (shown));
        if (number == "-0" || (number.startsWith ("-0.") && number.removeCharacters ("-0.").isEmpty()))
            number = number.substring (1);
    }

    return unit.isEmpty() ? number : number + " " + unit;
}

double ParameterDisplay::fromText (const juce::String& text) const
{
    const auto trimmed = text.trim();
    const double number = trimmed.getDoubleValue();

    // What follows the number: the unit, if any.
    const auto rest = trimmed.trimCharactersAtStart ("+-0123456789.eE").trim();
    if (scale != 1.0 && rest.isNotEmpty() && rest == baseUnit)
        return number;

    return number / scale;
}

} // namespace snaresim::ui
