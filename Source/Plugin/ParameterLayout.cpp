#include "ParameterLayout.h"

#include "ToggleParameter.h"

#include <cmath>
#include <string>

namespace snaresim::plugin
{
namespace
{
juce::String toJuce (std::string_view text)
{
    return juce::String (std::string (text));
}

juce::NormalisableRange<float> makeRange (const ParameterSpec& spec)
{
    const auto lo = (float) spec.minValue;
    const auto hi = (float) spec.maxValue;

    if (spec.scale == ParamScale::logarithmic && spec.minValue > 0.0 && spec.maxValue > spec.minValue)
    {
        const double logRatio = std::log (spec.maxValue / spec.minValue);
        const double minValue = spec.minValue;

        return { lo, hi,
                 [minValue, logRatio] (float start, float end, float proportion)
                 {
                     const auto v = (float) (minValue * std::exp ((double) proportion * logRatio));
                     return juce::jlimit (start, end, v);
                 },
                 [minValue, logRatio] (float, float, float value)
                 {
                     const auto p = std::log ((double) value / minValue) / logRatio;
                     return (float) juce::jlimit (0.0, 1.0, p);
                 },
                 [] (float start, float end, float value) { return juce::jlimit (start, end, value); } };
    }

    return { lo, hi };
}
} // namespace

juce::AudioProcessorValueTreeState::ParameterLayout createParameterLayout()
{
    juce::AudioProcessorValueTreeState::ParameterLayout layout;

    for (const auto& spec : parameterSpecs())
    {
        const juce::ParameterID id { toJuce (spec.key), 1 };
        const auto name = toJuce (spec.name);
        const auto unit = toJuce (spec.unit);

        switch (spec.kind)
        {
            case ParamKind::toggle:
                layout.add (std::make_unique<ToggleParameter> (id, name, spec.defaultValue >= 0.5, unit));
                break;

            case ParamKind::choice:
            {
                auto choices = juce::StringArray::fromTokens (toJuce (spec.choices), "|", "");
                const int numChoices = (int) std::lround (spec.maxValue - spec.minValue) + 1;

                // The engine reads the choice index (0 .. n-1); name any choice the table leaves unnamed.
                while (choices.size() < numChoices)
                    choices.add (juce::String (choices.size()));

                layout.add (std::make_unique<juce::AudioParameterChoice> (
                    id, name, choices, (int) std::lround (spec.defaultValue),
                    juce::AudioParameterChoiceAttributes().withLabel (unit)));
                break;
            }

            case ParamKind::integer:
                layout.add (std::make_unique<juce::AudioParameterInt> (
                    id, name, (int) std::lround (spec.minValue), (int) std::lround (spec.maxValue),
                    (int) std::lround (spec.defaultValue),
                    juce::AudioParameterIntAttributes().withLabel (unit)));
                break;

            case ParamKind::continuous:
            default:
            {
                const auto suffix = unit.isEmpty() ? juce::String() : " " + unit;
                auto attributes = juce::AudioParameterFloatAttributes()
                                      .withLabel (unit)
                                      .withStringFromValueFunction ([suffix] (float value, int maxLength)
                                                                    {
                                                                        auto text = juce::String (value, 4) + suffix;
                                                                        return maxLength > 0 ? text.substring (0, maxLength) : text;
                                                                    });

                layout.add (std::make_unique<juce::AudioParameterFloat> (
                    id, name, makeRange (spec), (float) spec.defaultValue, attributes));
                break;
            }
        }
    }

    return layout;
}

} // namespace snaresim::plugin
