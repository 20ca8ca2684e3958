#pragma once
// Streaming the energy ledger as CSV into an AtomicFile's temporary file, one row per
// sample (time_s = sample index / sample rate; numbers in shortest round-trip form): time_s,
// one column per ledger term in its order (EnergyLedger::columnName), total_J = their sum,
// dissipated_J, injected_J and balance_J = total_J + dissipated_J - injected_J. For the default
// drum (other air models add or drop the air's terms):
//   time_s,batter_J,carry_J,mallets_J,snares_J,cavity_J,outside_J,total_J,dissipated_J,injected_J,balance_J

#include "AtomicFile.h"

#include "EnergyLedger.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace juce
{
class FileOutputStream;
} // namespace juce

namespace snaresim::render
{

class EnergyCsvWriter
{
public:
    // The header line (no newline) for ledgers with the terms of `layout`.
    static std::string header(const EnergyLedger& layout);

    // Opens file.temporary() and writes the header line for ledgers with the terms of `layout`
    // (the drum's energy()). Throws UserError.
    EnergyCsvWriter(const AtomicFile& file, double sampleRate_Hz, const EnergyLedger& layout);
    ~EnergyCsvWriter();

    EnergyCsvWriter(const EnergyCsvWriter&) = delete;
    EnergyCsvWriter& operator=(const EnergyCsvWriter&) = delete;

    // rows[i] is the ledger after sample firstSample + i (with the terms of `layout`). Throws UserError.
    void write(std::int64_t firstSample, std::span<const EnergyLedger> rows);

    // Flushes and closes. Throws UserError.
    void finish();

private:
    void put(const std::string& text);
    [[noreturn]] void writeFailed() const;

    const AtomicFile& file;
    double sampleRate;
    std::unique_ptr<juce::FileOutputStream> stream;
    std::string line;
};

} // namespace snaresim::render
