// Fuzzer: any bytes as a saved state. The processor must not crash, must keep every parameter
// in range, save a state that loads again, and play finite audio afterwards.

#include "PluginProcessor.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace
{
SnareSimAudioProcessor& processor()
{
    static auto* proc = [] {
        juce::initialiseJuce_GUI(); // for the life of the process: nothing is shut down at exit
        auto* p = new SnareSimAudioProcessor();
        p->setRateAndBufferSizeDetails(48000.0, 64);
        p->prepareToPlay(48000.0, 64);
        return p;
    }();
    return *proc;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    auto& proc = processor();
    proc.setStateInformation(data, (int) size);

    const auto values = proc.currentParameters();
    for (const auto& spec : snaresim::parameterSpecs())
    {
        const double v = values.get(spec.id);
        if (! std::isfinite(v) || v < spec.minValue || v > spec.maxValue)
            std::abort();
    }

    // The saved state loads again to the same values, as the host holds them (what plays may
    // differ: a Quality the keep-up check found too slow here plays a lower bandwidth).
    const auto held = proc.parameterValues();
    juce::MemoryBlock saved;
    proc.getStateInformation(saved);
    proc.setStateInformation(saved.getData(), (int) saved.getSize());
    const auto reloaded = proc.parameterValues();
    for (const auto& spec : snaresim::parameterSpecs())
        if (reloaded.get(spec.id) != held.get(spec.id))
            std::abort();

    juce::AudioBuffer<float> buffer(2, 64);
    juce::MidiBuffer midi;
    midi.addEvent(juce::MidiMessage::noteOn(10, 38, (juce::uint8) 127), 0);
    buffer.clear();
    proc.processBlock(buffer, midi);
    for (int i = 0; i < 64; ++i)
        if (! std::isfinite(buffer.getSample(0, i)))
            std::abort();
    return 0;
}
