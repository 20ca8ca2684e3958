#include "ModelExchange.h"

#include "DrumConfig.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <new>
#include <stdexcept>

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

std::unique_ptr<Drum> buildDrum(const ParameterSet& params, double sampleRate, const BuildOptions& options)
{
    auto drum = std::make_unique<Drum>(makeDrumConfig(params, sampleRate, options));
    drum->setEnergyTracking(options.trackEnergy);
    return drum;
}

std::unique_ptr<DrumModel> buildModel(const ParameterSet& params, double sampleRate, const BuildOptions& options, OnBuildFailure onFailure)
{
    auto model = std::make_unique<DrumModel>();
    model->requested = GridKey::of(params, sampleRate);

    if (! (sampleRate > 0.0) || ! std::isfinite(sampleRate))
    {
        if (onFailure == OnBuildFailure::raise)
            throw std::invalid_argument("the sample rate must be positive and finite");
        return model;
    }

    auto padded = [&](std::unique_ptr<DrumModel> m) {
        if (options.constantLatency && m->drum != nullptr)
            m->pad.resize(latencyPadFor(*m->drum));
        return m;
    };

    try
    {
        model->drum = buildDrum(params, sampleRate, options);
        model->built = params;
        return padded(std::move(model));
    }
    catch (const std::bad_alloc&)
    {
        throw;
    }
    catch (const std::exception&)
    {
        if (onFailure == OnBuildFailure::raise)
            throw;
        // The parameters cannot be simulated here: the defaults are tried next.
    }

    model->fellBack = true;

    try
    {
        const ParameterSet defaults;
        model->drum = buildDrum(defaults, sampleRate, options);
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

    return padded(std::move(model));
}

//==============================================================================
ModelBuilder::ModelBuilder(ParameterReader reader, BuildOptions options) : readParameters(std::move(reader)), buildOptions(options) {}

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
    retired.deleteAll(); // as the background thread does (which an offline client may have stopped)
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
        model = buildModel(params, targetRate, buildOptions);
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
