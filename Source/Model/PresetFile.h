#pragma once
// Preset files (".snarepreset"): the factory presets (Resources/Presets) and the user's, read by
// the renderer's --preset FILE and the plug-in's "Load preset file". UTF-8 text, one entry a line:
//
//   # SnareSim preset              (a '#' starts a comment; blank lines are skipped)
//   name = Tight Funk              (required, once)
//   batter_tension = 4800 N/m      (a parameter key = its value, as --set reads it: a number in
//   snare_tension = 55             the schema's unit, optionally followed by that unit or the
//   snare_solver = quadratised     written one ("140 mm"); a toggle on/off; a choice's name)
//
// A parameter not listed keeps its default. Each key at most once.

#include "Parameters.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace snaresim
{

inline constexpr std::string_view kPresetFileExtension = ".snarepreset";

struct PresetFile
{
    std::string name;
    std::vector<std::pair<ParamId, double>> values; // in the file's order, each in range
};

// What is wrong with a preset file, with its line number ("line 3: ...").
struct PresetFileError : std::invalid_argument
{
    using std::invalid_argument::invalid_argument;
};

// Reads a preset file's text. Throws PresetFileError for a line that is not KEY = VALUE, an
// unknown key, a key given twice, a value that cannot be read or is outside the parameter's
// range, no name, or text that is not a preset file at all (binary, over 64 KiB).
PresetFile parsePresetFile(std::string_view text);

// Reads a preset file from disk, then as parsePresetFile. Throws PresetFileError for a path that
// is not a regular file ("no such preset file"), one over 64 KiB or one that cannot be read.
PresetFile readPresetFile(const std::filesystem::path& path);

// The defaults with the file's values set.
ParameterSet parametersOf(const PresetFile& preset);

// A preset file's text for these values: every parameter that differs from its default, in the
// schema's order, numbers in the schema's unit with the digits that read back exactly.
// The name must be one line (newlines become spaces).
std::string formatPresetFile(std::string_view name, const ParameterSet& params);

} // namespace snaresim
