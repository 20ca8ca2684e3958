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

// "top", "bottom", "far", "mix", "all".
std::string_view micName(MicOutput mic);

// The output named so; empty for any other name.
std::optional<MicOutput> findMic(std::string_view name);

// "top|bottom|far|mix|all", for messages and --help.
std::string_view micChoices();

// The WAV's channels in order: one signal, or with `all` top, bottom, far, mix.
std::vector<Mic> micChannels(MicOutput mic);

// The channel (index into micChannels) the spectrogram shows: the only one, or the mix.
int analysedChannel(MicOutput mic);

} // namespace snaresim::render
