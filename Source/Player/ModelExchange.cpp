#include "ModelExchange.h"

#include "DrumConfig.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <new>

namespace snaresim
{

GridKey GridKey::of(const ParameterSet& params, double sampleRate) noexcept
{
    GridKey key;
    key.sampleRate = sampleRate;

    for (const auto& s : parameterSpecs())
        if (s.rebuildsModel())
            key.values[static_cast<std::size_t>(s.id)] = params.get(s.id);

    return key;
}

std::unique_ptr<DrumModel> buildModel(const ParameterSet& params, double sampleRate)
{
    auto model = std::make_unique<DrumModel>();
    model->requested = GridKey::of(params, sampleRate);

    if (! (sampleRate > 0.0) || ! std::isfinite(sampleRate))
        return model;

    try
    {
        model->drum = std::make_unique<Drum>(makeDrumConfig(params, sampleRate));
        model->built = params;
        return model;
    }
    catch (const std::bad_alloc&)
    {
        throw;
    }
    catch (const std::exception&)
    {
        // The parameters cannot be simulated here: the defaults are tried next.
    }

    model->fellBack = true;

    try
    {
        const ParameterSet defaults;
        model->drum = std::make_unique<Drum>(makeDrumConfig(defaults, sampleRate));
        model->built = defaults;
    }
    catch (const std::bad_alloc&)
    {
        throw;
    }
    catch (const std::exception&)
    {
        // Nothing can be simulated at this rate: the player outputs silence.
        model->drum.reset();
    }

    return model;
}

//==============================================================================
ModelBuilder::ModelBuilder(ParameterReader reader) : readParameters(std::move(reader)) {}

ModelBuilder::~ModelBuilder() { stop(); }

void ModelBuilder::start()
{
    if (thread.joinable())
        return;

    {
        const std::lock_guard<std::mutex> g(wakeLock);
        exitRequested = false;
    }
    thread = std::thread([this] { run(); });
}

void ModelBuilder::stop()
{
    if (! thread.joinable())
        return;

    {
        const std::lock_guard<std::mutex> g(wakeLock);
        exitRequested = true;
    }
    wake.notify_all();
    thread.join(); // a build in flight finishes first
}

void ModelBuilder::setTargetLocked(double sampleRate, const GridKey& current)
{
    targetRate = sampleRate;
    lastKey = current;
}

void ModelBuilder::buildNowIfNeeded()
{
    const std::lock_guard<std::mutex> g(lock);
    buildIfNeededLocked();
}

void ModelBuilder::buildIfNeededLocked()
{
    if (! (targetRate > 0.0))
        return;

    const auto params = readParameters();
    const auto key = GridKey::of(params, targetRate);

    if (key == lastKey)
        return;

    std::unique_ptr<DrumModel> model;

    try
    {
        model = buildModel(params, targetRate);
    }
    catch (const std::exception&)
    {
        // Out of memory: keep the running model and try again at the next change.
    }

    // A model the audio thread has not taken yet is superseded: delete it.
    if (model != nullptr)
        delete pending.exchange(model.release());

    lastKey = key;
}

void ModelBuilder::run()
{
    for (;;)
    {
        retired.deleteAll();

        {
            const std::lock_guard<std::mutex> g(lock);
            buildIfNeededLocked();
        }

        std::unique_lock<std::mutex> w(wakeLock);
        if (wake.wait_for(w, std::chrono::milliseconds(pollIntervalMs), [this] { return exitRequested; }))
            break;
    }

    retired.deleteAll();
}

} // namespace snaresim
