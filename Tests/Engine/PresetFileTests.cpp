// Preset files (PresetFile.h): what they read, what they refuse, and that writing and reading
// back gives every value exactly; the factory presets, read from Resources/Presets.

#include "DrumConfig.h"
#include "ParameterText.h"
#include "PresetFile.h"
#include "Presets.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <string>

using namespace snaresim;

namespace
{
bool sameValues(const ParameterSet& a, const ParameterSet& b)
{
    for (const auto& s : parameterSpecs())
        if (a.get(s.id) != b.get(s.id))
            return false;
    return true;
}

// A value anywhere in the parameter's range, as a host or the matching search would leave it
// (whole for toggles, choices and integers; any double otherwise).
double randomValue(const ParameterSpec& s, std::mt19937_64& rng)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const double t = u(rng);
    double v =
        s.scale == ParamScale::logarithmic ? s.minValue * std::pow(s.maxValue / s.minValue, t) : s.minValue + t * (s.maxValue - s.minValue);
    if (s.kind != ParamKind::continuous)
        v = std::round(v);
    return std::clamp(v, s.minValue, s.maxValue);
}
} // namespace

TEST_CASE("preset files: values in the schema's unit, the written unit, toggles and choices by name", "[presets]")
{
    const auto p = parsePresetFile("# a comment\n"
                                   "name = My Drum   # trailing comment\n"
                                   "\n"
                                   "batter_tension = 4200 N/m\n"
                                   "shell_depth = 120 mm\r\n"
                                   "mallet_mass = 0.035\n"
                                   "snares_engaged = off\n"
                                   "snare_solver = newton\n"
                                   "  damping=40 %  \n");
    CHECK(p.name == "My Drum");
    const auto params = parametersOf(p);
    CHECK(params.get(ParamId::batterTension) == 4200.0);
    CHECK(params.get(ParamId::shellDepth) == Approx(0.12).epsilon(1e-15));
    CHECK(params.get(ParamId::malletMass) == 0.035);
    CHECK(params.get(ParamId::snaresEngaged) == 0.0);
    CHECK(params.get(ParamId::snareSolver) == (double) *choiceIndex(spec(ParamId::snareSolver), "newton"));
    CHECK(params.get(ParamId::damping) == 40.0);
    // the rest at their defaults
    CHECK(params.get(ParamId::snareTension) == spec(ParamId::snareTension).defaultValue);
    CHECK(params.get(ParamId::carryTension) == spec(ParamId::carryTension).defaultValue);
}

TEST_CASE("preset files: an older schema's key migrates as a saved state's does", "[presets]")
{
    // Quality was the grids' coarseness: 3 is the bandwidth those grids carry.
    const auto params = parametersOf(parsePresetFile("name = Old\ngrid_coarseness = 3\n"));
    CHECK(params.get(ParamId::bandwidth) == qualityBandwidth_Hz(3.0));
    CHECK(gridCoarsenessFor(params.get(ParamId::bandwidth)) == 3.0);
    // below the old range (1 to 4): its finest grids
    CHECK(parametersOf(parsePresetFile("name = Old\ngrid_coarseness = 0.5\n")).get(ParamId::bandwidth) == qualityBandwidth_Hz(1.0));
    CHECK_THROWS_AS(parsePresetFile("name = Old\ngrid_coarseness = 3\nbandwidth = 5000 Hz\n"), PresetFileError); // twice
}

TEST_CASE("preset files: bad files are refused with the line that is wrong", "[presets]")
{
    const std::vector<std::pair<std::string, std::string>> bad {
        { "batter_tension = 4000\n", "no 'name" },
        { "", "no 'name" },
        { "name = A\nname = B\n", "line 2: the name is given twice" },
        { "name =\n", "line 1: the name is empty" },
        { "name = A\nbatter tension 4000\n", "line 2:" },
        { "name = A\n\nno_such_parameter = 1\n", "line 3: unknown parameter 'no_such_parameter'" },
        { "name = A\ndamping = 20\ndamping = 30\n", "line 3: parameter 'damping' is given twice" },
        { "name = A\ndamping = 120\n", "line 2: parameter damping = 120 is outside its range" },
        { "name = A\ndamping = loud\n", "line 2: 'damping': cannot read the value 'loud'" },
        { "name = A\ndamping = 20 N\n", "line 2: 'damping': cannot read" },
        { "name = A\ndamping = nan\n", "line 2:" },
        { "name = A\ngrid_coarseness = fine\n", "line 2: 'grid_coarseness': cannot read the value 'fine'" },
        { "name = A\nsnare_count = 12.5\n", "line 2:" },
        { "name = A\nsnare_solver = fastest\n", "line 2:" },
        { std::string("name = A\n\0\x01\x02", 12), "binary" },
        { "name = A\n" + std::string(70000, '#'), "larger than 64 KiB" },
    };
    for (const auto& [text, message] : bad)
    {
        INFO(text.substr(0, 60));
        REQUIRE_THROWS_AS(parsePresetFile(text), PresetFileError);
        try
        {
            parsePresetFile(text);
        }
        catch (const PresetFileError& e)
        {
            CHECK_THAT(e.what(), Catch::Contains(message));
        }
    }
}

TEST_CASE("preset files: written and read back, every value is exact", "[presets]")
{
    std::mt19937_64 rng(20261124);
    for (int trial = 0; trial < 200; ++trial)
    {
        ParameterSet params;
        for (const auto& s : parameterSpecs())
            if (trial == 0 || rng() % 3 != 0) // trial 0: every parameter away from its default
                params.set(s.id, randomValue(s, rng));
        const auto text = formatPresetFile("Trial " + std::to_string(trial), params);
        INFO(text);
        const auto back = parsePresetFile(text);
        CHECK(back.name == "Trial " + std::to_string(trial));
        REQUIRE(sameValues(parametersOf(back), params));
    }
    // the defaults write no values; a name that is not one line is made one
    const auto empty = formatPresetFile("two\nlines # and a hash", ParameterSet {});
    const auto back = parsePresetFile(empty);
    CHECK(back.values.empty());
    CHECK(back.name == "two lines   and a hash");
    CHECK(parsePresetFile(formatPresetFile("  ", ParameterSet {})).name == "Untitled");
}

TEST_CASE("factory presets: read from their files, in program order, each different", "[presets]")
{
    const auto presets = factoryPresets();
    REQUIRE(presets.size() == 10);
    const char* names[] = { "Studio Default", "Tight Funk",  "Fat Rock", "Piccolo",     "Snares Off",
                            "Loose Vintage",  "Muffled Dry", "Marching", "Soft Mallet", "Open Air" };
    std::set<std::string> texts;
    for (size_t i = 0; i < presets.size(); ++i)
    {
        CHECK(presets[i].name == names[i]);
        ParameterSet params;
        REQUIRE(applyPreset(names[i], params));
        // each one writes and reads back as itself
        const auto text = formatPresetFile(presets[i].name, params);
        CHECK(sameValues(parametersOf(parsePresetFile(text)), params));
        texts.insert(text.substr(text.find('\n', text.find("name ="))));
    }
    CHECK(texts.size() == presets.size());
    for (const auto& [id, value] : presets[0].values) // Studio Default: the defaults
        CHECK(value == Approx(spec(id).defaultValue));

    ParameterSet funk;
    REQUIRE(applyPreset("tight funk", funk));
    CHECK(funk.get(ParamId::batterTension) == 4800.0);
    CHECK(funk.get(ParamId::snareTension) == 56.0);
    CHECK(funk.get(ParamId::damping) == 70.0);
    CHECK(funk.get(ParamId::malletStiffness) == 5.9e9);
    ParameterSet off;
    REQUIRE(applyPreset("Snares Off", off));
    CHECK(off.get(ParamId::snaresEngaged) == 0.0);
    ParameterSet piccolo;
    REQUIRE(applyPreset("Piccolo", piccolo));
    CHECK(piccolo.get(ParamId::shellDepth) == 0.076);
    CHECK_FALSE(applyPreset("No Such Preset", piccolo));
}
