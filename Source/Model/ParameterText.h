#pragma once
// How a parameter's value is written and read as text, derived once from its schema entry
// (Parameters.h): the host's parameter text, the editor's value boxes and tooltips and the
// renderer's --set all use it.
//   "3050 N/m", "30.0 N", "25 %", "140 mm" (for m), "28.0 g" (for kg), "1.0e8 N/m^α",
//   "On" / "Off" for toggles, the choice's name for choices.

#include "Parameters.h"

#include <optional>
#include <string>
#include <string_view>

namespace snaresim
{

struct ValueFormat
{
    double scale = 1.0;     // written number = value * scale
    std::string unit;       // written unit, UTF-8 (mm for m, g for kg, m² for m^2)
    std::string schemaUnit; // the schema's unit, UTF-8
    int decimals = 0;
    bool scientific = false; // mantissa with `decimals` decimals, "e", exponent
};

ValueFormat valueFormat(const ParameterSpec& spec);

// The value as text, in the written unit (no unit for toggles and choices).
std::string formatValue(const ParameterSpec& spec, double value);

// What a bare number (no unit) means when text is read.
enum class BareNumber
{
    writtenUnit, // as formatValue writes it ("140" is 140 mm): editors and hosts
    schemaUnit   // in the schema's SI unit ("0.14" is 0.14 m): the command line
};

// Reads a value: a number, optionally followed by the written or the schema's unit
// ("140 mm", "0.14 m"); for toggles also on/off (any case), for choices also a name.
// Empty when the text is none of these. The value is not clamped.
std::optional<double> parseValue(const ParameterSpec& spec, std::string_view text, BareNumber bare);

// A key of an older schema (the migrations of Parameters.h, as "grid_coarseness") with its value
// as a bare number: today's ID and value (clamped into its range), as a saved state of that
// schema migrates. Empty when the key is not an old one; throws std::invalid_argument when it
// is but the text is not a number. Preset files and the renderer's --set read old keys with it.
std::optional<std::pair<ParamId, double>> readOldKey(std::string_view key, std::string_view text);

// Toggles and choices: how many names there are, and each one ("off", "on"; "none", "cavity").
int numChoiceNames(const ParameterSpec& spec);
std::string_view choiceName(const ParameterSpec& spec, int index);
// The index of a name (exact match); empty when none has it.
std::optional<int> choiceIndex(const ParameterSpec& spec, std::string_view name);

// "N/m^alpha" -> "N/m^α", "m^2/s" -> "m²/s" (UTF-8).
std::string prettyUnit(std::string_view unit);

} // namespace snaresim
