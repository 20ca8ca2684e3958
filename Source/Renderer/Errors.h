#pragma once
// The renderer's error for bad input and unusable files: Main prints its message as one
// line "snaresim-render: error: ..." and exits with code 2. Anything else that escapes is
// an internal failure (exit code 1).

#include <charconv>
#include <stdexcept>
#include <string>
#include <string_view>

namespace snaresim::render
{

class UserError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

// 'text', for messages. (Built by appending: GCC 12 gives a false -Wrestrict warning for
// "'" + std::string + "'".)
inline std::string inQuotes(std::string_view text)
{
    std::string result(1, '\'');
    result.append(text);
    result += '\'';
    return result;
}

// Shortest text that reads back as the same double (for messages).
inline std::string numberText(double value)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

} // namespace snaresim::render
