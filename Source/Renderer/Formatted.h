#pragma once
// printf-style formatting into a std::string: the renderer's reports, plots and messages.

#include <cstdio>
#include <string>

namespace snaresim::render
{

template <class... Values>
std::string formatted(const char* format, Values... values)
{
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, format, values...);
    return buffer;
}

} // namespace snaresim::render
