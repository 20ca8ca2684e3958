#include "ParameterLayout.h"

#include "ParameterText.h"
#include "ToggleParameter.h"

#include <cmath>
#include <string>

namespace snaresim::plugin
{
namespace
{
juce::String toJuce(std::string_view text) { return juce::String(juce::CharPointer_UTF8(std::string(text).c_str())); }

// The schema's text (ParameterText.h), cut to what the host has room for.
juce::String textOf(const ParameterSpec& spec, double value, int maxLength)
{
    const auto text = toJuce(formatValue(spec, value));
    return maxLength > 0 ? text.substring(0, maxLength) : text;
}

// What a host or a user typed; text that is no value of the parameter gives its default.
double valueOf(const ParameterSpec& spec, const juce::String& text)
{
    return sanitise(spec, parseValue(spec, text.toStdString(), BareNumber::writtenUnit).value_or(spec.defaultValue));
}

juce::NormalisableRange<float> makeRange(const ParameterSpec& spec)
{
    const auto lo = (float) spec.minValue;
    const auto hi = (float) spec.maxValue;

    if (spec.scale == ParamScale::logarithmic && spec.minValue > 0.0 && spec.maxValue > spec.minValue)
    {
        const double logRatio = std::log(spec.maxValue / spec.minValue);
        const double minValue = spec.minValue;

        return { lo, hi,
                 [minValue, logRatio](float start, float end, float proportion) {
                     const auto v = (float) (minValue * std::exp((double) proportion * logRatio));
                     return juce::jlimit(start, end, v);
                 },
                 [minValue, logRatio](float, float, float value) {
                     const auto p = std::log((double) value / minValue) / logRatio;
                     return (float) juce::jlimit(0.0, 1.0, p);
                 },
                 [](float start, float end, float value) { return juce::jlimit(start, end, value); } };
    }

    return { lo, hi };
}
} // namespace

juce::AudioProcessorValueTreeState::ParameterLayout createParameterLayout()
{
    juce::AudioProcessorValueTreeState::ParameterLayout layout;

    for (const auto& spec : parameterSpecs())
    {
        const juce::ParameterID id { toJuce(spec.key), 1 };
        const auto name = toJuce(spec.name);
        const auto unit = toJuce(spec.unit);

        switch (spec.kind)
        {
            case ParamKind::toggle: layout.add(std::make_unique<ToggleParameter>(id, name, spec, unit)); break;

            case ParamKind::choice:
            {
                juce::StringArray choices;
                for (int i = 0; i < numChoiceNames(spec); ++i)
                    choices.add(toJuce(formatValue(spec, i)));

                layout.add(std::make_unique<juce::AudioParameterChoice>(
                    id, name, choices, (int) std::lround(spec.defaultValue),
                    juce::AudioParameterChoiceAttributes()
                        .withLabel(unit)
                        .withStringFromValueFunction([&spec](int value, int maxLength) { return textOf(spec, value, maxLength); })
                        .withValueFromStringFunction([&spec](const juce::String& text) { return (int) valueOf(spec, text); })));
                break;
            }

            case ParamKind::integer:
                layout.add(std::make_unique<juce::AudioParameterInt>(
                    id, name, (int) std::lround(spec.minValue), (int) std::lround(spec.maxValue), (int) std::lround(spec.defaultValue),
                    juce::AudioParameterIntAttributes()
                        .withLabel(unit)
                        .withStringFromValueFunction([&spec](int value, int maxLength) { return textOf(spec, value, maxLength); })
                        .withValueFromStringFunction([&spec](const juce::String& text) { return (int) valueOf(spec, text); })));
                break;

            case ParamKind::continuous:
            default:
            {
                auto attributes =
                    juce::AudioParameterFloatAttributes()
                        .withLabel(unit)
                        .withStringFromValueFunction([&spec](float value, int maxLength) { return textOf(spec, value, maxLength); })
                        .withValueFromStringFunction([&spec](const juce::String& text) { return (float) valueOf(spec, text); });

                layout.add(std::make_unique<juce::AudioParameterFloat>(id, name, makeRange(spec), (float) spec.defaultValue, attributes));
                break;
            }
        }
    }

    return layout;
}

} // namespace snaresim::plugin
