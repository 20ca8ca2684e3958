// snaresim-render's bad input: every kind exits with code 2, prints exactly one line on
// stderr starting with "snaresim-render: error: ", and leaves nothing in the target
// directory (no output, no temporary).

#include "RendererTestSupport.h"
#include "Report.h"

#include "Parameters.h"

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>
#include <iterator>
#include <thread>

using namespace rendertest;

namespace
{

// The bad-input contract (requireRejected) for these arguments after "-o OUT/out.wav", unless
// withOutput is false.
void requireBadInput(const TempDir& dir, std::vector<std::string> args, const std::string& mentions, bool withOutput = true)
{
    if (withOutput)
        args.insert(args.begin(), { "-o", (dir.out() / "out.wav").string() });
    requireRejected(dir, args, mentions);
}

} // namespace

TEST_CASE("bad input: unknown options, stray arguments and missing values", "[renderer][errors]")
{
    TempDir dir;
    requireBadInput(dir, { "--hit", "0:100", "--bogus" }, "--bogus");
    requireBadInput(dir, { "--hit", "0:100", "-x" }, "-x");
    requireBadInput(dir, { "--hit", "0:100", "stray.wav" }, "stray.wav");
    requireBadInput(dir, { "--hit", "0:100", "--seconds" }, "--seconds");
    requireBadInput(dir, { "--hit", "--seconds", "1" }, "--hit");
    requireBadInput(dir, { "--hit", "0:100", "--json=yes" }, "--json");
    requireBadInput(dir, { "--hit", "0:100", "--seconds", "1", "--seconds", "2" }, "--seconds");
    requireBadInput(dir, { "--hit", "0:100", "-o" }, "-o", false);
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot" }, "--snare-plot");
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot", "--json" }, "--snare-plot");
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot", "" }, "empty file name");
    requireBadInput(dir,
                    { "--hit", "0:100", "--snare-plot", (dir.out() / "a.png").string(), "--snare-plot", (dir.out() / "b.png").string() },
                    "more than once");
}

TEST_CASE("bad input: missing -o, or nothing to play", "[renderer][errors]")
{
    TempDir dir;
    requireBadInput(dir, { "--hit", "0:100" }, "-o", false);
    requireBadInput(dir, { "--seconds", "1" }, "--hit");
}

TEST_CASE("bad input: bad numbers", "[renderer][errors]")
{
    TempDir dir;
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases {
        { { "--hit", "0:100", "--seconds", "abc" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "0" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "-1" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "nan" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "inf" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "1e400" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "2s" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "1e-9" }, "--seconds" },
        { { "--hit", "0:100", "--seconds", "100000" }, "--seconds" },
        { { "--hit", "1:200" }, "velocity" },
        { { "--hit", "1:0" }, "velocity" },
        { { "--hit", "1:64.5" }, "velocity" },
        { { "--hit", "-1:100" }, "time" },
        { { "--hit", "nan:100" }, "time" },
        { { "--hit", "x:100" }, "time" },
        { { "--hit", "0.5" }, "--hit" },
        { { "--hit", "0:100", "--sample-rate", "abc" }, "--sample-rate" },
        { { "--hit", "0:100", "--sample-rate", "4000" }, "--sample-rate" },
        { { "--hit", "0:100", "--sample-rate", "400000" }, "--sample-rate" },
        { { "--hit", "0:100", "--sample-rate", "44100.5" }, "--sample-rate" },
        { { "--hit", "0:100", "--set", "mallet_mass=heavy" }, "mallet_mass" },
        // Integer, toggle and choice parameters take whole numbers only.
        { { "--hit", "0:100", "--set", "snares_engaged=0.5" }, "snares_engaged" },
        { { "--hit", "0:100", "--set", "snare_count=12.5" }, "snare_count" },
        { { "--hit", "0:100", "--set", "air_model=0.5" }, "air_model" },
        { { "--hit", "0:100", "--set", "air_model=bogus" }, "air_model" },
        { { "--hit", "0:100", "--set", "snare_solver=iterative" }, "snare_solver" },
    };
    for (const auto& [args, mentions] : cases)
        requireBadInput(dir, args, mentions);
}

TEST_CASE("bad input: unknown parameters, out-of-range values, unknown presets", "[renderer][errors]")
{
    TempDir dir;
    requireBadInput(dir, { "--hit", "0:100", "--set", "no_such_parameter=1" }, "no_such_parameter");
    requireBadInput(dir, { "--hit", "0:100", "--set", "mallet_mass" }, "mallet_mass");
    requireBadInput(dir, { "--hit", "0:100", "--preset", "No Such Preset" }, "No Such Preset");

    // preset files: missing, not a preset file, a bad line (named with its line number)
    fs::create_directories(dir.in());
    const auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir.in() / name, std::ios::binary) << text;
        return (dir.in() / name).string();
    };
    requireBadInput(dir, { "--hit", "0:100", "--preset", (dir.in() / "missing.snarepreset").string() }, "no such preset file");
    requireBadInput(dir, { "--hit", "0:100", "--preset", write("empty.snarepreset", "") }, "no 'name");
    requireBadInput(dir, { "--hit", "0:100", "--preset", write("wav.snarepreset", std::string("RIFF\0\0\0\0WAVE", 12)) }, "binary");
    requireBadInput(dir, { "--hit", "0:100", "--preset", write("bad.snarepreset", "name = Bad\ndamping = 20\nbatter_tension = 90000\n") },
                    "line 3");
    requireBadInput(dir, { "--hit", "0:100", "--preset", write("unknown.snarepreset", "name = U\nloudness = 11\n") },
                    "unknown parameter 'loudness'");
    requireBadInput(dir, { "--hit", "0:100", "--preset", (dir.in()).string() + "/" }, "no such preset file");

    // every parameter just outside its range, whole numbers for the whole-numbered kinds (a
    // fraction there is refused before the range is looked at: "bad numbers")
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const bool whole = spec.kind != snaresim::ParamKind::continuous;
        const double span = spec.maxValue - spec.minValue;
        const double above = whole ? spec.maxValue + 1.0 : spec.maxValue + 0.5 * span + 1.0;
        const double below = whole ? spec.minValue - 1.0 : spec.minValue - 0.5 * span - 1.0;
        for (const double value : { above, below })
        {
            const auto assignment = std::string(spec.key) + "=" + (whole ? std::to_string((long long) value) : std::to_string(value));
            INFO(assignment);
            requireBadInput(dir, { "--hit", "0:100", "--set", assignment }, "outside its range");
        }
    }
}

TEST_CASE("bad input: --model and --mic take only their names", "[renderer][errors]")
{
    TempDir dir;
    requireBadInput(dir, { "--hit", "0:100", "--model", "bogus" }, "--model");
    requireBadInput(dir, { "--hit", "0:100", "--model", "" }, "--model");
    requireBadInput(dir, { "--hit", "0:100", "--model", "Cavity" }, "--model");
    requireBadInput(dir, { "--hit", "0:100", "--model", "none", "--model", "cavity" }, "--model");
    requireBadInput(dir, { "--hit", "0:100", "--model" }, "--model");
    requireBadInput(dir, { "--hit", "0:100", "--mic", "left" }, "--mic");
    requireBadInput(dir, { "--hit", "0:100", "--mic", "all", "--mic", "mix" }, "--mic");
}

TEST_CASE("bad input: a grid or sample rate the scheme cannot take", "[renderer][errors]")
{
    TempDir dir;
    // At 8 kHz, Quality's coarsest grids (about 4 times the stability bound, eq. 39) leave fewer
    // than 4 grid points per radius; the engine throws std::invalid_argument, reported as "the
    // model cannot be ...".
    requireBadInput(dir, { "--hit", "0:100", "--sample-rate", "8000", "--set", "bandwidth=3750" }, "the model cannot be");
}

TEST_CASE("bad input: an air box that does not hold the drum, microphones outside it or in the shell, no threads",
          "[renderer][errors][airbox]")
{
    TempDir dir;
    const std::vector<std::string> box { "--hit", "0:100", "--seconds", "0.01", "--sample-rate", "22050", "--model", "airbox" };
    auto with = [&](std::vector<std::string> more) {
        auto args = box;
        args.insert(args.end(), more.begin(), more.end());
        return args;
    };
    requireBadInput(dir, with({ "--box", "0.3" }), "does not hold the drum");
    requireBadInput(dir, with({ "--box", "0,1,1" }), "--box");
    requireBadInput(dir, with({ "--box-margin", "-0.1" }), "--box-margin");
    requireBadInput(dir, with({ "--air-mic", "1,0,0" }), "inside the air box");
    requireBadInput(dir, with({ "--air-mic", "0,0,0" }), "inside the drum's shell");
    requireBadInput(dir, with({ "--threads", "0" }), "--threads");
    requireBadInput(dir, with({ "--box", "0.7", "--box-margin", "0.1" }), "one or the other");
    requireBadInput(dir, { "--hit", "0:100", "--air-mic", "0,0,0.2" }, "applies to the air box only");
    requireBadInput(dir, { "--hit", "0:100", "--mic", "air" }, "--mic air");
}

TEST_CASE("bad input: the air box's options without the air box, too many or malformed air microphones", "[renderer][errors][airbox]")
{
    TempDir dir;
    requireBadInput(dir, { "--hit", "0:100", "--walls", "reflecting" }, "--walls applies to the air box only");
    requireBadInput(dir, { "--hit", "0:100", "--box", "1" }, "--box applies to the air box only");
    requireBadInput(dir, { "--hit", "0:100", "--box-margin", "0.1" }, "--box-margin applies to the air box only");
    requireBadInput(dir, { "--hit", "0:100", "--threads", "2" }, "--threads applies to the air box only");
    requireBadInput(dir, { "--hit", "0:100", "--model", "airbox", "--walls", "rigid" }, "--walls");
    requireBadInput(dir, { "--hit", "0:100", "--model", "airbox", "--air-mic", "1,2" }, "--air-mic");
    std::vector<std::string> nine { "--hit", "0:100", "--model", "airbox" };
    for (int i = 1; i <= 9; ++i)
        nine.insert(nine.end(), { "--air-mic", "0.3,0,0." + std::to_string(i) });
    requireBadInput(dir, nine, "at most 8 air microphones");
}

TEST_CASE("bad input: an output over the MIDI file, a negative seed, an empty preset name, a directory as the output", "[renderer][errors]")
{
    TempDir dir;
    fs::create_directories(dir.out());
    // one snare note (38, velocity 100) and its note-off, 480 ticks a quarter note
    const std::string bytes("MThd\0\0\0\6\0\0\0\1\1\xe0MTrk\0\0\0\x0c\0\x99\x26\x64\x60\x89\x26\0\0\xff\x2f\0", 34);
    const auto midi = dir.out() / "x.mid";
    std::ofstream(midi, std::ios::binary) << bytes;
    requireBadInput(dir, { "-o", midi.string(), "--midi", midi.string() }, "would overwrite the MIDI file (-o)", false);
    requireBadInput(dir, { "--midi", midi.string(), "--energy-csv", midi.string() }, "would overwrite the MIDI file (--energy-csv)");
    std::ifstream in(midi, std::ios::binary);
    CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == bytes); // the MIDI file as it was
    in.close();
    fs::remove(midi);

    requireBadInput(dir, { "--hit", "0:100", "--match-seed", "-1" }, "--match-seed");
    requireBadInput(dir, { "--hit", "0:100", "--preset", "" }, "empty preset name");
    requireBadInput(dir, { "-o", dir.out().string() + "/", "--hit", "0:100" }, "not a file name", false);
}

TEST_CASE("bad input: unreadable or invalid MIDI files", "[renderer][errors]")
{
    TempDir dir;
    const auto garbage = dir.in() / "garbage.mid";
    std::ofstream(garbage) << "this is not a MIDI file, not even close\n";
    const auto empty = dir.in() / "empty.mid";
    std::ofstream { empty };

    requireBadInput(dir, { "--midi", (dir.in() / "missing.mid").string() }, "missing.mid");
    requireBadInput(dir, { "--midi", garbage.string() }, "garbage.mid");
    requireBadInput(dir, { "--midi", empty.string() }, "empty.mid");
    requireBadInput(dir, { "--midi", dir.in().string() }, "directory");
}

TEST_CASE("bad input: unwritable outputs fail before rendering and leave nothing behind", "[renderer][errors]")
{
    TempDir dir;
    const auto missing = dir.out() / "no-such-dir" / "out.wav";
    requireBadInput(dir, { "-o", missing.string(), "--hit", "0:100" }, "does not exist", false);

    // The target is a directory.
    fs::create_directory(dir.out() / "sub");
    requireBadInput(dir, { "-o", (dir.out() / "sub").string(), "--hit", "0:100" }, "directory", false);
    CHECK(fs::is_directory(dir.out() / "sub"));
    fs::remove(dir.out() / "sub");

    // The WAV is fine but the energy CSV is not: neither appears.
    requireBadInput(dir, { "--hit", "0:100", "--energy-csv", (dir.out() / "nowhere" / "e.csv").string() }, "does not exist");

    // Both outputs on the same file.
    requireBadInput(dir, { "--hit", "0:100", "--energy-csv", (dir.out() / "out.wav").string() }, "same file");
    requireBadInput(dir, { "--hit", "0:100", "--energy-csv", (dir.out() / "." / "out.wav").string() }, "same file");

    // The PNG outputs: a missing directory, a directory, or the name of another output.
    // Every other output is fine, and none appears.
    const auto energy = (dir.out() / "e.png").string();
    const auto spectrum = (dir.out() / "s.png").string();
    requireBadInput(dir,
                    { "--hit", "0:100", "--energy-csv", (dir.out() / "e.csv").string(), "--spectrogram", spectrum, "--energy-plot",
                      (dir.out() / "nowhere" / "e.png").string() },
                    "does not exist");
    requireBadInput(dir, { "--hit", "0:100", "--energy-plot", energy, "--spectrogram", (dir.out() / "nowhere" / "s.png").string() },
                    "does not exist");
    fs::create_directory(dir.out() / "sub.png");
    requireBadInput(dir, { "--hit", "0:100", "--energy-plot", energy, "--spectrogram", (dir.out() / "sub.png").string() }, "directory");
    requireBadInput(dir, { "--hit", "0:100", "--energy-plot", energy, "--snare-plot", (dir.out() / "sub.png").string() }, "directory");
    fs::remove(dir.out() / "sub.png");
    requireBadInput(dir, { "--hit", "0:100", "--energy-plot", (dir.out() / "out.wav").string() }, "same file");
    requireBadInput(dir, { "--hit", "0:100", "--spectrogram", energy, "--energy-plot", energy }, "same file");
    requireBadInput(dir, { "--hit", "0:100", "--energy-csv", spectrum, "--spectrogram", spectrum }, "same file");

    // --snare-plot: the same rules.
    const auto snares = (dir.out() / "w.png").string();
    requireBadInput(dir,
                    { "--hit", "0:100", "--energy-plot", energy, "--spectrogram", spectrum, "--snare-plot",
                      (dir.out() / "nowhere" / "w.png").string() },
                    "does not exist");
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot", snares, "--energy-plot", (dir.out() / "nowhere" / "e.png").string() },
                    "does not exist");
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot", (dir.out() / "out.wav").string() }, "same file");
    requireBadInput(dir, { "--hit", "0:100", "--spectrogram", snares, "--snare-plot", snares }, "same file");
    requireBadInput(dir, { "--hit", "0:100", "--snare-plot", (dir.out() / "." / "e.png").string(), "--energy-plot", energy }, "same file");

    // A directory without write permission (skipped when running as root).
    const auto locked = dir.root() / "locked";
    fs::create_directory(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    if (std::ofstream(locked / "probe").good())
    {
        WARN("running with permissions that ignore directory modes; skipping the read-only case");
    }
    else
    {
        requireBadInput(dir, { "-o", (locked / "out.wav").string(), "--hit", "0:100" }, "locked", false);
        CHECK(entries(locked).empty());
    }
    fs::permissions(locked, fs::perms::owner_all);
}

TEST_CASE("interrupted: SIGINT, SIGTERM or SIGHUP during a render leaves no output, no temporary, and an older file intact",
          "[renderer][errors]")
{
    int tried = 0;
    for (const int signalNumber : { SIGINT, SIGTERM, SIGHUP })
    {
        INFO("signal " << signalNumber);
        TempDir dir;
        const auto capture = dir.root() / "capture";

        // A file of that name from before: it must survive the interrupted render unchanged.
        const auto target = dir.out() / "long.wav";
        {
            std::ofstream old(target);
            old << "an older render";
        }

        const int pid = startRenderer({ "-o", target.string(), "--energy-csv", (dir.out() / "long.csv").string(), "--energy-plot",
                                        (dir.out() / "long-energy.png").string(), "--spectrogram",
                                        (dir.out() / "long-spectrum.png").string(), "--hit", "0:100", "--seconds", "600" },
                                      capture);

        // Wait until it is rendering (its four temporaries exist beside the old file), then stop it.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (entries(dir.out()).size() < 5 && std::chrono::steady_clock::now() < deadline)
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        CHECK(entries(dir.out()).size() == 5);
        ::kill(pid, signalNumber);

        const auto run = waitForRenderer(pid, capture);
        INFO("stderr: " << run.err);
        CHECK(run.exitCode == 128 + signalNumber);
        CHECK(lines(run.err).size() == 1);
        CHECK(entries(dir.out()) == std::vector<std::string> { "long.wav" });
        CHECK(readText(target) == "an older render");
        ++tried;
    }
    snaresim::test::report() << "interrupted renders: " << tried
                             << " signals (SIGINT, SIGTERM, SIGHUP), exit 128 + N, nothing left behind\n";
}
