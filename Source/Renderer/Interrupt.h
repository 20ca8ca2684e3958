#pragma once
// Ctrl-C (SIGINT), SIGTERM and SIGHUP during a render: the handler only records the signal;
// the render loop checks it once per block and throws Interrupted, so that the temporary
// output files are removed on the way out. Main then exits with 128 + the signal number.

#include <stdexcept>

namespace snaresim::render
{

class Interrupted : public std::runtime_error
{
public:
    explicit Interrupted(int signalNumber);
    int signalNumber() const { return signal; }

private:
    int signal;
};

void installInterruptHandlers();

// Throws Interrupted when a signal has arrived since installInterruptHandlers().
void throwIfInterrupted();

} // namespace snaresim::render
