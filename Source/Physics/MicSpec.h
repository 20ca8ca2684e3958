#pragma once
// The microphones (PressureMicrophones.h).
// "From the schema": the model's mapping of the parameters fills the field in (DrumConfig.h).

#include "AirPoint.h"

namespace snaresim
{

// Microphones: the sound pressure at three points outside the drum (PressureMicrophones.h),
// metres from the drum's centre (z up, the batter at +H/2); from the schema.
struct MicSpec
{
    AirPoint top { 0.0, 0.0, 0.11 };                     // above the batter
    AirPoint bottom { 0.0, 0.0, -0.11 };                 // below the carry head, under the snares
    AirPoint room { 0.0, 0.0, 1.07 };                    // the room
    double reach_m = 2.5;                                // no microphone farther from the centre (the delay lines' length)
    double cellSize_m = 0.02;                            // side of the heads' radiating cells
    double fineCellSize_m = 0.008;                       // and of those near a close microphone (PressureMicrophones.cpp)
    double topGain = 5.7e-3;                             // output per Pa
    double bottomGain = 3.7e-3;                          // output per Pa
    double roomGain = 0.041;                             // output per Pa (the room)
    double mixTop = 0.0, mixBottom = 0.0, mixRoom = 0.0; // weights of the mixed output (from the schema)
};

} // namespace snaresim
