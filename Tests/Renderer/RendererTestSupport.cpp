#include "RendererTestSupport.h"

#include <catch2/catch.hpp>

#include <juce_audio_formats/juce_audio_formats.h>
#include <juce_graphics/juce_graphics.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <set>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

extern char** environ;

namespace rendertest
{

TempDir::TempDir()
{
    auto pattern = (fs::temp_directory_path() / "snaresim-render-test-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
        throw std::runtime_error("mkdtemp failed");
    base = pattern;
    fs::create_directory(in());
    fs::create_directory(out());
    fs::create_directory(base / "capture");
}

TempDir::~TempDir()
{
    std::error_code ec;
    fs::remove_all(base, ec);
}

int startRenderer(const std::vector<std::string>& args, const fs::path& captureDir, const std::vector<std::string>& environment)
{
    // This process's environment less the names `environment` names, then its settings.
    const auto nameOf = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
    std::set<std::string> overridden;
    for (const auto& entry : environment)
        overridden.insert(nameOf(entry));
    std::vector<std::string> envStrings;
    for (char** e = environ; *e != nullptr; ++e)
        if (overridden.count(nameOf(*e)) == 0)
            envStrings.emplace_back(*e);
    for (const auto& entry : environment)
        if (entry.find('=') != std::string::npos)
            envStrings.push_back(entry);
    std::vector<char*> envp;
    for (auto& s : envStrings)
        envp.push_back(s.data());
    envp.push_back(nullptr);

    const auto outFile = (captureDir / "stdout.txt").string();
    const auto errFile = (captureDir / "stderr.txt").string();

    std::vector<std::string> argvStrings { SNARESIM_RENDER_EXE };
    argvStrings.insert(argvStrings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& s : argvStrings)
        argv.push_back(s.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);

    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
        throw std::runtime_error("cannot run " SNARESIM_RENDER_EXE);
    return (int) pid;
}

RunResult waitForRenderer(int pid, const fs::path& captureDir)
{
    int status = 0;
    while (waitpid((pid_t) pid, &status, 0) < 0)
        if (errno != EINTR)
            throw std::runtime_error("waitpid failed");

    RunResult result;
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = readText(captureDir / "stdout.txt");
    result.err = readText(captureDir / "stderr.txt");
    return result;
}

RunResult runRenderer(const std::vector<std::string>& args, const fs::path& captureDir, const std::vector<std::string>& environment)
{
    return waitForRenderer(startRenderer(args, captureDir, environment), captureDir);
}

std::vector<std::string> entries(const fs::path& directory)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(directory))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

WavData readWav(const fs::path& file)
{
    WavData data;
    juce::WavAudioFormat wav;
    auto stream = std::make_unique<juce::FileInputStream>(juce::File(fs::absolute(file).string()));
    if (! stream->openedOk())
        return data;

    std::unique_ptr<juce::AudioFormatReader> reader(wav.createReaderFor(stream.release(), true));
    if (reader == nullptr)
        return data;

    data.opened = true;
    data.sampleRate = reader->sampleRate;
    data.channels = (int) reader->numChannels;
    data.bitsPerSample = (int) reader->bitsPerSample;
    data.floatingPoint = reader->usesFloatingPointData;
    data.length = (long long) reader->lengthInSamples;

    juce::AudioBuffer<float> buffer((int) reader->numChannels, (int) reader->lengthInSamples);
    reader->read(&buffer, 0, (int) reader->lengthInSamples, 0, true, true);
    for (int c = 0; c < buffer.getNumChannels(); ++c)
        data.channelSamples.emplace_back(buffer.getReadPointer(c), buffer.getReadPointer(c) + buffer.getNumSamples());
    if (! data.channelSamples.empty())
        data.samples = data.channelSamples.front();
    return data;
}

PngData readPng(const fs::path& file)
{
    PngData data;
    const auto bytes = readText(file);
    data.pngSignature = bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0;
    const auto image = juce::ImageFileFormat::loadFrom(juce::File(fs::absolute(file).string()));
    if (! image.isValid())
        return data;
    data.loaded = true;
    data.width = image.getWidth();
    data.height = image.getHeight();
    return data;
}

juce::Image loadImage(const fs::path& file) { return juce::ImageFileFormat::loadFrom(juce::File(fs::absolute(file).string())); }

int distinctColours(const fs::path& file, int x, int y, int width, int height, int limit)
{
    const auto image = loadImage(file);
    if (! image.isValid())
        return 0;
    std::set<juce::uint32> colours;
    const auto area = juce::Rectangle<int>(x, y, width, height).getIntersection(image.getBounds());
    for (int py = area.getY(); py < area.getBottom(); ++py)
        for (int px = area.getX(); px < area.getRight(); ++px)
        {
            colours.insert(image.getPixelAt(px, py).getARGB());
            if ((int) colours.size() >= limit)
                return limit;
        }
    return (int) colours.size();
}

float peakOf(const std::vector<float>& signal)
{
    float peak = 0.0f;
    for (const float x : signal)
        peak = std::max(peak, std::abs(x));
    return peak;
}

double rmsDifference(const std::vector<float>& a, const std::vector<float>& b)
{
    const auto n = std::min(a.size(), b.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double d = (double) a[i] - (double) b[i];
        sum += d * d;
    }
    return n > 0 ? std::sqrt(sum / (double) n) : 0.0;
}

std::string readText(const fs::path& file)
{
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::string> csvFields(const std::string& line)
{
    std::vector<std::string> fields(1);
    for (const char c : line)
        if (c == ',')
            fields.emplace_back();
        else
            fields.back() += c;
    return fields;
}

EnergyColumns energyColumns(const std::string& header)
{
    EnergyColumns c;
    c.names = csvFields(header);
    INFO("energy CSV header: " << header);
    const std::size_t n = c.names.size();
    REQUIRE(n >= 5);
    REQUIRE(c.names.front() == "time_s");
    REQUIRE(c.names[n - 4] == "total_J");
    REQUIRE(c.names[n - 3] == "dissipated_J");
    REQUIRE(c.names[n - 2] == "injected_J");
    REQUIRE(c.names[n - 1] == "balance_J");
    for (std::size_t i = 1; i + 4 < n; ++i)
        c.terms.push_back(i);
    c.total = n - 4;
    c.dissipated = n - 3;
    c.injected = n - 2;
    c.balance = n - 1;
    return c;
}

juce::var parseJson(const std::string& text)
{
    juce::var result;
    if (juce::JSON::parse(juce::String(text), result).failed())
        return {};
    return result;
}

std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> result;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        result.push_back(line);
    return result;
}

void requirePicture(const fs::path& file, int width, int height)
{
    INFO("picture " << file.string());
    const auto png = readPng(file);
    CHECK(png.pngSignature);
    REQUIRE(png.loaded);
    CHECK(png.width == width);
    CHECK(png.height == height);
    CHECK(distinctColours(file, 0, 0, png.width, png.height) > 1);
}

EngineRun playInProcess(const snaresim::DrumConfig& config, const std::vector<std::pair<long long, int>>& strikes, long long numSamples)
{
    EngineRun run;
    snaresim::Drum drum(config);
    const long long lag = std::lround(drum.latencySamples());
    std::size_t next = 0;
    double sumSquares = 0.0;
    for (long long n = 0; n < numSamples + lag; ++n)
    {
        while (next < strikes.size() && strikes[next].first <= n)
            drum.strikeAtDefaultPoint(snaresim::strikeSpeedFromVelocity(strikes[next++].second, config.strikeSpeedMax_m_per_s));
        const float x = (float) drum.step();
        if (n < lag)
            continue;
        run.mix.push_back(x);
        run.peak = std::max(run.peak, (double) std::abs(x));
        sumSquares += (double) x * (double) x;
    }
    run.rms = numSamples > 0 ? std::sqrt(sumSquares / (double) numSamples) : 0.0;
    run.stats = drum.solverStats();
    return run;
}

void requireRejected(const TempDir& dir, const std::vector<std::string>& args, const std::string& mentions)
{
    std::string command;
    for (const auto& a : args)
        command += " " + a;
    INFO("snaresim-render" << command);

    const auto before = entries(dir.out());
    const auto run = runRenderer(args, dir.root() / "capture");
    INFO("stderr: " << run.err);
    CHECK(run.exitCode == 2);
    CHECK(run.err.rfind("snaresim-render: error: ", 0) == 0);
    CHECK(lines(run.err).size() == 1);
    CHECK((! run.err.empty() && run.err.back() == '\n'));
    CHECK(run.err.find(mentions) != std::string::npos);
    CHECK(run.out.empty());
    CHECK(entries(dir.out()) == before);
}

} // namespace rendertest
