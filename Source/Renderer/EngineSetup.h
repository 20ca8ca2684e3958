#pragma once
// From a RenderJob to a started DrumSession: parameters (defaults, then the preset, then
// --model, then each --set), the build options (the air box's, --lossless), the physical
// configuration checked (also at every --set-at), and the session's drum. Every rejection by
// the engine (unknown preset, out-of-range value, impossible grid or sample rate) becomes a
// UserError.

#include "RenderJob.h"

#include "RenderPlan.h"

#include "BuildOptions.h"
#include "DrumConfig.h"
#include "DrumSession.h"
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

// The air box's options (--air-mic, --walls, --box, --box-margin, --threads; refused without
// the air box), --lossless, and the energy ledger when tracked.
BuildOptions makeBuildOptions(const RenderJob& job, const ParameterSet& params, bool trackEnergy);

// makeDrumConfig(params, job.sampleRate_Hz, options), checked.
DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params, const BuildOptions& options);

// Every state the plan's --set-at changes lead to, checked as makeConfig checks the first.
void checkChanges(const RenderJob& job, const RenderPlan& plan, ParameterSet params, const BuildOptions& options);

// The session set to `params` and started at the job's rate (blocks of blockSize).
void startSession(DrumSession& session, const ParameterSet& params, double sampleRate_Hz, int blockSize);

} // namespace snaresim::render
