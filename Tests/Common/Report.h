#pragma once
// What a test measured, for a reader: printed only where the environment sets
// SNARESIM_TEST_REPORT (`SNARESIM_TEST_REPORT=1 ctest --test-dir build -R NAME -V`); otherwise
// the tests assert and stay quiet.

#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace snaresim::test
{

inline bool reporting()
{
    static const bool on = std::getenv("SNARESIM_TEST_REPORT") != nullptr;
    return on;
}

// std::cout while reporting, else a stream that drops what it is given.
inline std::ostream& report()
{
    static std::ostream dropped(nullptr);
    return reporting() ? std::cout : dropped;
}

// std::printf while reporting, else nothing.
template <class... Args>
void reportf(const char* format, Args... args)
{
    if (reporting())
        std::printf(format, args...);
}

// stdout while reporting, else nullptr (for helpers that print where they are told).
inline std::FILE* reportFile() { return reporting() ? stdout : nullptr; }

} // namespace snaresim::test
