#pragma once
// From a RenderJob to a ready snaresim::Drum: parameters (defaults, then the preset, then
// --model, then each --set), the physical configuration, and the model. Every rejection by
// the engine (unknown preset, out-of-range value, impossible grid or sample rate) becomes a
// UserError.

#include "RenderJob.h"

#include "Drum.h"
#include "DrumConfig.h"
#include "Parameters.h"

#include <memory>

namespace snaresim::render
{

ParameterSet makeParameters(const RenderJob& job);

// makeDrumConfig(params, job.sampleRate_Hz), made lossless for --lossless.
DrumConfig makeConfig(const RenderJob& job, const ParameterSet& params);

std::unique_ptr<Drum> makeDrum(const DrumConfig& config);

} // namespace snaresim::render
