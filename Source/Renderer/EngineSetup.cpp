#include "EngineSetup.h"

#include "Errors.h"
#include "PresetFile.h"
#include "Presets.h"

#include <cctype>
#include <filesystem>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

namespace snaresim::render
{

bool isPresetFile(std::string_view text)
{
    const auto ext = kPresetFileExtension;
    if (text.size() >= ext.size() && std::equal(ext.begin(), ext.end(), text.end() - (std::ptrdiff_t) ext.size(), [](char a, char b) {
            return std::tolower((unsigned char) a) == std::tolower((unsigned char) b);
        }))
        return true;
    return text.find('/') != std::string_view::npos; // no factory preset's name holds one
}

ParameterSet presetFileParameters(const std::filesystem::path& path)
{
    try
    {
        return parametersOf(snaresim::readPresetFile(path));
    }
    catch (const PresetFileError& e)
    {
        throw UserError("--preset " + path.string() + ": " + e.what());
    }
}

ParameterSet makeParameters(const RenderJob& job)
{
    ParameterSet params;

    if (job.preset && isPresetFile(*job.preset))
        params = presetFileParameters(*job.preset);
    else if (job.preset && ! applyPreset(*job.preset, params))
    {
        std::string names;
        for (const auto& preset : factoryPresets())
            names += (names.empty() ? "" : ", ") + std::string(preset.name);
        throw UserError("--preset: unknown preset '" + *job.preset + "' (available: " + names + "; or a preset file: a path ending in " +
                        std::string(kPresetFileExtension) + ")");
    }

    // --model after the preset, before --set (a later --set air_model=... wins).
    if (job.airModel)
    {
        try
        {
            params.set(ParamId::airModel, (double) *job.airModel);
        }
        catch (const std::out_of_range& e)
        {
            throw UserError(std::string("--model: ") + e.what());
        }
    }

    for (const auto& item : job.overrides)
    {
        try
        {
            params.set(item.id, item.value);
        }
        catch (const std::out_of_range& e)
        {
            throw UserError("--set " + item.text + ": " + e.what());
        }
    }
    return params;
}

BuildOptions makeBuildOptions(const RenderJob& job, const ParameterSet& params, bool trackEnergy)
{
    BuildOptions options;
    options.lossless = job.lossless;
    options.trackEnergy = trackEnergy;

    const DrumConfig config = mapParameters(params, job.sampleRate_Hz);
    const bool airBox = config.cavity.model == AirModel::airbox;
    for (const auto& [given, option] : { std::pair { ! job.airMics.empty(), "--air-mic" },
                                         { job.walls.has_value(), "--walls" },
                                         { job.boxSize.has_value(), "--box" },
                                         { job.boxMargin.has_value(), "--box-margin" },
                                         { job.threads.has_value(), "--threads" } })
        if (given && ! airBox)
            throw UserError(std::string(option) + " applies to the air box only (--model airbox)");
    if (! airBox)
        return options;
    if (job.boxSize && job.boxMargin)
        throw UserError("--box and --box-margin: give one or the other");

    if ((int) job.airMics.size() > DrumAirSpec::maxMics)
        throw UserError("--air-mic: at most " + std::to_string(DrumAirSpec::maxMics) + " air microphones");
    const double R = config.batter.radius_m, H = config.cavity.shellDepth_m;
    for (const auto& p : job.airMics)
    {
        if (std::hypot(p.x, p.y) <= R && std::abs(p.z) <= 0.5 * H)
            throw UserError("--air-mic " + numberText(p.x) + "," + numberText(p.y) + "," + numberText(p.z) +
                            ": inside the drum's shell (radius " + numberText(R) + " m, heads at z = +-" + numberText(0.5 * H) +
                            " m); a microphone goes in the air around the drum");
        options.airMics[(std::size_t) options.numAirMics++] = { p.x, p.y, p.z };
    }
    if (job.walls)
        options.walls = *job.walls == Walls::reflecting ? AirWalls::reflecting : AirWalls::absorbing;
    if (job.boxSize)
        options.boxSize_m = std::array<double, 3> { job.boxSize->x, job.boxSize->y, job.boxSize->z };
    options.boxMargin_m = job.boxMargin;
    options.threads = job.threads.value_or((int) std::clamp(std::thread::hardware_concurrency(), 1u, 64u)); // the air box takes 1..64
    return options;
}

DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params, const BuildOptions& options)
{
    try
    {
        return makeDrumConfig(params, job.sampleRate_Hz, options);
    }
    catch (const std::invalid_argument& e)
    {
        throw UserError(std::string("the model cannot be configured: ") + e.what());
    }
    catch (const std::out_of_range& e)
    {
        throw UserError(std::string("the model cannot be configured: ") + e.what());
    }
}

void checkChanges(const RenderJob& job, const RenderPlan& plan, ParameterSet params, const BuildOptions& options)
{
    for (const auto& change : plan.changes)
    {
        try
        {
            params.set(change.id, change.value);
        }
        catch (const std::out_of_range& e)
        {
            throw UserError("--set-at " + change.text + ": " + e.what());
        }
        try
        {
            (void) makeConfig(job, params, options);
        }
        catch (const UserError& e)
        {
            throw UserError("--set-at " + change.text + ": " + e.what());
        }
    }
}

void startSession(DrumSession& session, const ParameterSet& params, double sampleRate_Hz, int blockSize)
{
    session.setParameters(params);
    try
    {
        session.prepareAndStart(sampleRate_Hz, blockSize);
    }
    catch (const std::invalid_argument& e)
    {
        throw UserError("the model cannot be simulated at " + numberText(sampleRate_Hz) + " Hz with these parameters: " + e.what());
    }
}

} // namespace snaresim::render
