#include "Interrupt.h"

#include <csignal>
#include <string>

namespace snaresim::render
{
namespace
{

volatile std::sig_atomic_t pendingSignal = 0;

extern "C" void recordSignal(int signalNumber) { pendingSignal = signalNumber; }

} // namespace

Interrupted::Interrupted(int signalNumber)
    : std::runtime_error("interrupted by signal " + std::to_string(signalNumber)), signal(signalNumber)
{}

void installInterruptHandlers()
{
    for (const int signalNumber : { SIGINT, SIGTERM, SIGHUP })
        std::signal(signalNumber, recordSignal);
}

void throwIfInterrupted()
{
    if (const int signalNumber = pendingSignal; signalNumber != 0)
        throw Interrupted(signalNumber);
}

} // namespace snaresim::render
