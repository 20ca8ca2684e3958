#pragma once
// From a RenderJob to a ready snaresim::Drum: parameters (defaults, then the preset, then
// --model, then each --set), the physical configuration, and the model. Every rejection by
// the engine (unknown preset, out-of-range value, impossible grid or sample rate) becomes a
// UserError.

#include "RenderJob.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "Parameters.h"

#include <filesystem>
#include <memory>
#include <string_view>

namespace snaresim::render
{

ParameterSet makeParameters(const RenderJob& job);

// --preset TEXT names a preset file (PresetFile.h) rather than a factory preset: it ends in
// .snarepreset, or it holds a '/' (a path).
bool isPresetFile(std::string_view text);
// The defaults with a preset file's values; a UserError naming the file (and the line) when it
// cannot be read or is not a valid preset file.
ParameterSet presetFileParameters(const std::filesystem::path& path);

// makeDrumConfig(params, job.sampleRate_Hz), made lossless for --lossless.
DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params);

std::unique_ptr<Drum> makeDrum(const DrumConfig& config);

} // namespace snaresim::render
