// Every place the plug-in lists parameters follows the engine's schema (Parameters.h,
// ParameterText.h): the host's parameters in the schema's order with its texts, the saved
// state's keys and version, and the editor's groups and controls.

#include "ParameterPanel.h"
#include "ParameterText.h"
#include "PluginState.h"
#include "ProcessorTestHelpers.h"

#include <catch2/catch.hpp>

#include <set>
#include <string>

namespace
{
juce::String toJuce(std::string_view s) { return juce::String(juce::CharPointer_UTF8(std::string(s).c_str())); }
} // namespace

TEST_CASE("the host's parameters are the schema's, in its order, with its texts", "[processor][schema]")
{
    SnareSimAudioProcessor proc;
    const auto& params = proc.getParameters();
    REQUIRE((size_t) params.size() == snaresim::kNumParameters);

    for (const auto& spec : snaresim::parameterSpecs())
    {
        INFO("parameter " << spec.key);
        auto* p = dynamic_cast<juce::RangedAudioParameter*>(params[(int) spec.id]);
        REQUIRE(p != nullptr);
        CHECK(p->getParameterID() == toJuce(spec.key));

        // The texts: what the schema writes, and what it reads back.
        for (double v : { spec.minValue, spec.defaultValue, spec.maxValue, 0.5 * (spec.minValue + spec.maxValue) })
        {
            if (spec.kind != snaresim::ParamKind::continuous)
                v = std::round(v);
            const auto normalised = p->convertTo0to1((float) v);
            const auto expected = toJuce(snaresim::formatValue(spec, p->convertFrom0to1(normalised)));
            CHECK(p->getText(normalised, 1024) == expected);
            const auto parsed = p->convertFrom0to1(p->getValueForText(expected));
            CHECK(toJuce(snaresim::formatValue(spec, parsed)) == expected);
        }
        // Text that is no value of the parameter gives its default.
        CHECK(p->convertFrom0to1(p->getValueForText("not a value")) == Approx((float) spec.defaultValue).margin(1e-6));

        if (spec.kind == snaresim::ParamKind::toggle || spec.kind == snaresim::ParamKind::choice)
        {
            juce::StringArray names;
            for (int i = 0; i < snaresim::numChoiceNames(spec); ++i)
                names.add(toJuce(snaresim::formatValue(spec, i)));
            CHECK(p->getAllValueStrings() == names);
        }
    }
}

TEST_CASE("the saved state holds every schema key once, at the schema's version", "[processor][schema]")
{
    SnareSimAudioProcessor proc;
    juce::MemoryBlock state;
    proc.getStateInformation(state);
    const auto xml = juce::AudioProcessor::getXmlFromBinary(state.getData(), (int) state.getSize());
    REQUIRE(xml != nullptr);
    CHECK(xml->getIntAttribute(snaresim::plugin::PluginState::versionAttribute, -1) == snaresim::kStateVersion);

    std::multiset<std::string> stored;
    for (const auto* child : xml->getChildIterator())
        if (child->hasTagName("PARAM"))
            stored.insert(child->getStringAttribute("id").toStdString());
    std::multiset<std::string> schema;
    for (const auto& spec : snaresim::parameterSpecs())
        schema.insert(std::string(spec.key));
    CHECK(stored == schema);
}

TEST_CASE("the editor's panels are the schema's groups, in order, each with its parameters", "[editor][schema]")
{
    SnareSimAudioProcessor proc;
    snaresim::ui::EditorLookAndFeel look;
    const auto panels = snaresim::ui::makeParameterPanels(proc.getValueTreeState(), look, { "main" });

    std::vector<std::vector<const snaresim::ParameterSpec*>> expected;
    std::vector<std::string_view> keys;
    for (const auto& group : snaresim::parameterGroups())
    {
        std::vector<const snaresim::ParameterSpec*> members;
        for (const auto& spec : snaresim::parameterSpecs())
            if (spec.group == group.key)
                members.push_back(&spec);
        if (! members.empty())
        {
            expected.push_back(members);
            keys.push_back(group.key);
        }
    }

    REQUIRE(panels.size() == expected.size());
    std::size_t controls = 0;
    for (std::size_t g = 0; g < panels.size(); ++g)
    {
        INFO("group " << keys[g]);
        CHECK(panels[g]->getGroupKey() == toJuce(keys[g]));
        REQUIRE(panels[g]->getNumControls() == (int) expected[g].size());
        for (int c = 0; c < panels[g]->getNumControls(); ++c)
            CHECK(&panels[g]->getControl(c)->getSpec() == expected[g][(std::size_t) c]);
        controls += (std::size_t) panels[g]->getNumControls();
    }
    CHECK(controls == snaresim::kNumParameters);
}
