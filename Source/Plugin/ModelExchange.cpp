#include "ModelExchange.h"

#include "DrumConfig.h"

#include <cmath>
#include <exception>
#include <new>

namespace snaresim::plugin
{

GridKey GridKey::of (const ParameterSet& params, double sampleRate) noexcept
{
    GridKey key;
    key.sampleRate = sampleRate;

    for (const auto& s : parameterSpecs())
        if (s.needsNewGrid)
            key.values[static_cast<std::size_t> (s.id)] = params.get (s.id);

    return key;
}

std::unique_ptr<DrumModel> buildModel (const ParameterSet& params, double sampleRate)
{
    auto model = std::make_unique<DrumModel>();
    model->requested = GridKey::of (params, sampleRate);

    if (! (sampleRate > 0.0) || ! std::isfinite (sampleRate))
        return model;

    try
    {
        model->drum = std::make_unique<Drum> (makeDrumConfig (params, sampleRate));
        model->built = params;
        return model;
    }
    catch (const std::bad_alloc&)
    {
        throw;
    }
    catch (const std::exception& e)
    {
        juce::ignoreUnused (e);
        DBG ("SnareSim: cannot build the drum from the parameters (" << e.what() << "); using the defaults");
    }

    model->fellBack = true;

    try
    {
        const ParameterSet defaults;
        model->drum = std::make_unique<Drum> (makeDrumConfig (defaults, sampleRate));
        model->built = defaults;
    }
    catch (const std::bad_alloc&)
    {
        throw;
    }
    catch (const std::exception& e)
    {
        // Nothing can be simulated at this rate: the processor outputs silence.
        juce::ignoreUnused (e);
        DBG ("SnareSim: cannot build the default drum at " << sampleRate << " Hz: " << e.what());
        model->drum.reset();
    }

    return model;
}

//==============================================================================
ModelBuilder::ModelBuilder (ParameterReader reader)
    : juce::Thread ("SnareSim model builder"), readParameters (std::move (reader))
{
}

ModelBuilder::~ModelBuilder()
{
    stop();
}

void ModelBuilder::start()
{
    if (! isThreadRunning())
        startThread (juce::Thread::Priority::low);
}

void ModelBuilder::stop()
{
    // A build in flight cannot be interrupted; give it ample time before JUCE gives up on it.
    stopThread (30000);
}

void ModelBuilder::setTargetLocked (double sampleRate, const GridKey& current)
{
    targetRate = sampleRate;
    lastKey = current;
}

void ModelBuilder::buildNowIfNeeded()
{
    const juce::ScopedLock sl (lock);
    buildIfNeededLocked();
}

void ModelBuilder::buildIfNeededLocked()
{
    if (! (targetRate > 0.0))
        return;

    const auto params = readParameters();
    const auto key = GridKey::of (params, targetRate);

    if (key == lastKey)
        return;

    std::unique_ptr<DrumModel> model;

    try
    {
        model = buildModel (params, targetRate);
    }
    catch (const std::exception&)
    {
        // Out of memory: keep the running model and try again at the next change.
    }

    // A model the audio thread has not taken yet is superseded: delete it.
    if (model != nullptr)
        delete pending.exchange (model.release());

    lastKey = key;
}

void ModelBuilder::run()
{
    while (! threadShouldExit())
    {
        retired.deleteAll();

        {
            const juce::ScopedLock sl (lock);

            if (! threadShouldExit())
                buildIfNeededLocked();
        }

        wait (pollIntervalMs);
    }

    retired.deleteAll();
}

} // namespace snaresim::plugin
