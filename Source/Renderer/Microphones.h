#pragma once
// --mic: the names on the command line and in the JSON report, and the engine signals
// (snaresim::Mic) that become the WAV's channels.

#include "RenderJob.h"

#include "Drum.h"

#include <optional>
#include <string_view>
#include <vector>

namespace snaresim::render
{

// An air microphone's output per pascal (times the output level): a fortissimo strike gives
// about 100 Pa 4 cm above the batter, about -6 dBFS.
inline constexpr double kAirMicGain_per_Pa = 0.005;

// One channel of the WAV: an engine signal (Drum::output; Mic::mix is the player's output) or,
// when air >= 0, the pressure at that air microphone of the air box.
struct Channel
{
    Mic mic = Mic::mix;
    int air = -1;
    bool operator==(const Channel&) const = default;
};

// "top", "bottom", "far", "mix", "all", "air".
std::string_view micName(MicOutput mic);

// The output named so; empty for any other name.
std::optional<MicOutput> findMic(std::string_view name);

// "top|bottom|far|mix|all|air", for messages and --help.
std::string_view micChoices();

// The WAV's channels in order: one signal, with `all` top, bottom, far, mix, with `air` each of
// the drum's numAirMics air microphones.
std::vector<Channel> micChannels(MicOutput mic, int numAirMics);

// The channel (index into micChannels) the spectrogram shows: the mix with `all`, else the
// first (with `air`, the first air microphone).
int analysedChannel(MicOutput mic);

} // namespace snaresim::render
