// Catch2 runner for the processor tests: JUCE's message manager must exist while processors
// (and their AudioProcessorValueTreeState) are alive.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include "PluginProcessor.h"

#include <juce_events/juce_events.h>

int main(int argc, char* argv[])
{
    const juce::ScopedJuceInitialiser_GUI juceInitialiser;
    // Quality's real-time fallback sees a machine that keeps up with every drum, so that what
    // the tests render does not depend on how fast this one is; the fallback's own tests give
    // their processors slower machines.
    SnareSimAudioProcessor::setDefaultQualityMeasurement([](snaresim::DrumSession&, int blockSize, const std::function<bool()>&) {
        snaresim::KeepUpFigures f;
        f.audioSeconds = 0.1;
        f.blockSize = blockSize;
        return f;
    });
    return Catch::Session().run(argc, argv);
}
