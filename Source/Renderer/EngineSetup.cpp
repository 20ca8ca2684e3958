#include "EngineSetup.h"

#include "Errors.h"
#include "Presets.h"

#include <stdexcept>
#include <string>

namespace snaresim::render
{

ParameterSet makeParameters(const RenderJob& job)
{
    ParameterSet params;

    if (job.preset && ! applyPreset(*job.preset, params))
    {
        std::string names;
        for (const auto& preset : factoryPresets())
            names += (names.empty() ? "" : ", ") + std::string(preset.name);
        throw UserError("--preset: unknown preset '" + *job.preset + "' (available: " + names + ")");
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

DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params)
{
    try
    {
        DrumConfig config = makeDrumConfig(params, job.sampleRate_Hz);
        return job.lossless ? config.lossless() : config;
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
        throw UserError("the model cannot be simulated at " + numberText(config.sampleRate_Hz)
                        + " Hz with these parameters: " + e.what());
    }
}

} // namespace snaresim::render
