// Fuzzer: any bytes as snaresim-render's arguments, split at NUL bytes. Parsing must either
// give a job or reject it with a UserError (exit 2 in the program); so must the engine's
// checks of its values (parameters, presets). Anything else escaping is a finding.

#include "CommandLine.h"
#include "EngineSetup.h"
#include "Errors.h"

#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    std::vector<std::string> args;
    std::string current;
    for (std::size_t i = 0; i < size; ++i)
    {
        if (data[i] == 0)
        {
            args.push_back(current);
            current.clear();
        }
        else
            current.push_back((char) data[i]);
    }
    if (! current.empty())
        args.push_back(current);

    try
    {
        const auto command = snaresim::render::parseCommandLine(args);
        if (command.action == snaresim::render::CommandLine::Action::render)
            (void) snaresim::render::makeParameters(command.job);
    }
    catch (const snaresim::render::UserError&)
    {
        // A clear rejection: what bad input must get.
    }
    return 0;
}
