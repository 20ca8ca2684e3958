#pragma once
// Where a drum's steps spend their time (Drum::setProfiling): the seconds of each phase of
// step(), read from std::chrono::steady_clock between the phases and summed over the steps
// since the last reset, and the number of steps. Fixed size, no allocation.
//
// The phases are named from the physics. The cavity path and the air box path run different
// lists of them (phasesOf); a phase a path does not run stays at 0.

#include <array>
#include <span>
#include <string_view>

namespace snaresim
{

enum class StepPhase
{
    batterFree,    // the batter's free update (eq. 22 without the contact force); cavity path: and its sums, taken after the mallets' solve
    carryFree,     // the carry head's (eq. 23 without the snares' forces)
    wiresFree,     // the wires' free update (eq. 28 without the collision's forces)
    malletsFree,   // the mallets' free update (eq. 43), and the rising ones taken back
    malletContact, // cavity: the mallet contact solve (eq. 44-45)
    snareContact,  // cavity: the snare contact solve (eq. 48-50)
    cavity,        // cavity: the air coupling step, dV^{n+1}
    airBegin,      // air box: the air's own update (eq. 25) begun on the caller (the layers at the heads)
    batterJoint,   // air box: the batter's joint solve with its air and the mallets
    carryJoint,    // air box: the carry head's with its air and the snares
    airJoin,       // air box: the rest of the air's update, joined
    energy,        // the energy ledger (only while tracked)
    signals,       // the microphones and the mix (air box: the air microphones, dV)
    advance,       // every time level moves on
    count
};

enum class StepPath
{
    cavity, // the reduced cavity (or no air): Drum::stepCouplings
    airBox  // AirModel::airbox: Drum::stepCouplingsInAir
};

struct StepProfile
{
    static constexpr int numPhases = (int) StepPhase::count;

    std::array<double, numPhases> seconds {}; // per phase, summed over the steps
    long long steps = 0;
    StepPath path = StepPath::cavity;

    double operator[](StepPhase phase) const { return seconds[(size_t) phase]; }

    // The sum over every phase: the steps' time, less the two clock reads around each step.
    double total() const
    {
        double sum = 0.0;
        for (const double s : seconds)
            sum += s;
        return sum;
    }

    void clear()
    {
        seconds = {};
        steps = 0;
    }

    // The phases a path runs, grouped by part (step() runs the mallets' and the snares' phases
    // after their own head's; each phase sums its laps wherever they fall).
    static std::span<const StepPhase> phasesOf(StepPath path)
    {
        using enum StepPhase;
        static constexpr StepPhase cavityPhases[] = { batterFree,   carryFree, wiresFree, malletsFree, malletContact,
                                                      snareContact, cavity,    energy,    signals,     advance };
        static constexpr StepPhase airPhases[] = { airBegin,   batterFree, carryFree, wiresFree, malletsFree, batterJoint,
                                                   carryJoint, airJoin,    energy,    signals,   advance };
        if (path == StepPath::airBox)
            return airPhases;
        return cavityPhases;
    }

    // "batter_free", ...: the JSON key.
    static std::string_view name(StepPhase phase)
    {
        static constexpr std::string_view names[] = { "batter_free",   "carry_free", "wires_free", "mallets_free", "mallet_contact",
                                                      "snare_contact", "cavity",     "air_begin",  "batter_joint", "carry_joint",
                                                      "air_join",      "energy",     "signals",    "advance" };
        static_assert(std::size(names) == (size_t) numPhases);
        return names[(size_t) phase];
    }

    static std::string_view name(StepPath path) { return path == StepPath::airBox ? "airbox" : "cavity"; }
};

} // namespace snaresim
