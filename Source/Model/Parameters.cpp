#include "Parameters.h"

#include "DrumConfig.h" // qualityBandwidth_Hz: the old Quality's migration

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace snaresim
{

namespace
{
using P = ParamId;
using S = ParamScale;
using N = ChangeNeeds;

constexpr auto C = ParamKind::continuous;
constexpr auto I = ParamKind::integer;
constexpr auto B = ParamKind::toggle;
constexpr auto K = ParamKind::choice;

// Ranges chosen for a 14 x 5.5 inch snare (its defaults: docs/MODEL.md, "Defaults").
// The head and wire grids are designed for the largest tension, high damping and
// shallowest shell allowed here, so moving those controls never needs a new grid.
// clang-format off
constexpr std::array<ParameterSpec, kNumParameters> kSpecs {{
    { P::batterTension, "batter_tension", "Membrane tension", "N/m", 1000.0, 6000.0, 3050.0, S::linear, N::coefficients,
      "Tension of the batter (top) head; 3050 N/m puts its (0,1) mode near 200 Hz", C, "", "main" },
    { P::snareTension, "snare_tension", "Snare tension", "N", 10.0, 100.0, 10.0, S::linear, N::coefficients,
      "Tension of each snare wire", C, "", "main" },
    { P::damping, "damping", "Damping", "%", 0.0, 100.0, 19.0, S::linear, N::coefficients,
      "Muffling of both heads: the lowest modes ring for 4 s at 0 % down to 0.15 s at 100 %", C, "", "main" },
    { P::carryTension, "carry_tension", "Carry tension", "N/m", 800.0, 5000.0, 2060.0, S::linear, N::coefficients,
      "Tension of the carry (snare-side) head; 2060 N/m puts its (0,1) mode near 300 Hz", C, "", "heads" },
    { P::carryFollows, "carry_follows", "Carry follows batter", "", 0.0, 1.0, 0.0, S::linear, N::coefficients,
      "Carry tension follows the membrane tension (keeping the default ratio) instead of its own control", B, "off|on", "heads" },
    { P::highDamping, "high_damping", "High damping", "m^2/s", 0.0, 3.0e-3, 1.15e-3, S::linear, N::coefficients,
      "Frequency-dependent loss sigma1 of both heads: higher dulls the overtones", C, "", "heads" },
    { P::shellDepth, "shell_depth", "Shell depth", "m", 0.05, 0.25, 0.14, S::linear, N::coefficients,
      "Depth of the shell: the enclosed air's volume and so its stiffness", C, "", "heads" },
    { P::airModel, "air_model", "Air model", "", 0.0, 2.0, 1.0, S::linear, N::newModel,
      "The air: none (heads uncoupled), the reduced cavity between the heads, or the air box (the drum in a 3D box of air that radiates; in real time only where this machine keeps up with it, else the cavity plays and bounces use the air box)",
      K, "none|cavity|airbox", "heads" },
    { P::snaresEngaged, "snares_engaged", "Snares on", "", 0.0, 1.0, 1.0, S::linear, N::coefficients,
      "Snares on the carry head (1) or thrown off (0)", B, "off|on", "snares" },
    { P::snareCount, "snare_count", "Snare wires", "", 1.0, 40.0, 20.0, S::linear, N::newGrid,
      "Number of snare wires", I, "", "snares" },
    { P::strikePosition, "strike_position", "Strike position", "r/R", 0.0, 0.9, 0.3, S::linear, N::coefficients,
      "Distance of the main strike point from the centre, as a fraction of the radius", C, "", "mallet" },
    { P::strikeSpeedMax, "strike_speed_max", "Strike speed at velocity 127", "m/s", 1.0, 10.0, 6.0, S::linear, N::coefficients,
      "Mallet speed for MIDI velocity 127; lower velocities follow the documented curve", C, "", "mallet" },
    { P::malletMass, "mallet_mass", "Mallet mass", "kg", 0.005, 0.1, 0.028, S::logarithmic, N::coefficients,
      "Moving mass of the stick or mallet", C, "", "mallet" },
    { P::malletStiffness, "mallet_stiffness", "Mallet hardness", "N/m^alpha", 1.0e6, 1.0e10, 4.0e9, S::logarithmic, N::coefficients,
      "Contact stiffness kappa_M of the power-law contact", C, "", "mallet" },
    { P::malletExponent, "mallet_exponent", "Mallet contact exponent", "", 1.5, 3.0, 1.5, S::linear, N::coefficients,
      "Power-law exponent alpha: 1.5 Hertz (stick), up to 3 (felt)", C, "", "mallet" },
    { P::malletContactRadius, "mallet_contact_radius", "Mallet contact radius", "m", 0.0, 0.02, 0.005, S::linear, N::coefficients,
      "Radius of the contact patch on the head", C, "", "mallet" },
    { P::micTop, "mic_top", "Top mic level", "", 0.0, 1.0, 0.97, S::linear, N::coefficients,
      "Level of the microphone above the batter head in the mix", C, "", "output" },
    { P::micBottom, "mic_bottom", "Bottom mic level", "", 0.0, 1.0, 0.78, S::linear, N::coefficients,
      "Level of the microphone under the snares in the mix", C, "", "output" },
    { P::micRoom, "mic_room", "Room level", "", 0.0, 1.0, 0.29, S::linear, N::coefficients,
      "Level of the room microphone (mic_room_distance from the batter's centre) in the mix", C, "", "output" },
    { P::micTopPosition, "mic_top_position", "Top mic position", "r/R", 0.0, 0.9, 0.5, S::linear, N::coefficients,
      "Distance of the top microphone from the drum's axis, as a fraction of the radius", C, "", "output" },
    { P::outputGain, "output_gain", "Output level", "dB", -48.0, 12.0, 0.0, S::linear, N::coefficients,
      "Output level", C, "", "output" },
    // The default is Quality 2's bandwidth, qualityBandwidth_Hz(2): its grids to the millionth.
    { P::bandwidth, "bandwidth", "Quality (bandwidth)", "Hz", 3750.0, 21100.0, 7839.5127, S::logarithmic, N::newGrid,
      "The highest frequency the heads' and snare wires' grids carry, the same at every rate from 44.1 kHz (lower rates carry less); their cost grows as its square. Lower is cheaper and duller; 21.1 kHz is the finest grid the stability bounds (eq. 39, 40) allow at 48 kHz", C, "", "model" },
    { P::snareSolver, "snare_solver", "Snare collision solver", "", 0.0, 1.0, 0.0, S::linear, N::newModel,
      "Snare/head collisions: quadratised (one linear solve per sample, real time) or Newton (the paper's eq. 50, iterative)",
      K, "quadratised|newton", "model" },
    { P::airLoss, "air_loss", "Air loss (air box)", "m", 0.0, 2.0e-5, 2.0e-6, S::linear, N::newGrid,
      "Viscothermal loss sigma_a of the air box's air (eq. 5): it damps the air grid's highest, most dispersed band; its grid spacing follows eq. (41)",
      C, "", "heads" },
    { P::offlineAirBox, "offline_airbox", "Air box when bouncing", "", 0.0, 1.0, 1.0, S::linear, N::coefficients,
      "When the host renders offline (a bounce), the drum plays in the air box whatever the air model says; off: bounces play the air model. Read by the plug-in only: the renderer plays the air model",
      B, "off|on", "model" },
    { P::headPrecision, "head_precision", "Head arithmetic", "", 0.0, 1.0, 1.0, S::linear, N::newModel,
      "The batter's state and update (eq. 22) in double precision, or in single: the batter a quarter to a third cheaper, the energy identity held to float round-off, the snares' sound the same in the mean (BENCHMARKS.md); the carry head, which the snares strike, and the air box's heads always run in double",
      K, "double|single", "model" },
    { P::outsideAir, "outside_air", "Outside air", "", 0.0, 1.0, 1.0, S::linear, N::newModel,
      "The air around the heads with the cavity: its mass lowers the heads' lowest modes and it carries their sound away (radiation channels calibrated against the air box); the air box has its own",
      B, "off|on", "heads" },
    { P::micTopHeight, "mic_top_height", "Top mic height", "m", 0.01, 0.3, 0.04, S::linear, N::coefficients,
      "Height of the top microphone above the batter head", C, "", "output" },
    { P::micBottomPosition, "mic_bottom_position", "Bottom mic position", "r/R", 0.0, 0.9, 0.35, S::linear, N::coefficients,
      "Distance of the bottom microphone from the drum's axis, as a fraction of the radius", C, "", "output" },
    { P::micBottomHeight, "mic_bottom_height", "Bottom mic distance", "m", 0.01, 0.3, 0.04, S::linear, N::coefficients,
      "Distance of the bottom microphone below the carry head", C, "", "output" },
    { P::micRoomDistance, "mic_room_distance", "Room mic distance", "m", 0.3, 2.0, 1.0, S::linear, N::coefficients,
      "Distance of the room microphone from the batter's centre", C, "", "output" },
    { P::micRoomAngle, "mic_room_angle", "Room mic angle", "deg", 0.0, 90.0, 45.0, S::linear, N::coefficients,
      "Angle of the room microphone from the drum's axis: 0 above the batter, 90 level with it", C, "", "output" },
    { P::keepUp, "keep_up", "Lower Quality when slow", "", 0.0, 1.0, 1.0, S::linear, N::coefficients,
      "In real time, where this machine is measured not to keep up with the drum at the chosen Quality in the host's blocks, a lower bandwidth that keeps up plays and the editor says so; off: the chosen Quality always plays. Read by the plug-in only: bounces and the renderer play the chosen Quality",
      B, "off|on", "model" },
    { P::nearField, "near_field", "Near field", "", 0.0, 1.0, 0.0, S::linear, N::newModel,
      "With the outside air: the air sloshing beside the heads weighs on their higher modes and lowers them 7-11 %, as the air box does; the drum then costs about 1.6 times as much (BENCHMARKS.md), so it is off by default; the air box has its own",
      B, "off|on", "heads" },
    { P::snareDamping, "snare_damping", "Snare contact damping", "s/m", 0.0, 20.0, 0.0, S::linear, N::coefficients,
      "Damping lambda of the snares' collisions with the carry head (Hunt and Crossley): the contact force kappa xi^beta (1 + lambda dxi/dt); 0 is the paper's elastic contact, higher shortens the buzz's high tail",
      C, "", "snares" },
    { P::snareStiffness, "snare_stiffness", "Snare contact stiffness", "N/m^beta", 1.0e6, 1.0e10, 1.0e9, S::logarithmic, N::coefficients,
      "Stiffness kappa_s of the snares' collisions with the carry head (eq. 16), with beta 1.5: the coiled wire's and the head's compliance where they meet; lower is a softer, longer contact with fewer clicks above 10 kHz",
      C, "", "snares" },
    { P::roomTime, "room_time", "Room reverberation time", "s", 0.0, 2.0, 0.0, S::linear, N::coefficients,
      "T60 of the room the drum is recorded in: its diffuse field (Sabine's level, Schroeder's random decay) joins every microphone; 0 is the free field, no room",
      C, "", "output" },
    { P::roomVolume, "room_volume", "Room volume", "m^3", 10.0, 2000.0, 60.0, S::logarithmic, N::coefficients,
      "Volume of the room: with the reverberation time it sets how loud the room's diffuse field is beside the drum's direct sound (the critical distance 0.057 sqrt(V / T60))",
      C, "", "output" },
}};
// clang-format on

constexpr bool tableInOrder()
{
    for (std::size_t i = 0; i < kSpecs.size(); ++i)
        if (static_cast<std::size_t>(kSpecs[i].id) != i)
            return false;
    return true;
}
static_assert(tableInOrder(), "parameter table must be in ParamId order");

// clang-format off
constexpr std::array<ParameterGroup, 6> kGroups {{
    { "main", "Tension & damping" },
    { "heads", "Heads & shell" },
    { "snares", "Snares" },
    { "mallet", "Mallet & playing" },
    { "model", "Model" },
    { "output", "Microphones & output" },
}};
// clang-format on

constexpr bool everyParameterInAGroup()
{
    for (const auto& s : kSpecs)
    {
        bool found = false;
        for (const auto& g : kGroups)
            found = found || g.key == s.group;
        if (! found)
            return false;
    }
    return true;
}
static_assert(everyParameterInAGroup(), "every parameter's group must be in the group table");

constexpr bool toggleAndChoiceNamesComplete()
{
    for (const auto& s : kSpecs)
    {
        if (s.kind != ParamKind::toggle && s.kind != ParamKind::choice)
            continue;
        std::size_t names = 1;
        for (char c : s.choices)
            names += c == '|' ? 1 : 0;
        if (s.choices.empty() || s.minValue != 0.0 || (double) names != s.maxValue + 1.0)
            return false;
    }
    return true;
}
static_assert(toggleAndChoiceNamesComplete(), "toggles and choices name every value from 0");

// Version 0 (no version attribute) and 1: the first table, where the damping was the batter's
// T60 and two keys had other names. Versions 0 to 2: Quality was the grids' coarseness, a
// multiple of their stability bounds at 48 kHz; it is the bandwidth those grids carry.
// clang-format off
constexpr std::array<ParameterMigration, 4> kMigrations {{
    { 2, "batter_decay", P::damping, &dampingFromT60 },
    { 2, "batter_high_damping", P::highDamping, nullptr },
    { 2, "listen_position", P::micTopPosition, nullptr },
    { 3, "grid_coarseness", P::bandwidth, &qualityBandwidth_Hz },
}};
// clang-format on

// Versions 0 to 3: their defaults, where a state does not hold the key (the outside air off, the
// batter in single precision, the losses of then); with the outside air they had its near field,
// which became a parameter of its own in version 4. Version 4: the batter in double, its losses and
// snare tension. The first entry for a key that applies to a state wins.
// clang-format off
constexpr std::array<ImpliedParameter, 9> kImplied {{
    { 4, P::outsideAir, 0.0 },
    { 4, P::nearField, 1.0 },
    { 4, P::headPrecision, 1.0 },
    { 4, P::damping, 75.0 },
    { 4, P::highDamping, 2.1e-4 },
    { 5, P::headPrecision, 0.0 },
    { 5, P::damping, 44.0 },
    { 5, P::highDamping, 4e-4 },
    { 5, P::snareTension, 20.0 },
}};
// clang-format on

constexpr double kLongestT60_s = 4.0, kShortestT60_s = 0.15;
} // namespace

const std::array<ParameterSpec, kNumParameters>& parameterSpecs() { return kSpecs; }

std::span<const ParameterGroup> parameterGroups() { return kGroups; }

std::string_view groupTitle(std::string_view key)
{
    for (const auto& g : kGroups)
        if (g.key == key)
            return g.title;
    return key;
}

std::span<const ParameterMigration> parameterMigrations() { return kMigrations; }

std::span<const ImpliedParameter> impliedParameters() { return kImplied; }

std::optional<std::pair<ParamId, double>> migrateParameter(int stateVersion, std::string_view key, double value)
{
    for (const auto& m : kMigrations)
        if (stateVersion < m.beforeVersion && key == m.oldKey)
            return std::pair { m.id, m.convert != nullptr ? m.convert(value) : value };
    if (const auto id = findParameter(key))
        return std::pair { *id, value };
    return std::nullopt;
}

std::optional<std::pair<ParamId, double>> migrateOldKey(std::string_view key, double value)
{
    if (findParameter(key))
        return std::nullopt;
    return migrateParameter(0, key, value);
}

double dampingT60(double dampingPercent) { return kLongestT60_s * std::pow(kShortestT60_s / kLongestT60_s, dampingPercent / 100.0); }

double dampingFromT60(double t60)
{
    if (! std::isfinite(t60) || t60 <= 0.0)
        return spec(ParamId::damping).defaultValue;
    return std::clamp(100.0 * std::log(t60 / kLongestT60_s) / std::log(kShortestT60_s / kLongestT60_s), 0.0, 100.0);
}

const ParameterSpec& spec(ParamId id) { return kSpecs[static_cast<std::size_t>(id)]; }

std::optional<ParamId> findParameter(std::string_view key)
{
    for (const auto& s : kSpecs)
        if (s.key == key)
            return s.id;
    return std::nullopt;
}

ParameterSet::ParameterSet()
{
    for (const auto& s : kSpecs)
        values[static_cast<std::size_t>(s.id)] = s.defaultValue;
}

void ParameterSet::set(ParamId id, double value)
{
    const auto& s = spec(id);
    const bool whole = s.kind == ParamKind::continuous || value == std::round(value);
    if (! std::isfinite(value) || value < s.minValue || value > s.maxValue || ! whole)
    {
        std::ostringstream msg;
        msg << "parameter " << s.key << " = " << value << " is outside its range [" << s.minValue << ", " << s.maxValue << "]"
            << (s.unit.empty() ? "" : " ") << s.unit << (s.kind == ParamKind::continuous ? "" : " or not a whole number");
        throw std::out_of_range(msg.str());
    }
    values[static_cast<std::size_t>(id)] = value;
}

void ParameterSet::setClamped(ParamId id, double value)
{
    const auto& s = spec(id);
    double v = std::isfinite(value) ? std::clamp(value, s.minValue, s.maxValue) : s.defaultValue;
    if (s.kind != ParamKind::continuous)
        v = std::round(v);
    values[static_cast<std::size_t>(id)] = v;
}

std::string describeParameters()
{
    std::ostringstream out;
    out << "# id  min  max  default  unit  scale  description\n";
    for (const auto& s : kSpecs)
        out << s.key << "  " << s.minValue << "  " << s.maxValue << "  " << s.defaultValue << "  " << (s.unit.empty() ? "-" : s.unit)
            << "  " << (s.scale == ParamScale::logarithmic ? "log" : "lin") << "  " << s.name << ": " << s.help
            << (s.choices.empty() ? "" : " [") << s.choices << (s.choices.empty() ? "" : "]")
            << (s.rebuildsModel() ? " (rebuilds the model)" : "") << "\n";
    return out.str();
}

double sanitise(const ParameterSpec& spec, double raw) noexcept
{
    double v = std::isfinite(raw) ? std::clamp(raw, spec.minValue, spec.maxValue) : spec.defaultValue;
    if (spec.kind != ParamKind::continuous)
        v = std::round(v);
    return v;
}

} // namespace snaresim
