// snaresim-render: renders strikes of the SnareSim drum model to a WAV file.
// This file only wires the pieces together; see CommandLine.cpp (helpText) for the options.
//
// Exit codes: 0 success; 2 bad input or unusable file (one line on stderr starting with
// "snaresim-render: error: ", no output left behind); 1 unexpected internal failure;
// 128 + N when interrupted by signal N (SIGINT, SIGTERM, SIGHUP; no output left behind).
// --bench also exits with 1 when the output went non-finite (after its report), never on time.

#include "AtomicFile.h"
#include "Benchmark.h"
#include "CommandLine.h"
#include "Distance.h"
#include "EnergyCsvWriter.h"
#include "EnergyPlot.h"
#include "EngineSetup.h"
#include "Errors.h"
#include "Interrupt.h"
#include "Match.h"
#include "Microphones.h"
#include "MidiStrikes.h"
#include "Plotting.h"
#include "ProgressLine.h"
#include "RenderPlan.h"
#include "Renderer.h"
#include "Report.h"
#include "SnarePlot.h"
#include "Spectrogram.h"
#include "WavWriter.h"

#include "Parameters.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace snaresim::render
{
namespace
{

namespace fs = std::filesystem;

// Absolute, without "." / ".." and with the symbolic links of its existing part resolved.
fs::path resolved(const fs::path& path)
{
    std::error_code ec;
    const auto absolute = fs::absolute(path).lexically_normal();
    auto canonical = fs::weakly_canonical(absolute, ec);
    return ec ? absolute : canonical;
}

bool sameFile(const fs::path& a, const fs::path& b) { return resolved(a) == resolved(b); }

// Every output with its option, for the "same file" checks.
std::vector<std::pair<std::string, fs::path>> outputsOf(const RenderJob& job)
{
    std::vector<std::pair<std::string, fs::path>> outputs;
    if (job.output)
        outputs.emplace_back("-o", *job.output);
    if (job.energyCsv)
        outputs.emplace_back("--energy-csv", *job.energyCsv);
    if (job.energyPlot)
        outputs.emplace_back("--energy-plot", *job.energyPlot);
    if (job.spectrogram)
        outputs.emplace_back("--spectrogram", *job.spectrogram);
    if (job.snarePlot)
        outputs.emplace_back("--snare-plot", *job.snarePlot);
    return outputs;
}

void checkDistinctFiles(const RenderJob& job)
{
    const auto outputs = outputsOf(job);
    for (std::size_t i = 0; i < outputs.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (sameFile(outputs[i].second, outputs[j].second))
                throw UserError(outputs[i].first + " and " + outputs[j].first + " name the same file");
    if (job.midiFile)
        for (const auto& [option, path] : outputs)
            if (sameFile(*job.midiFile, path))
                throw UserError("an output file would overwrite the MIDI file (" + option + ")");
}

std::optional<fs::path> absolutePath(const std::optional<fs::path>& path)
{
    return path ? std::optional(fs::absolute(*path).lexically_normal()) : std::nullopt;
}

// Commits every file in order; when one fails, the ones already committed are removed.
void commitAll(const std::vector<AtomicFile*>& files)
{
    for (std::size_t i = 0; i < files.size(); ++i)
    {
        try
        {
            files[i]->commit();
        }
        catch (...)
        {
            for (std::size_t j = 0; j < i; ++j)
                files[j]->discardCommitted();
            throw;
        }
    }
}

int render(const RenderJob& commandLineJob)
{
    installInterruptHandlers(); // before any temporary file exists
    checkDistinctFiles(commandLineJob);

    // Inputs first: parameters, strikes, model (all cheap to reject).
    const auto params = makeParameters(commandLineJob);
    const auto midiStrikes = commandLineJob.midiFile ? readMidiStrikes(*commandLineJob.midiFile) : std::vector<Strike> {};
    const auto plan = makeRenderPlan(commandLineJob, midiStrikes);
    const bool trackEnergy = commandLineJob.lossless || commandLineJob.energyCsv || commandLineJob.energyPlot;
    const auto options = makeBuildOptions(commandLineJob, params, trackEnergy);
    const auto config = makeConfig(commandLineJob, params, options);
    checkChanges(commandLineJob, plan, params, options);
    DrumSession session(DrumSession::Mode::render, options);
    startSession(session, params, plan.sampleRate_Hz, kRenderBlockSize);
    const Drum* drum = session.drumPlayer().drum();
    std::optional<DistanceReport> distance;
    if (! commandLineJob.references.empty())
        distance = DistanceReport { loadReferences(commandLineJob.references), {} };

    // With the air box the WAV holds its air microphones unless --mic says otherwise.
    RenderJob job = commandLineJob;
    if (! job.mic && config.cavity.model == AirModel::airbox)
        job.mic = MicOutput::air;
    if (job.mic == MicOutput::air && drum->numAirMics() == 0)
        throw UserError("--mic air: the air microphones are the air box's (--model airbox)");
    const auto mic = job.selectedMic();
    const auto mics = micChannels(mic, drum->numAirMics());

    // Then the outputs, before any rendering: a bad path fails here.
    AtomicFile wavFile(*job.output);
    WavWriter wav(wavFile, plan.sampleRate_Hz, (int) mics.size());

    std::optional<AtomicFile> csvFile;
    std::unique_ptr<EnergyCsvWriter> csv;
    if (job.energyCsv)
    {
        csvFile.emplace(*job.energyCsv);
        csv = std::make_unique<EnergyCsvWriter>(*csvFile, plan.sampleRate_Hz, drum->energy());
    }

    std::optional<AtomicFile> energyPlotFile;
    std::unique_ptr<EnergyPlot> energyPlot;
    if (job.energyPlot)
    {
        energyPlotFile.emplace(*job.energyPlot);
        energyPlot =
            std::make_unique<EnergyPlot>(plan.numSamples, plan.sampleRate_Hz,
                                         plan.strikes.empty() ? std::nullopt : std::optional(plan.strikes.front().sample), drum->energy());
    }

    std::optional<AtomicFile> spectrogramFile;
    std::unique_ptr<Spectrogram> spectrogram;
    const int analysed = analysedChannel(mic);
    if (job.spectrogram)
    {
        spectrogramFile.emplace(*job.spectrogram);
        spectrogram = std::make_unique<Spectrogram>(plan.numSamples, plan.sampleRate_Hz,
                                                    std::string(micName(mic == MicOutput::all ? MicOutput::mix : mic)));
    }

    std::optional<AtomicFile> snarePlotFile;
    std::unique_ptr<SnarePlot> snarePlot;
    if (job.snarePlot)
    {
        snarePlotFile.emplace(*job.snarePlot);
        snarePlot = std::make_unique<SnarePlot>(*drum, plan.numSamples, plan.sampleRate_Hz,
                                                plan.strikes.empty() ? std::nullopt : std::optional(plan.strikes.front().sample));
        snarePlot->add(0, *drum); // the state before the first step (time 0), when in the window
    }

    RenderSinks sinks;
    std::vector<const float*> channelPointers(mics.size());
    ProgressLine progress(! job.json, plan.numSamples, plan.sampleRate_Hz);
    sinks.audio = [&](std::span<const std::span<const float>> channels) {
        throwIfInterrupted(); // once per block
        for (std::size_t c = 0; c < channels.size(); ++c)
            channelPointers[c] = channels[c].data();
        wav.write(channelPointers.data(), (int) channels.front().size());
        progress.update(wav.samplesWritten());
        if (spectrogram)
            spectrogram->add(channels[(std::size_t) analysed]);
    };
    if (csv || energyPlot)
        sinks.energy = [&](std::int64_t first, std::span<const EnergyLedger> rows) {
            if (csv)
                csv->write(first, rows);
            if (energyPlot)
                energyPlot->add(first, rows);
        };

    if (snarePlot)
    {
        // The step of sample n gives the state at time n + 1.
        sinks.state = [&](std::int64_t sample, const Drum& state) { snarePlot->add(sample + 1, state); };
        sinks.stateFrom = std::max<std::int64_t>(snarePlot->firstTime() - 1, 0);
        sinks.stateTo = snarePlot->lastTime();
    }

    const auto stats = renderDrum(session, plan, mics, sinks);

    progress.finish();
    wav.finish();
    if (distance) // the WAV as --distance reads it, before anything is committed
    {
        distance->strikes.push_back(
            measureDistances(wavFile.temporary(), "the rendered strike " + job.output->string(), distance->references));
        distance->strikes.back().file = *absolutePath(job.output);
    }
    if (csv)
        csv->finish();
    if (energyPlot)
    {
        throwIfInterrupted();
        plot::writePng(energyPlot->draw(), *energyPlotFile);
    }
    if (spectrogram)
    {
        throwIfInterrupted();
        plot::writePng(spectrogram->draw(), *spectrogramFile);
    }
    if (snarePlot)
    {
        throwIfInterrupted();
        plot::writePng(snarePlot->draw(), *snarePlotFile);
    }
    throwIfInterrupted();

    std::vector<AtomicFile*> files { &wavFile };
    for (auto* file : { &csvFile, &energyPlotFile, &spectrogramFile, &snarePlotFile })
        if (*file)
            files.push_back(&**file);
    commitAll(files);

    const RenderReport report { job,
                                plan,
                                stats,
                                absolutePath(job.output),
                                absolutePath(job.energyCsv),
                                absolutePath(job.energyPlot),
                                absolutePath(job.spectrogram),
                                absolutePath(job.snarePlot),
                                distance ? &*distance : nullptr };
    std::cout << (job.json ? formatJson(report) : formatSummary(report)) << std::flush;
    return 0;
}

// --bench (Benchmark.h): the render timed block by block as the plug-in runs it. Fails (exit
// 1, after the report) when the output went non-finite; never on time.
int benchmark(const RenderJob& commandLineJob)
{
    installInterruptHandlers();
    checkDistinctFiles(commandLineJob);

    const auto job = benchmarkJob(commandLineJob);
    const auto params = makeParameters(job);
    const auto midiStrikes = job.midiFile ? readMidiStrikes(*job.midiFile) : std::vector<Strike> {};
    const auto plan = makeRenderPlan(job, midiStrikes);
    const auto options = makeBuildOptions(job, params, false); // no --lossless with --bench
    const auto config = makeConfig(job, params, options);      // a config the engine refuses fails here, before any output
    checkChanges(job, plan, params, options);
    {
        DrumSession probe(DrumSession::Mode::render, options);
        startSession(probe, params, plan.sampleRate_Hz, job.selectedBlockSize());
    }

    std::optional<AtomicFile> wavFile;
    std::unique_ptr<WavWriter> wav;
    if (job.output)
    {
        wavFile.emplace(*job.output);
        wav = std::make_unique<WavWriter>(*wavFile, plan.sampleRate_Hz, 1);
    }

    const auto stats =
        benchmarkDrum(params, options, config, plan, job.selectedBlockSize(), job.selectedRepeats(), [&](std::span<const float> block) {
            throwIfInterrupted(); // once per block, outside the timed section
            if (wav)
            {
                const float* channel = block.data();
                wav->write(&channel, (int) block.size());
            }
        });

    if (wav)
    {
        wav->finish();
        throwIfInterrupted();
        wavFile->commit();
    }

    // The command line's job: the scenario is named from it (job holds its strikes as --hit).
    const RenderReport report { commandLineJob, plan, stats, absolutePath(job.output), {}, {}, {}, {}, nullptr };
    std::cout << (job.json ? formatJson(report) : formatSummary(report)) << std::flush;

    if (stats.nonfiniteSamples > 0)
    {
        std::cerr << "snaresim-render: benchmark failed: the output has " << stats.nonfiniteSamples << " non-finite sample(s)" << std::endl;
        return 1;
    }
    return 0;
}

int run(const std::vector<std::string>& args)
{
    const auto commandLine = parseCommandLine(args);

    switch (commandLine.action)
    {
        case CommandLine::Action::help: std::cout << helpText() << std::flush; return 0;
        case CommandLine::Action::listParameters: std::cout << describeParameters() << std::flush; return 0;
        case CommandLine::Action::render: break;
    }
    if (! commandLine.job.distanceFiles.empty())
        return runDistance(commandLine.job);
    if (commandLine.job.match)
        return runMatch(commandLine.job);
    return commandLine.job.bench ? benchmark(commandLine.job) : render(commandLine.job);
}

// Messages are printed as exactly one line.
std::string oneLine(std::string message)
{
    std::replace(message.begin(), message.end(), '\n', ' ');
    std::replace(message.begin(), message.end(), '\r', ' ');
    while (! message.empty() && message.back() == ' ')
        message.pop_back();
    return message;
}

} // namespace
} // namespace snaresim::render

int main(int argc, char* argv[])
{
    using namespace snaresim::render;

    try
    {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    }
    catch (const Interrupted& e)
    {
        std::cerr << "snaresim-render: " << e.what() << "; no output written" << std::endl;
        return 128 + e.signalNumber();
    }
    catch (const UserError& e)
    {
        std::cerr << "snaresim-render: error: " << oneLine(e.what()) << std::endl;
        return 2;
    }
    catch (const std::exception& e)
    {
        std::cerr << "snaresim-render: internal error: " << oneLine(e.what()) << std::endl;
        return 1;
    }
    catch (...)
    {
        std::cerr << "snaresim-render: internal error: unknown exception" << std::endl;
        return 1;
    }
}
