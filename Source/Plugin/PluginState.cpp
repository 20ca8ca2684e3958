#include "PluginState.h"

#include "ParameterLayout.h"
#include "Parameters.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

namespace snaresim::plugin
{

void PluginState::write (juce::AudioProcessorValueTreeState& parameters, juce::MemoryBlock& destination)
{
    auto state = parameters.copyState();

    if (auto xml = state.createXml())
    {
        xml->setAttribute (versionAttribute, version);
        juce::AudioProcessor::copyXmlToBinary (*xml, destination);
    }
}

bool PluginState::read (juce::AudioProcessorValueTreeState& parameters, const void* data, int sizeInBytes)
{
    if (data == nullptr || sizeInBytes <= 0)
        return false;

    const auto xml = juce::AudioProcessor::getXmlFromBinary (data, sizeInBytes);

    if (xml == nullptr || ! xml->hasTagName (treeType))
        return false;

    // Version 0 (no attribute) and 1: the first version's table, where the damping was the
    // batter's T60 (batter_decay), high_damping was batter_high_damping and mic_top_position
    // was listen_position. Unknown IDs are ignored; missing parameters take their defaults.
    const int stateVersion = xml->getIntAttribute (versionAttribute, 0);
    std::array<std::optional<double>, kNumParameters> values {};

    for (const auto* child : xml->getChildIterator())
    {
        if (! child->hasTagName ("PARAM") || ! child->hasAttribute ("id") || ! child->hasAttribute ("value"))
            continue;

        auto key = child->getStringAttribute ("id").toStdString();
        double value = child->getDoubleAttribute ("value");
        if (! std::isfinite (value))
            continue;

        if (stateVersion < 2)
        {
            if (key == "batter_decay")
            {
                key = "damping";
                value = dampingFromDecay (value);
            }
            else if (key == "batter_high_damping")
                key = "high_damping";
            else if (key == "listen_position")
                key = "mic_top_position";
        }

        if (const auto id = findParameter (key))
            values[static_cast<std::size_t> (*id)] = value;
    }

    // A complete tree: replaceState leaves parameters missing from it at their current values.
    // Its children in the order the processor's own tree has them (by ID), so that a restored
    // state saves byte for byte as it was loaded.
    std::array<const ParameterSpec*, kNumParameters> byKey {};
    for (std::size_t i = 0; i < byKey.size(); ++i)
        byKey[i] = &parameterSpecs()[i];
    std::sort (byKey.begin(), byKey.end(), [] (const auto* a, const auto* b) { return a->key < b->key; });

    juce::ValueTree tree (treeType);

    for (const auto* spec : byKey)
    {
        const auto& stored = values[static_cast<std::size_t> (spec->id)];
        // As a float: the parameter holds one, and the tree must say what it holds.
        const double value = (float) (stored.has_value() ? sanitise (*spec, *stored) : spec->defaultValue);

        juce::ValueTree param ("PARAM");
        param.setProperty ("id", juce::String (std::string (spec->key)), nullptr);
        param.setProperty ("value", value, nullptr);
        tree.appendChild (param, nullptr);
    }

    parameters.replaceState (tree);
    return true;
}

double PluginState::dampingFromDecay (double t60) noexcept
{
    if (! std::isfinite (t60) || t60 <= 0.0)
        return spec (ParamId::damping).defaultValue;

    return std::clamp (100.0 * std::log (t60 / 4.0) / std::log (0.15 / 4.0), 0.0, 100.0);
}

} // namespace snaresim::plugin
