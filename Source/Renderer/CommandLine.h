#pragma once
// Parsing snaresim-render's command line into a RenderJob. Throws UserError (one readable
// sentence) for an unknown option, a missing or malformed value, an unknown parameter ID,
// or an out-of-bounds sample rate / length / strike. Parameter ranges and preset names are
// checked later, against the engine (EngineSetup.h).

#include "RenderJob.h"

#include <string>
#include <vector>

namespace snaresim::render
{

struct CommandLine
{
    enum class Action
    {
        render,
        help,
        listParameters
    };

    Action action = Action::render;
    RenderJob job;
};

// args: the arguments without the program name.
CommandLine parseCommandLine(const std::vector<std::string>& args);

// The --help text (several lines, ends with a newline).
std::string helpText();

} // namespace snaresim::render
