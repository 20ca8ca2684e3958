#pragma once
// Helpers for the snaresim-render tests: running the binary with captured output, a
// temporary directory per test, reading the WAV / CSV / JSON / PNG it writes.

#include <juce_core/juce_core.h>
#include <juce_graphics/juce_graphics.h>

#include "Drum.h"
#include "DrumConfig.h"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace rendertest
{

namespace fs = std::filesystem;

struct RunResult
{
    int exitCode = -1; // -1: did not exit normally
    std::string out;
    std::string err;
};

// A fresh directory, removed with everything in it at the end of the test. Tests put
// inputs under in() and outputs under out(); the captured stdout/stderr live elsewhere.
class TempDir
{
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const fs::path& root() const { return base; }
    fs::path in() const { return base / "in"; }
    fs::path out() const { return base / "out"; }

private:
    fs::path base;
};

// Runs snaresim-render with these arguments (no shell), capturing stdout and stderr. Its
// environment is this process's with `environment` laid over it: "NAME=VALUE" sets NAME,
// "NAME" alone removes it.
RunResult runRenderer(const std::vector<std::string>& args, const fs::path& captureDir, const std::vector<std::string>& environment = {});

// The same in two halves: start it, then wait for it to end.
int startRenderer(const std::vector<std::string>& args, const fs::path& captureDir,
                  const std::vector<std::string>& environment = {}); // the pid
RunResult waitForRenderer(int pid, const fs::path& captureDir);

// Names of the entries of a directory, sorted.
std::vector<std::string> entries(const fs::path& directory);

struct WavData
{
    bool opened = false;
    double sampleRate = 0.0;
    int channels = 0;
    int bitsPerSample = 0;
    bool floatingPoint = false;
    long long length = 0;
    std::vector<float> samples;                     // channel 0
    std::vector<std::vector<float>> channelSamples; // every channel
};

WavData readWav(const fs::path& file);

struct PngData
{
    bool loaded = false;       // juce::ImageFileFormat::loadFrom gave an image
    bool pngSignature = false; // the file starts with the PNG signature
    int width = 0;
    int height = 0;
};

PngData readPng(const fs::path& file);

// The image of a picture file (invalid when it cannot be loaded).
juce::Image loadImage(const fs::path& file);

// Checks that `file` is a PNG of this size with more than one colour (REQUIRE: it loads).
void requirePicture(const fs::path& file, int width, int height);

// The number of distinct colours (ARGB) in a region of an image file (0 when it cannot be
// loaded), counting at most `limit`.
int distinctColours(const fs::path& file, int x, int y, int width, int height, int limit = 1000);

// Largest |x| of a signal, and the RMS of the difference of two (equal lengths).
float peakOf(const std::vector<float>& signal);
double rmsDifference(const std::vector<float>& a, const std::vector<float>& b);

std::string readText(const fs::path& file);

juce::var parseJson(const std::string& text);

// Every line of a text, without the line ends.
std::vector<std::string> lines(const std::string& text);

// The comma-separated fields of a line.
std::vector<std::string> csvFields(const std::string& line);

// The columns of an energy CSV (--energy-csv), from its header line: time_s, the ledger's terms,
// total_J, dissipated_J, injected_J, balance_J (REQUIRE: the fixed ones are there, in that order).
struct EnergyColumns
{
    std::vector<std::string> names;
    std::vector<std::size_t> terms; // the columns between time_s and total_J
    std::size_t total = 0, dissipated = 0, injected = 0, balance = 0;
};
EnergyColumns energyColumns(const std::string& header);

// The renderer's drum played in-process, as Renderer.cpp plays it: each strike (sample, MIDI
// velocity) at the default strike point before the step of its sample, the mix as float with
// the drum's lag taken off (Drum::latencySamples).
struct EngineRun
{
    std::vector<float> mix;
    snaresim::SolverStats stats;
    double peak = 0.0;
    double rms = 0.0;
};
EngineRun playInProcess(const snaresim::DrumConfig& config, const std::vector<std::pair<long long, int>>& strikes, long long numSamples);

// Runs the renderer with exactly these arguments and checks the bad-input contract: exit 2,
// one line on stderr starting with "snaresim-render: error: " and naming `mentions`, nothing
// on stdout, nothing left in dir.out().
void requireRejected(const TempDir& dir, const std::vector<std::string>& args, const std::string& mentions);

} // namespace rendertest
