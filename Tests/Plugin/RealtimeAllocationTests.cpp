// processBlock never allocates: this test binary replaces the global operator new / delete and
// counts the allocations made on a thread while a thread_local flag is on, which the test sets
// around each processBlock call only (other threads, and the test's own work between blocks,
// are not counted).

#include <catch2/catch.hpp>

#include "Drum.h"
#include "ProcessorTestHelpers.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <new>
#include <thread>

#include "CountingAllocator.h"

using snaresim::test::CountAllocations;
using snaresim::test::countedAllocations;

using namespace snaresim::testing;
using snaresim::ParamId;

TEST_CASE("the allocation counter sees allocations on the counted thread only", "[processor][realtime]")
{
    const long before = countedAllocations.load();
    {
        CountAllocations counting;
        auto* p = new int(3);
        delete p;
    }
    CHECK(countedAllocations.load() == before + 1);

    auto* q = new int(4); // not counted
    delete q;
    CHECK(countedAllocations.load() == before + 1);
}

TEST_CASE("processBlock never allocates", "[processor][realtime]")
{
    SnareSimAudioProcessor proc;
    fastSettings(proc);
    const int announced = 256;
    prepare(proc, 48000.0, announced);

    // Everything the test needs is allocated before counting starts.
    juce::AudioBuffer<float> storage(2, 4096);
    juce::MidiBuffer midi;
    midi.ensureSize(4096);
    const int swapsAtStart = proc.getModelSwapCount();
    long blocks = 0;
    countedAllocations = 0;

    auto processOne = [&](int numSamples, std::initializer_list<std::pair<int, juce::MidiMessage>> events) {
        juce::AudioBuffer<float> buffer(storage.getArrayOfWritePointers(), 2, numSamples);
        midi.clear();
        for (const auto& [at, message] : events)
            midi.addEvent(message, at);
        {
            CountAllocations counting;
            proc.processBlock(buffer, midi);
        }
        ++blocks;
    };

    // Notes, rolls, snares off / on, all-sound-off, parameters moving every block, block sizes
    // from 1 to far above the announced size.
    for (int i = 0; i < 200; ++i)
    {
        set(proc, ParamId::damping, (double) (i % 100));
        set(proc, ParamId::batterTension, 2000.0 + 10.0 * i);
        set(proc, ParamId::strikePosition, (i % 9) / 10.0);
        set(proc, ParamId::outputGain, -(double) (i % 24));
        if (i % 50 == 25)
            set(proc, ParamId::airModel, (double) ((i / 50) % 2));
        if (i % 40 == 10)
            set(proc, ParamId::snaresEngaged, (double) ((i / 40) % 2));

        const int n = i % 10 == 0 ? 4096 : i % 10 == 1 ? 1 : i % 3 == 0 ? 1000 : announced;
        switch (i % 8)
        {
            case 0: processOne(n, { { 0, note(110) } }); break;
            case 1: processOne(n, { { 0, note(60, 40) } }); break;
            case 2: processOne(n, { { n / 2, note(90, 33) }, { n - 1, note(90, 38) } }); break; // snares off
            case 3: processOne(n, { { 0, note(90, 34) } }); break;                              // snares on
            case 4:
                processOne(n, { { 0, note(127) }, { n / 3, note(100) }, { n / 2, note(80) }, { n / 2, note(70) }, { n - 1, note(60) } });
                break; // a roll
            case 5: processOne(n, { { 0, juce::MidiMessage::noteOff(10, 38) }, { 0, juce::MidiMessage::allNotesOff(10) } }); break;
            case 6:
                processOne(n,
                           i % 48 == 6
                               ? std::initializer_list<std::pair<int, juce::MidiMessage>> { { n / 2, juce::MidiMessage::allSoundOff(10) } }
                               : std::initializer_list<std::pair<int, juce::MidiMessage>> {});
                break;
            default: processOne(n, {}); break;
        }
    }
    CHECK(countedAllocations.load() == 0);

    // A model swap: the new model is built in the background and installed, crossfaded and the
    // old one sent back, all without allocating on the audio thread.
    // (The air model's changes above swapped models too.)
    set(proc, ParamId::snareCount, 7.0);
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (proc.getDrum()->config().snares.count != 7 && std::chrono::steady_clock::now() < until)
    {
        processOne(announced, { { 0, note(100) } });
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    REQUIRE(proc.getModelSwapCount() > swapsAtStart);
    for (int i = 0; i < 20; ++i)
        processOne(announced, { { 0, note(100) } });
    CHECK(proc.getDrum()->config().snares.count == 7);

    INFO("blocks processed: " << blocks);
    CHECK(countedAllocations.load() == 0);
}
