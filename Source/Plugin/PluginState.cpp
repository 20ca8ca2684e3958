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

void PluginState::write(juce::AudioProcessorValueTreeState& parameters, juce::MemoryBlock& destination)
{
    auto state = parameters.copyState();

    if (auto xml = state.createXml())
    {
        xml->setAttribute(versionAttribute, version);
        juce::AudioProcessor::copyXmlToBinary(*xml, destination);
    }
}

bool PluginState::read(juce::AudioProcessorValueTreeState& parameters, const void* data, int sizeInBytes)
{
    if (data == nullptr || sizeInBytes <= 8)
        return false;

    // AudioProcessor::copyXmlToBinary's layout: "VC2!", the text's length, the UTF-8 text. The
    // text is checked before JUCE parses it: its XML reader runs past the end of text that is
    // not valid UTF-8 (a lead byte skips the terminator), where getXmlFromBinary checks nothing.
    const auto* bytes = static_cast<const char*>(data);
    constexpr juce::uint32 magic = 0x21324356; // "VC2!"
    if (juce::ByteOrder::littleEndianInt(bytes) != magic)
        return false;
    const auto stated = juce::ByteOrder::littleEndianInt(bytes + 4);
    const int length = (int) std::min<juce::uint32>(stated, (juce::uint32)(sizeInBytes - 8));
    if (length <= 0 || ! juce::CharPointer_UTF8::isValidString(bytes + 8, length))
        return false;
    const auto xml = juce::parseXML(juce::String::fromUTF8(bytes + 8, length));

    if (xml == nullptr || ! xml->hasTagName(treeType))
        return false;

    // Older versions' keys migrate as the schema says, and what they did not hold is implied
    // (impliedParameters); unknown keys are ignored; missing parameters take their defaults.
    const int stateVersion = xml->getIntAttribute(versionAttribute, 0);
    std::array<std::optional<double>, kNumParameters> values {};

    for (const auto* child : xml->getChildIterator())
    {
        if (! child->hasTagName("PARAM") || ! child->hasAttribute("id") || ! child->hasAttribute("value"))
            continue;

        const double value = child->getDoubleAttribute("value");
        if (! std::isfinite(value))
            continue;

        if (const auto migrated = migrateParameter(stateVersion, child->getStringAttribute("id").toStdString(), value))
            values[static_cast<std::size_t>(migrated->first)] = migrated->second;
    }

    for (const auto& implied : impliedParameters())
        if (stateVersion < implied.beforeVersion && ! values[static_cast<std::size_t>(implied.id)].has_value())
            values[static_cast<std::size_t>(implied.id)] = implied.value;

    // A complete tree: replaceState leaves parameters missing from it at their current values.
    // Its children in the order the processor's own tree has them (by ID), so that a restored
    // state saves byte for byte as it was loaded.
    std::array<const ParameterSpec*, kNumParameters> byKey {};
    for (std::size_t i = 0; i < byKey.size(); ++i)
        byKey[i] = &parameterSpecs()[i];
    std::sort(byKey.begin(), byKey.end(), [](const auto* a, const auto* b) { return a->key < b->key; });

    juce::ValueTree tree(treeType);

    for (const auto* spec : byKey)
    {
        const auto& stored = values[static_cast<std::size_t>(spec->id)];
        // As a float: the parameter holds one, and the tree must say what it holds.
        const double value = (float) (stored.has_value() ? sanitise(*spec, *stored) : spec->defaultValue);

        juce::ValueTree param("PARAM");
        param.setProperty("id", juce::String(std::string(spec->key)), nullptr);
        param.setProperty("value", value, nullptr);
        tree.appendChild(param, nullptr);
    }

    parameters.replaceState(tree);
    return true;
}

} // namespace snaresim::plugin
