// Catch2 runner for the processor tests: JUCE's message manager must exist while processors
// (and their AudioProcessorValueTreeState) are alive.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <juce_events/juce_events.h>

int main (int argc, char* argv[])
{
    const juce::ScopedJuceInitialiser_GUI juceInitialiser;
    return Catch::Session().run (argc, argv);
}
