#include "Microphones.h"

#include <array>
#include <utility>

namespace snaresim::render
{
namespace
{

constexpr std::array<std::pair<MicOutput, std::string_view>, 6> kNames { {
    { MicOutput::top, "top" },
    { MicOutput::bottom, "bottom" },
    { MicOutput::far, "far" },
    { MicOutput::mix, "mix" },
    { MicOutput::all, "all" },
    { MicOutput::air, "air" },
} };

} // namespace

std::string_view micName(MicOutput mic)
{
    for (const auto& [value, name] : kNames)
        if (value == mic)
            return name;
    return "mix";
}

std::optional<MicOutput> findMic(std::string_view name)
{
    for (const auto& [value, text] : kNames)
        if (text == name)
            return value;
    return std::nullopt;
}

std::string_view micChoices() { return "top|bottom|far|mix|all|air"; }

std::vector<Channel> micChannels(MicOutput mic, int numAirMics)
{
    switch (mic)
    {
        case MicOutput::top: return { { Mic::top } };
        case MicOutput::bottom: return { { Mic::bottom } };
        case MicOutput::far: return { { Mic::room } };
        case MicOutput::mix: return { { Mic::mix } };
        case MicOutput::all: return { { Mic::top }, { Mic::bottom }, { Mic::room }, { Mic::mix } };
        case MicOutput::air:
        {
            std::vector<Channel> channels;
            for (int i = 0; i < numAirMics; ++i)
                channels.push_back({ Mic::mix, i });
            return channels;
        }
    }
    return { { Mic::mix } };
}

int analysedChannel(MicOutput mic) { return mic == MicOutput::all ? 3 : 0; }

} // namespace snaresim::render
