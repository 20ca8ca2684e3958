#include "EnergyCsvWriter.h"

#include "Errors.h"

#include <juce_core/juce_core.h>

#include <charconv>
#include <filesystem>

namespace snaresim::render
{
namespace
{

void appendNumber(std::string& line, double value)
{
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    line.append(buffer, result.ptr);
}

} // namespace

std::string EnergyCsvWriter::header(const EnergyLedger& layout)
{
    std::string text = "time_s";
    for (const auto& term : layout.terms())
        (text += ',') += EnergyLedger::columnName(term.name);
    for (const char* column : { "total", "dissipated", "injected", "balance" })
        (text += ',') += EnergyLedger::columnName(column);
    return text;
}

EnergyCsvWriter::EnergyCsvWriter(const AtomicFile& target, double sampleRate_Hz, const EnergyLedger& layout)
    : file(target), sampleRate(sampleRate_Hz)
{
    const juce::File path(juce::String(std::filesystem::absolute(file.temporary()).string()));
    stream = std::make_unique<juce::FileOutputStream>(path, 1 << 16);
    if (! stream->openedOk())
        writeFailed();
    stream->setPosition(0);
    stream->truncate();

    put(header(layout) + "\n");
}

EnergyCsvWriter::~EnergyCsvWriter() = default;

void EnergyCsvWriter::writeFailed() const
{
    const auto reason = stream != nullptr && stream->getStatus().failed() ? stream->getStatus().getErrorMessage().toStdString()
                                                                          : std::string("write error");
    throw UserError("cannot write " + file.displayName() + ": " + reason);
}

void EnergyCsvWriter::put(const std::string& text)
{
    if (! stream->write(text.data(), text.size()))
        writeFailed();
}

void EnergyCsvWriter::write(std::int64_t firstSample, std::span<const EnergyLedger> rows)
{
    line.clear();
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const auto& e = rows[i];
        appendNumber(line, (double) (firstSample + (std::int64_t) i) / sampleRate);
        for (const auto& term : e.terms())
        {
            line += ',';
            appendNumber(line, term.value_J);
        }
        for (const double value : { e.total(), e.dissipated_J, e.injected_J, e.balance() })
        {
            line += ',';
            appendNumber(line, value);
        }
        line += '\n';
    }
    put(line);
}

void EnergyCsvWriter::finish()
{
    stream->flush();
    if (stream->getStatus().failed())
        writeFailed();
    stream.reset();
}

} // namespace snaresim::render
