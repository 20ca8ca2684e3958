#pragma once
// An on/off parameter whose value is always 0 or 1.
//
// juce::AudioParameterBool keeps whatever normalised value a host sends (0.66, say) while its
// state holds the snapped 1, so a state restored over it compared equal and left the 0.66 in
// place: the host then read back a value the saved state never had. This one snaps on every
// set, so the value a host reads, the value saved and the value restored are the same.

#include "ParameterText.h"

#include <juce_audio_processors/juce_audio_processors.h>

#include <atomic>

namespace snaresim::plugin
{

class ToggleParameter final : public juce::RangedAudioParameter
{
public:
    // Default and texts from the schema's entry (which outlives the parameter).
    ToggleParameter(const juce::ParameterID& parameterId, const juce::String& parameterName, const ParameterSpec& specToUse,
                    const juce::String& unitLabel)
        : RangedAudioParameter(parameterId, parameterName, juce::AudioProcessorParameterWithIDAttributes().withLabel(unitLabel)),
          spec(specToUse), defaultValue(specToUse.defaultValue >= 0.5 ? 1.0f : 0.0f), value(defaultValue)
    {}

    bool get() const noexcept { return value.load(std::memory_order_relaxed) >= 0.5f; }

    float getValue() const override { return value.load(std::memory_order_relaxed); }
    void setValue(float newValue) override { value.store(snap(newValue), std::memory_order_relaxed); }
    float getDefaultValue() const override { return defaultValue; }

    int getNumSteps() const override { return 2; }
    bool isDiscrete() const override { return true; }
    bool isBoolean() const override { return true; }

    juce::String getText(float normalised, int maximumLength) const override
    {
        const juce::String text(formatValue(spec, snap(normalised)));
        return maximumLength > 0 ? text.substring(0, maximumLength) : text;
    }

    float getValueForText(const juce::String& text) const override
    {
        return snap((float) parseValue(spec, text.toStdString(), BareNumber::writtenUnit).value_or(defaultValue));
    }

    juce::StringArray getAllValueStrings() const override
    {
        return { juce::String(formatValue(spec, 0.0)), juce::String(formatValue(spec, 1.0)) };
    }

    const juce::NormalisableRange<float>& getNormalisableRange() const override { return range; }

private:
    // NaN and anything below one half are off.
    static float snap(float v) noexcept { return v >= 0.5f ? 1.0f : 0.0f; }

    const ParameterSpec& spec;
    const float defaultValue;
    std::atomic<float> value;
    const juce::NormalisableRange<float> range { 0.0f, 1.0f, 1.0f };
};

} // namespace snaresim::plugin
