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

namespace
{
// The air box's options (--air-mic, --walls, --box, --box-margin, --threads) into the config.
void applyAirOptions(const RenderJob& job, DrumConfig& config)
{
    const bool airBox = config.cavity.model == AirModel::airbox;
    for (const auto& [given, option] : { std::pair { ! job.airMics.empty(), "--air-mic" },
                                         { job.walls.has_value(), "--walls" },
                                         { job.boxSize.has_value(), "--box" },
                                         { job.boxMargin.has_value(), "--box-margin" },
                                         { job.threads.has_value(), "--threads" } })
        if (given && ! airBox)
            throw UserError(std::string(option) + " applies to the air box only (--model airbox)");
    if (! airBox)
        return;
    if (job.boxSize && job.boxMargin)
        throw UserError("--box and --box-margin: give one or the other");

    auto& air = config.airBox;
    if ((int) job.airMics.size() > DrumAirSpec::maxMics)
        throw UserError("--air-mic: at most " + std::to_string(DrumAirSpec::maxMics) + " air microphones");
    const double R = config.batter.radius_m, H = config.cavity.shellDepth_m;
    for (const auto& p : job.airMics)
    {
        if (std::hypot(p.x, p.y) <= R && std::abs(p.z) <= 0.5 * H)
            throw UserError("--air-mic " + numberText(p.x) + "," + numberText(p.y) + "," + numberText(p.z) +
                            ": inside the drum's shell (radius " + numberText(R) + " m, heads at z = +-" + numberText(0.5 * H) +
                            " m); a microphone goes in the air around the drum");
        air.mics[(std::size_t) air.numMics++] = { p.x, p.y, p.z };
    }
    if (job.walls)
        air.walls = *job.walls == Walls::reflecting ? AirWalls::reflecting : AirWalls::absorbing;
    if (job.boxSize)
        air.size_m = { job.boxSize->x, job.boxSize->y, job.boxSize->z };
    if (job.boxMargin)
    {
        air.size_m = { 0.0, 0.0, 0.0 }; // sized from the drum and the margin
        air.margin_m = *job.boxMargin;
    }
    air.threads = job.threads.value_or((int) std::max(1u, std::thread::hardware_concurrency()));
}
} // namespace

DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params)
{
    try
    {
        DrumConfig config = mapParameters(params, job.sampleRate_Hz);
        applyAirOptions(job, config);
        if (job.lossless)
            config = config.lossless(); // with the air box: reflecting walls, sigma_a = 0
        config.validate();
        return config;
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

std::unique_ptr<Drum> makeDrum(const DrumConfig& config)
{
    try
    {
        return std::make_unique<Drum>(config);
    }
    catch (const std::invalid_argument& e)
    {
        throw UserError("the model cannot be simulated at " + numberText(config.sampleRate_Hz) + " Hz with these parameters: " + e.what());
    }
}

} // namespace snaresim::render
