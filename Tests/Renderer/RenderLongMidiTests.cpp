// A long MIDI render as a batch script or a person at a terminal runs it: 100 000 notes,
// rendered with a progress line when stderr is a terminal (and only then, and not with --json),
// in memory that grows with neither the number of notes beyond their list nor the length.

#include "RendererTestSupport.h"
#include "Report.h"

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using namespace rendertest;

namespace
{

// A format-0 Standard MIDI file: `notes` note-ons of note 38 (velocity 100), one every
// millisecond (1000 ticks a quarter note at 1 s a quarter note), in running status.
void writeMidi(const fs::path& file, int notes)
{
    std::string track;
    track += std::string("\x00\xff\x51\x03\x0f\x42\x40", 7); // tempo: 1 000 000 us a quarter note
    for (int i = 0; i < notes; ++i)
    {
        track += i == 0 ? std::string("\x00\x99", 2) : std::string("\x01", 1);
        track += std::string("\x26\x64", 2);
    }
    track += std::string("\x00\xff\x2f\x00", 4);

    auto be32 = [](std::uint32_t v) { return std::string { (char) (v >> 24), (char) (v >> 16), (char) (v >> 8), (char) v }; };
    std::ofstream out(file, std::ios::binary);
    out << "MThd" << be32(6) << std::string("\x00\x00\x00\x01\x03\xe8", 6) << "MTrk" << be32((std::uint32_t) track.size()) << track;
}

// The child's own peak resident size (VmHWM, kB), polled every 5 ms until it exits; then its
// exit status. (wait4's ru_maxrss is no use here: a spawned child counts its parent's peak.)
int waitPolling(pid_t pid, long& peak_kB)
{
    const auto statusFile = "/proc/" + std::to_string((long) pid) + "/status";
    int status = 0;
    for (;;)
    {
        std::ifstream in(statusFile);
        for (std::string line; std::getline(in, line);)
            if (line.rfind("VmHWM:", 0) == 0)
                peak_kB = std::max(peak_kB, std::atol(line.c_str() + 6));
        const pid_t done = ::waitpid(pid, &status, WNOHANG);
        if (done == pid)
            return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        REQUIRE(done == 0);
        ::usleep(5000);
    }
}

struct PtyRun
{
    int exitCode = -1;
    std::string terminal; // what the renderer wrote to the terminal (stderr)
    std::string out;      // its stdout
    long maxRss_kB = 0;   // the renderer's own peak (VmHWM)
};

// Runs snaresim-render with stderr (and stdin) on a pseudo-terminal and stdout to a file.
PtyRun runOnTerminal(const std::vector<std::string>& args, const fs::path& stdoutFile)
{
    std::vector<std::string> all { SNARESIM_RENDER_EXE };
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all)
        argv.push_back(a.data());
    argv.push_back(nullptr);

    int master = -1;
    const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
    REQUIRE(pid >= 0);
    if (pid == 0)
    {
        const int fd = ::open(stdoutFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd < 0 || ::dup2(fd, STDOUT_FILENO) < 0)
            ::_exit(126);
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }

    PtyRun run;
    char buffer[4096];
    for (;;)
    {
        const ssize_t n = ::read(master, buffer, sizeof buffer);
        if (n > 0)
            run.terminal.append(buffer, (size_t) n);
        else if (n < 0 && errno == EINTR)
            continue;
        else
            break; // EIO: the renderer closed the terminal (it exited)
    }
    ::close(master);

    run.exitCode = waitPolling(pid, run.maxRss_kB);
    run.out = readText(stdoutFile);
    return run;
}

// Peak resident size of a render with stderr on a pipe (ordinary capture).
long peakRssOfRun(const std::vector<std::string>& args, const fs::path& capture, RunResult& result)
{
    const int pid = startRenderer(args, capture);
    long peak = 0;
    result.exitCode = waitPolling(pid, peak);
    result.out = readText(capture / "stdout.txt");
    result.err = readText(capture / "stderr.txt");
    return peak;
}

// A cheap drum: coarse grids (the coarsest 16 kHz allows), one wire, no air, at 16 kHz.
std::vector<std::string> cheap(std::vector<std::string> args)
{
    for (const char* a : { "--sample-rate", "16000", "--set", "snare_count=1", "--model", "none" })
        args.emplace_back(a);
    return args;
}

} // namespace

TEST_CASE("a MIDI file of 100 000 notes renders with a progress line on a terminal, in bounded memory", "[renderer][long][slow]")
{
    TempDir dir;
    const auto many = dir.in() / "many.mid", few = dir.in() / "few.mid";
    writeMidi(many, 100000); // 100 s of notes, one every millisecond
    writeMidi(few, 1000);    // the first second of them

    // On a terminal: the progress line, then the summary on stdout. 300 s of audio, so that the
    // render takes far longer than the line's delay (2 s): about 24 s on the AVX2 machine
    // (BENCHMARKS.md), where 200 s took 15.8 s.
    const auto run = runOnTerminal(cheap({ "-o", (dir.out() / "many.wav").string(), "--midi", many.string(), "--seconds", "300" }),
                                   dir.root() / "stdout.txt");
    INFO("terminal: " << run.terminal);
    REQUIRE(run.exitCode == 0);
    const auto wav = readWav(dir.out() / "many.wav");
    REQUIRE(wav.opened);
    CHECK(wav.length == 300LL * 16000);
    CHECK(run.terminal.find("\rsnaresim-render: ") != std::string::npos);
    CHECK(run.terminal.find("s of audio") != std::string::npos);
    CHECK(run.terminal.find("100%") != std::string::npos);
    CHECK(run.out.find("strikes") != std::string::npos);

    // The same on a terminal with --json, just past the last note: no progress, stdout is one
    // JSON object.
    const auto quiet =
        runOnTerminal(cheap({ "-o", (dir.out() / "many-json.wav").string(), "--midi", many.string(), "--seconds", "101", "--json" }),
                      dir.root() / "stdout-json.txt");
    CHECK(quiet.exitCode == 0);
    CHECK(quiet.terminal.find("snaresim-render") == std::string::npos);
    CHECK(parseJson(quiet.out).getProperty("strikes", 0).operator int() == 100000);

    // Stderr on a pipe: nothing on it. And the memory: the 100 000 notes against 1 000 notes
    // rendered for as long, and those against a render a tenth as long.
    RunResult manyRun, fewRun, shortRun;
    const long manyRss = peakRssOfRun(cheap({ "-o", (dir.out() / "a.wav").string(), "--midi", many.string(), "--seconds", "200" }),
                                      dir.root() / "capture", manyRun);
    const long fewRss = peakRssOfRun(cheap({ "-o", (dir.out() / "b.wav").string(), "--midi", few.string(), "--seconds", "200" }),
                                     dir.root() / "capture", fewRun);
    const long shortRss = peakRssOfRun(cheap({ "-o", (dir.out() / "c.wav").string(), "--midi", few.string(), "--seconds", "20" }),
                                       dir.root() / "capture", shortRun);
    REQUIRE(manyRun.exitCode == 0);
    REQUIRE(fewRun.exitCode == 0);
    REQUIRE(shortRun.exitCode == 0);
    CHECK(manyRun.err.empty());
    CHECK(fewRun.err.empty());

    // The output is streamed to disk: ten times the length costs no memory to speak of (the
    // 200 s of audio would be 12.8 MB held). The notes cost their list and the MIDI reader's
    // copy of the file's events (juce::MidiFile: about 220 bytes a note): 400 bytes a note at most.
    CHECK(fewRss - shortRss < 2 * 1024);
    CHECK(manyRss - fewRss < 100000 * 400 / 1024);
    snaresim::test::report()
        << "100 000-note MIDI file: 300 s of audio at 16 kHz rendered with a progress line on a terminal; peak RSS of 200 s "
        << manyRss / 1024 << " MB (1 000 notes for as long: " << fewRss / 1024 << " MB; a tenth as long: " << shortRss / 1024 << " MB)\n";
}
