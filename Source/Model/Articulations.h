#pragma once
// What each MIDI note does: the default note map shared by the plugin and the renderer.
// It follows the General MIDI drum map where it fits (37 side stick, 38 and 40 snares);
// notes outside the map strike at the main strike point, so any pad or keyboard plays.

#include <span>
#include <string_view>

namespace snaresim
{

enum class ArticulationAction
{
    strike,    // a mallet strike at a point
    snaresOff, // throw the snares off the carry head
    snaresOn   // put them back
};

struct Articulation
{
    int note; // MIDI note number
    std::string_view name;
    ArticulationAction action;
    double radius_frac; // strike point: distance from the centre / R; < 0 means the strike_position control
    double angle_rad;   // and its angle from the snares' direction
    double speedScale;  // multiplies the velocity curve's speed
};

std::span<const Articulation> articulations();

// The articulation of a note: its entry in the map, or the main strike for any other note.
const Articulation& articulationForNote(int midiNote);

// The main strike: the strike_position control's radius, off the snares' axis (a stick never
// lands on the drum's mirror line; there the drum's antisymmetric modes would stay silent).
const Articulation& mainStrike();

} // namespace snaresim
