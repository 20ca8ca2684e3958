// Fuzzer: any bytes as the Standard MIDI file of --midi. Reading must give strikes (sorted,
// velocities 1..127, times within the longest render) or a UserError.

#include "Errors.h"
#include "MidiStrikes.h"
#include "RenderJob.h"

#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    try
    {
        const auto strikes = snaresim::render::readMidiStrikes(data, size, "'fuzz.mid'");
        double previous = 0.0;
        for (const auto& s : strikes)
        {
            if (s.velocity < 1 || s.velocity > 127 || ! (s.time_s >= previous) || s.time_s > snaresim::render::kMaxSeconds)
                std::abort();
            previous = s.time_s;
        }
    }
    catch (const snaresim::render::UserError&)
    {}
    return 0;
}
