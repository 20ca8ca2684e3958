// Fuzzer: any bytes as a host's MIDI for one block. The first two bytes give the block size
// (1..8192); the rest is a sequence of events: a sample position (two bytes), a length (one
// byte, up to 255) and that many raw bytes, added as the host's MIDI buffer would hold them
// (so any status byte, truncated messages, running-status data bytes and SysEx). The output
// must stay finite.

#include "PluginProcessor.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <utility>

namespace
{
SnareSimAudioProcessor& processor()
{
    static auto* proc = [] {
        juce::initialiseJuce_GUI(); // for the life of the process: nothing is shut down at exit
        auto* p = new SnareSimAudioProcessor();
        // A coarse, cheap drum: the fuzzer is after the event handling, not the physics.
        auto& state = p->getValueTreeState();
        for (const auto& [id, value] : { std::pair { "bandwidth", 3750.0f }, std::pair { "snare_count", 4.0f } })
            if (auto* param = state.getParameter(id))
                param->setValueNotifyingHost(param->convertTo0to1(value));
        p->setRateAndBufferSizeDetails(48000.0, 512);
        p->prepareToPlay(48000.0, 512);
        return p;
    }();
    return *proc;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    if (size < 2)
        return 0;

    auto& proc = processor();
    const int blockSize = 1 + (int) ((data[0] | (data[1] << 8)) % 8192);
    data += 2;
    size -= 2;

    juce::MidiBuffer midi;
    while (size >= 3)
    {
        const int position = (int) ((data[0] | (data[1] << 8)) % (unsigned) (blockSize + 16));
        const std::size_t length = std::min<std::size_t>(data[2], size - 3);
        if (length > 0)
            midi.addEvent(data + 3, (int) length, position);
        data += 3 + length;
        size -= 3 + length;
    }

    juce::AudioBuffer<float> buffer(2, blockSize);
    buffer.clear();
    proc.processBlock(buffer, midi);

    for (int ch = 0; ch < 2; ++ch)
        for (int i = 0; i < blockSize; ++i)
            if (! std::isfinite(buffer.getSample(ch, i)))
                std::abort();
    return 0;
}
