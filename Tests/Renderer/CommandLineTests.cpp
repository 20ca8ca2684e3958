// snaresim-render's command line parsed in-process (CommandLine.h): the forms of options and
// values, the exact messages, the order of errors and of repeated options; and the fuzzer's
// seed corpus replayed through it (Tests/Fuzz, here in every build).

#include "CommandLine.h"
#include "DrumConfig.h"
#include "EngineSetup.h"
#include "Errors.h"

#include "Parameters.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>

using namespace snaresim::render;
using Args = std::vector<std::string>;

namespace
{

Args with(Args args, const Args& more)
{
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// Enough to render, so that only the arguments after it are under test.
Args playable(const Args& more) { return with({ "-o", "out.wav", "--hit", "0:100" }, more); }

// parseCommandLine's UserError message ("" when it accepts the arguments). Anything else
// escaping fails the test.
std::string errorOf(const Args& args)
{
    try
    {
        (void) parseCommandLine(args);
    }
    catch (const UserError& e)
    {
        return e.what();
    }
    return "";
}

RenderJob jobOf(const Args& args)
{
    const auto command = parseCommandLine(args);
    REQUIRE(command.action == CommandLine::Action::render);
    return command.job;
}

} // namespace

TEST_CASE("an option's value: next argument or attached with =, -o only separate", "[renderer][command-line]")
{
    for (const auto& args :
         { Args { "-o", "a.wav", "--hit", "0.5:60", "--seconds", "1.5" }, Args { "--output", "a.wav", "--hit=0.5:60", "--seconds=1.5" },
           Args { "--output=a.wav", "--hit", "0.5:60", "--seconds=1.5" } })
    {
        const auto job = jobOf(args);
        CHECK(job.output == std::filesystem::path("a.wav"));
        REQUIRE(job.hits.size() == 1);
        CHECK(job.hits[0].time_s == 0.5);
        CHECK(job.hits[0].velocity == 60);
        CHECK(job.seconds == 1.5);
    }

    // As before: -o takes its value from the next argument only.
    CHECK(errorOf({ "-oa.wav", "--hit", "0:100" }) == "unknown option '-oa.wav' (see --help)");
    CHECK(errorOf({ "-o=a.wav", "--hit", "0:100" }) == "unknown option '-o=a.wav' (see --help)");
    // Each spelling of -o / --output is named as used.
    CHECK(errorOf({ "--output", "", "--hit", "0:100" }) == "--output: empty file name");
    CHECK(errorOf({ "-o", "", "--hit", "0:100" }) == "-o: empty file name");
    CHECK(errorOf({ "-o", "a.wav", "--output", "b.wav", "--hit", "0:100" }) == "--output given more than once");
    CHECK(errorOf({ "--output", "a.wav", "-o", "b.wav", "--hit", "0:100" }) == "-o given more than once");
}

TEST_CASE("values that start with '-' are values, but a next argument starting with '--' is an option", "[renderer][command-line]")
{
    // Negative numbers reach the option's own checks.
    CHECK(errorOf(playable({ "--seconds", "-1" })) == "--seconds: '-1' must be greater than 0 and at most 3600");
    CHECK(errorOf(playable({ "--seconds", "-.5" })) == "--seconds: '-.5' must be greater than 0 and at most 3600");
    CHECK(errorOf(playable({ "--seconds", "-inf" })) == "--seconds: '-inf' is not a finite number");
    CHECK(errorOf({ "-o", "a.wav", "--hit", "-1:100" }) == "--hit: time '-1' is outside 0..3600 s");
    CHECK(errorOf({ "--bench", "--block-size", "-64" }) == "--block-size: '-64' is outside 1..8192 samples");
    CHECK(jobOf(playable({ "--set", "output_gain=-6" })).overrides.at(0).value == -6.0);

    // Any text starting with one '-' is a value: file and preset names too.
    CHECK(jobOf({ "-o", "-out.wav", "--hit", "0:100" }).output == std::filesystem::path("-out.wav"));
    CHECK(jobOf({ "-o", "-o", "--hit", "0:100" }).output == std::filesystem::path("-o"));
    CHECK(jobOf(playable({ "--preset", "-x" })).preset == "-x");

    // A next argument starting with "--" is an option: the value is missing.
    CHECK(errorOf(playable({ "--preset", "--json" })) == "option --preset needs a value (see --help)");
    CHECK(errorOf({ "--hit", "--seconds", "1" }) == "option --hit needs a value (see --help)");
    CHECK(errorOf({ "-o", "--hit", "0:100" }) == "option -o needs a value (see --help)");
    CHECK(errorOf(playable({ "--preset", "--" })) == "option --preset needs a value (see --help)");
    // Attached, it is the value.
    CHECK(jobOf(playable({ "--preset=--json" })).preset == "--json");
    CHECK(jobOf({ "--output=--out.wav", "--hit", "0:100" }).output == std::filesystem::path("--out.wav"));

    // An attached empty value is empty (not the next argument).
    CHECK(errorOf(playable({ "--seconds=", "1" })) == "--seconds: '' is not a number");
    CHECK(errorOf(playable({ "--seconds=" })) == "--seconds: '' is not a number");
    CHECK(errorOf({ "--output=", "a.wav", "--hit", "0:100" }) == "--output: empty file name");
    CHECK(errorOf(playable({ "--preset=" })) == "--preset: empty preset name");
    CHECK(errorOf(playable({ "--seconds", "" })) == "--seconds: '' is not a number");
}

TEST_CASE("flags take no value and may be repeated", "[renderer][command-line]")
{
    for (const char* flag : { "--json=yes", "--json=", "--json=true", "--json=1" })
        CHECK(errorOf(playable({ flag })) == "option --json takes no value");
    CHECK(errorOf({ "--bench=yes" }) == "option --bench takes no value");
    CHECK(errorOf({ "--list-params=1" }) == "option --list-params takes no value");

    const auto job = jobOf(playable({ "--json", "--lossless", "--json" }));
    CHECK(job.json);
    CHECK(job.lossless);
    CHECK_FALSE(job.bench);
}

TEST_CASE("unknown options and stray arguments, worded as before", "[renderer][command-line]")
{
    CHECK(errorOf(playable({ "--bogus" })) == "unknown option '--bogus' (see --help)");
    CHECK(errorOf(playable({ "--bogus=1" })) == "unknown option '--bogus' (see --help)");
    CHECK(errorOf(playable({ "-x" })) == "unknown option '-x' (see --help)");
    CHECK(errorOf(playable({ "-5" })) == "unknown option '-5' (see --help)");
    CHECK(errorOf(playable({ "---x" })) == "unknown option '---x' (see --help)");
    CHECK(errorOf(playable({ "--" })) == "unknown option '--' (see --help)");
    CHECK(errorOf(playable({ "--", "x" })) == "unknown option '--' (see --help)");
    CHECK(errorOf(playable({ "--help=1" })) == "unknown option '--help' (see --help)");
    CHECK(errorOf(playable({ "stray.wav" })) == "unexpected argument 'stray.wav' (see --help)");
    CHECK(errorOf(playable({ "-" })) == "unexpected argument '-' (see --help)");
    CHECK(errorOf(playable({ "" })) == "unexpected argument '' (see --help)");
    CHECK(errorOf(playable({ "--json", "yes" })) == "unexpected argument 'yes' (see --help)");
    CHECK(errorOf(playable({ "--seconds" })) == "option --seconds needs a value (see --help)");
    CHECK(errorOf({ "--hit", "0:100", "-o" }) == "option -o needs a value (see --help)");
}

TEST_CASE("the first mistake from the left is the one reported", "[renderer][command-line]")
{
    CHECK(errorOf({ "--bogus", "--seconds", "abc" }) == "unknown option '--bogus' (see --help)");
    CHECK(errorOf({ "--seconds", "abc", "--bogus" }) == "--seconds: 'abc' is not a number");
    CHECK(errorOf({ "stray", "--json=yes" }) == "unexpected argument 'stray' (see --help)");
    CHECK(errorOf({ "stray", "--seconds" }) == "unexpected argument 'stray' (see --help)");
    CHECK(errorOf({ "--seconds", "1", "--seconds", "abc" }) == "--seconds: 'abc' is not a number");
    CHECK(errorOf({ "--seconds", "1", "--seconds", "2" }) == "--seconds given more than once");
    // The whole line is read before what needs all of it.
    CHECK(errorOf({ "--hit", "0:100" }) == "missing -o OUTPUT.wav (see --help)");
    CHECK(errorOf({ "-o", "a.wav" }) == "nothing to play: give --hit TIME:VELOCITY or --midi FILE (see --help)");
    CHECK(errorOf({ "-o", "a.wav", "--hit", "0:100", "--bench-short" }) == "--bench-short is an option of --bench");
}

TEST_CASE("repeated --hit and --set keep their order", "[renderer][command-line]")
{
    const auto job = jobOf({ "-o", "a.wav", "--hit", "0.5:60", "--set", "output_gain=-6", "--hit=0:100", "--set", "air_model=none", "--set",
                             "output_gain=-3", "--set", "air_model=1" });
    REQUIRE(job.hits.size() == 2);
    CHECK(job.hits[0].time_s == 0.5);
    CHECK(job.hits[1].time_s == 0.0);

    REQUIRE(job.overrides.size() == 4);
    CHECK(job.overrides[0].text == "output_gain=-6");
    CHECK(job.overrides[1].id == snaresim::ParamId::airModel);
    CHECK(job.overrides[1].value == 0.0);
    CHECK(job.overrides[2].value == -3.0);
    CHECK(job.overrides[3].value == 1.0);
}

TEST_CASE("parameter values in --set: numbers, choice names, whole numbers where the parameter needs them", "[renderer][command-line]")
{
    CHECK(jobOf(playable({ "--set", "air_model=cavity" })).overrides.at(0).value == 1.0);
    CHECK(jobOf(playable({ "--set", "snares_engaged=+1" })).overrides.at(0).value == 1.0);
    CHECK(errorOf(playable({ "--set", "air_model=bogus" })) == "--set air_model: 'bogus' is not one of 0 none, 1 cavity, 2 airbox");
    CHECK(errorOf(playable({ "--set", "air_model=0.5" })) ==
          "--set air_model=0.5: air_model takes one of 0 none, 1 cavity, 2 airbox (the number or the name), not a fraction");
    CHECK(errorOf(playable({ "--set", "snares_engaged=0.5" })) == "--set snares_engaged=0.5: snares_engaged takes 0 or 1, not a fraction");
    CHECK(errorOf(playable({ "--set", "mallet_mass=heavy" })) == "--set mallet_mass: 'heavy' is not a number");
    CHECK(errorOf(playable({ "--set", "mallet_mass" })) == "--set: 'mallet_mass' is not ID=VALUE (see --list-params)");
    CHECK(errorOf(playable({ "--set", "nope=1" })) == "--set: unknown parameter 'nope' (see --list-params)");
    // an older schema's key, its value migrated: Quality's old coarseness 3 is its bandwidth
    const auto old = jobOf(playable({ "--set", "grid_coarseness=3" })).overrides.at(0);
    CHECK(old.id == snaresim::ParamId::bandwidth);
    CHECK(old.value == snaresim::qualityBandwidth_Hz(3.0));
    CHECK(errorOf(playable({ "--set", "grid_coarseness=fine" })) == "--set grid_coarseness: 'fine' is not a number");
}

TEST_CASE("the values of --set are read by the schema text rule: units, names of toggles and choices", "[renderer][command-line]")
{
    auto valueOf = [](const char* assignment) { return jobOf(playable({ "--set", assignment })).overrides.at(0).value; };
    CHECK(valueOf("shell_depth=0.12") == Approx(0.12)); // a bare number is in the schema's unit
    CHECK(valueOf("shell_depth=120 mm") == Approx(0.12));
    CHECK(valueOf("shell_depth=120mm") == Approx(0.12));
    CHECK(valueOf("mallet_mass=28 g") == Approx(0.028));
    CHECK(valueOf("snares_engaged=off") == 0.0);
    CHECK(valueOf("snares_engaged=On") == 1.0);
    CHECK(valueOf("air_model=Cavity") == 1.0);
    CHECK(valueOf("snare_solver=newton") == 1.0);
    CHECK(errorOf(playable({ "--set", "shell_depth=120 furlongs" })) == "--set shell_depth: '120 furlongs' is not a number in mm or m");
    CHECK(errorOf(playable({ "--set", "snares_engaged=maybe" })) == "--set snares_engaged: 'maybe' is not one of 0 off, 1 on");
}

TEST_CASE("help: --help anywhere wins, and --list-params reads the whole line first", "[renderer][command-line]")
{
    for (const auto& args : { Args { "--help" }, Args { "-h" }, Args { "--bogus", "-h" }, Args { "--preset", "--help" },
                              Args { "--seconds", "abc", "--help" } })
        CHECK(parseCommandLine(args).action == CommandLine::Action::help);

    CHECK(parseCommandLine({ "--list-params" }).action == CommandLine::Action::listParameters);
    CHECK(parseCommandLine({ "--list-params", "--bench-short" }).action == CommandLine::Action::listParameters);
    CHECK(errorOf({ "--list-params", "--bogus" }) == "unknown option '--bogus' (see --help)");
    CHECK(errorOf({ "--list-params", "--seconds", "0" }) == "--seconds: '0' must be greater than 0 and at most 3600");
}

TEST_CASE("every option the help names is an option", "[renderer][command-line]")
{
    const auto help = helpText();
    const std::regex option(R"((^|[\s(\[|])(--[a-z][a-z-]*[a-z]|-[a-z])\b)");
    std::set<std::string> named;
    for (auto it = std::sregex_iterator(help.begin(), help.end(), option); it != std::sregex_iterator(); ++it)
        named.insert((*it)[2]);
    CHECK(named.size() >= 23);
    for (const auto& name : named)
    {
        INFO(name);
        CHECK(errorOf({ name }).find("unknown option") == std::string::npos);
    }
}

TEST_CASE("the fuzzer's seed corpus: a job or a UserError, nothing else", "[renderer][command-line]")
{
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(SNARESIM_COMMAND_LINE_CORPUS))
    {
        INFO(entry.path());
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string bytes { std::istreambuf_iterator<char>(in), {} };

        // As Tests/Fuzz/Fuzz_command_line.cpp: arguments separated by NUL bytes.
        Args args { "" };
        for (const char c : bytes)
            if (c == '\0')
                args.emplace_back();
            else
                args.back().push_back(c);
        if (args.back().empty())
            args.pop_back();

        try
        {
            const auto command = parseCommandLine(args);
            if (command.action == CommandLine::Action::render)
                (void) makeParameters(command.job);
        }
        catch (const UserError&)
        {}
        ++files;
    }
    CHECK(files >= 6);
}

TEST_CASE("the air box's options: microphones, walls, box, margin, threads", "[renderer][command-line]")
{
    const auto job = jobOf(playable({ "--air-mic", "0.1,0,0.12", "--air-mic", "-0.2,0.05,-0.3", "--walls", "reflecting", "--box",
                                      "0.7,0.6,0.8", "--box-margin", "0.1", "--threads", "2" }));
    REQUIRE(job.airMics.size() == 2);
    CHECK(job.airMics[0].x == 0.1);
    CHECK(job.airMics[0].z == 0.12);
    CHECK(job.airMics[1].x == -0.2);
    CHECK(job.airMics[1].z == -0.3);
    CHECK(job.walls == snaresim::render::Walls::reflecting);
    REQUIRE(job.boxSize.has_value());
    CHECK(job.boxSize->y == 0.6);
    CHECK(job.boxMargin == 0.1);
    CHECK(job.threads == 2);
    const auto cube = jobOf(playable({ "--box", "0.5" })).boxSize;
    REQUIRE(cube.has_value());
    CHECK((cube->x == 0.5 && cube->y == 0.5 && cube->z == 0.5));

    CHECK(errorOf(playable({ "--air-mic", "0.1,0" })) == "--air-mic: '0.1,0' is not X,Y,Z in metres");
    CHECK(errorOf(playable({ "--air-mic", "0.1,0,0,4" })) == "--air-mic: '0.1,0,0,4' is not X,Y,Z in metres");
    CHECK(errorOf(playable({ "--air-mic", "a,0,0" })) == "--air-mic: 'a' is not a number");
    CHECK(errorOf(playable({ "--box", "0" })) == "--box: '0' must be positive sizes in metres");
    CHECK(errorOf(playable({ "--box", "1,-1,1" })) == "--box: '1,-1,1' must be positive sizes in metres");
    CHECK(errorOf(playable({ "--box-margin", "0" })) == "--box-margin: '0' must be greater than 0 (metres)");
    CHECK(errorOf(playable({ "--walls", "open" })) == "--walls: 'open' is not one of absorbing|reflecting");
    CHECK(errorOf(playable({ "--threads", "0" })) == "--threads: '0' is outside 1..64");
    CHECK(errorOf(playable({ "--threads", "65" })) == "--threads: '65' is outside 1..64");
}

TEST_CASE("match options: the recording, the preset file, the parameters searched and the budget", "[renderer][command-line][match]")
{
    const auto job = jobOf({ "--match", "snare.flac", "-o", "m.snarepreset", "--match-params", "batter_tension,velocity,snare_count",
                             "--match-budget", "100" });
    REQUIRE(job.match);
    CHECK(job.match->string() == "snare.flac");
    CHECK(job.output->string() == "m.snarepreset");
    REQUIRE(job.matchParams);
    CHECK(*job.matchParams ==
          std::vector<MatchCoordinate> { { snaresim::ParamId::batterTension }, { std::nullopt }, { snaresim::ParamId::snareCount } });
    CHECK(job.matchBudget == 100);
    CHECK_FALSE(jobOf({ "--match", "a.wav", "-o", "m.snarepreset" }).matchParams); // the default list

    CHECK(errorOf({ "--match", "a.wav" }) == "--match: missing -o PRESET_FILE, the preset file to write (see --help)");
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-params", "batter_tension,bogus" }) ==
          "--match-params: unknown parameter 'bogus' (see --list-params)");
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-params", "" }).starts_with("--match-params: '' is not a comma-separated list"));
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-params", "damping," }).starts_with("--match-params: 'damping,' is not"));
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-params", "velocity,velocity" }) == "--match-params: 'velocity' is given twice");
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-params", "air_model" }).find("a switch or a choice") != std::string::npos);
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-budget", "11" }) == "--match-budget: '11' is outside 12..100000 renders");
    CHECK(errorOf(playable({ "--match-params", "damping" })) == "--match-params is an option of --match");
    CHECK(errorOf(playable({ "--match-budget", "50" })) == "--match-budget is an option of --match");
    CHECK(jobOf({ "--match", "a.wav", "-o", "m", "--match-seed", "42" }).matchSeed == 42);
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--match-seed", "-1" }) == "--match-seed: '-1' is outside 0..2147483647");
    CHECK(errorOf(playable({ "--match-seed", "5" })) == "--match-seed is an option of --match");
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--sample-rate", "44100" }).starts_with("--sample-rate cannot be used with --match"));
}

TEST_CASE("distance options: the strikes, the recordings, and what they cannot go with", "[renderer][command-line][distance]")
{
    const auto job = jobOf({ "--distance", "a.wav", "--ref", "kits/Forzee:Snare-*.wav", "--distance", "b.aiff", "--ref", "k:x:y" });
    CHECK(job.distanceFiles == std::vector<std::filesystem::path> { "a.wav", "b.aiff" });
    REQUIRE(job.references.size() == 2);
    CHECK(job.references[0].kitDir == "kits/Forzee");
    CHECK(job.references[0].pattern == "Snare-*.wav");
    CHECK(job.references[0].text == "kits/Forzee:Snare-*.wav");
    CHECK(job.references[1].kitDir == "k"); // split at the first ':'
    CHECK(job.references[1].pattern == "x:y");
    CHECK_FALSE(job.output);

    const auto render = jobOf(playable({ "--ref", "k:*.wav" })); // a render measured too
    CHECK(render.references.size() == 1);
    CHECK(render.distanceFiles.empty());

    CHECK(errorOf({ "--distance", "a.wav" }) == "--distance: missing --ref KITDIR:GLOB, the recordings to measure against (see --help)");
    for (const auto* bad : { "kits", ":*.wav", "kits:" })
        CHECK(errorOf({ "--distance", "a.wav", "--ref", bad }).starts_with("--ref: '" + std::string(bad) + "' is not KITDIR:GLOB"));
    CHECK(errorOf({ "--distance", "a.wav", "--ref", "k:*", "-o", "x.wav" }).starts_with("-o cannot be used with --distance"));
    CHECK(errorOf({ "--distance", "a.wav", "--ref", "k:*", "--sample-rate", "44100" })
              .starts_with("--sample-rate cannot be used with --distance"));
    CHECK(errorOf({ "--distance", "a.wav", "--ref", "k:*", "--match", "b.wav" }) == "--match cannot be used with --distance");
    CHECK(errorOf({ "--match", "a.wav", "-o", "m", "--ref", "k:*" }) == "--ref cannot be used with --match");
    CHECK(errorOf({ "--bench", "--ref", "k:*" }).starts_with("--ref cannot be used with --bench"));
    CHECK(errorOf({ "--distance" }) == "option --distance needs a value (see --help)");
}
