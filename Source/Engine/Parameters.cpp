#include "Parameters.h"

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

// Ranges chosen for a 14 x 5.5 inch snare (../shared/reference/physics-notes.md, section 2).
constexpr std::array<ParameterSpec, kNumParameters> kSpecs {{
    { P::batterTension, "batter_tension", "Batter tension", "N/m", 1000.0, 6000.0, 3050.0, S::linear, false,
      "Membrane tension of the batter head; 3050 N/m puts its (0,1) mode near 200 Hz" },
    { P::batterDecay, "batter_decay", "Batter decay", "s", 0.1, 5.0, 1.5, S::logarithmic, false,
      "T60 of the batter's lowest mode (sets sigma0 = 3 ln10 / T60)" },
    { P::batterHighDamping, "batter_high_damping", "Batter high damping", "m^2/s", 0.0, 3.0e-3, 1.0e-3, S::linear, false,
      "Frequency-dependent loss sigma1 of the batter head" },
    { P::strikeSpeedMax, "strike_speed_max", "Strike speed at velocity 127", "m/s", 1.0, 10.0, 6.0, S::linear, false,
      "Mallet speed for MIDI velocity 127; lower velocities follow the documented curve" },
    { P::malletMass, "mallet_mass", "Mallet mass", "kg", 0.005, 0.1, 0.028, S::logarithmic, false,
      "Moving mass of the stick or mallet" },
    { P::malletStiffness, "mallet_stiffness", "Mallet hardness", "N/m^alpha", 1.0e6, 1.0e10, 1.0e8, S::logarithmic, false,
      "Contact stiffness kappa_M of the power-law contact" },
    { P::malletExponent, "mallet_exponent", "Mallet contact exponent", "", 1.5, 3.0, 1.5, S::linear, false,
      "Power-law exponent alpha: 1.5 Hertz (stick), up to 3 (felt)" },
    { P::malletContactRadius, "mallet_contact_radius", "Mallet contact radius", "m", 0.0, 0.02, 0.005, S::linear, false,
      "Radius of the contact patch on the head" },
    { P::strikePosition, "strike_position", "Strike position", "r/R", 0.0, 0.9, 0.3, S::linear, false,
      "Distance of the strike point from the centre, as a fraction of the radius" },
    { P::listenPosition, "listen_position", "Listening position", "r/R", 0.0, 0.9, 0.5, S::linear, false,
      "Distance of the listening point from the centre, as a fraction of the radius" },
    { P::gridCoarseness, "grid_coarseness", "Grid coarseness", "", 1.0, 4.0, 1.0, S::linear, true,
      "Head grid spacing as a multiple of the stability bound (eq. 39); larger is cheaper and duller" },
    { P::outputGain, "output_gain", "Output gain", "dB", -48.0, 12.0, 0.0, S::linear, false,
      "Output level" },
    { P::carryTension, "carry_tension", "Carry tension", "N/m", 800.0, 5000.0, 2060.0, S::linear, false,
      "Membrane tension of the carry (snare-side) head; 2060 N/m puts its (0,1) mode near 300 Hz" },
    { P::snareTension, "snare_tension", "Snare tension", "N", 10.0, 100.0, 30.0, S::linear, false,
      "Tension of each snare wire" },
    { P::snaresEngaged, "snares_engaged", "Snares on", "", 0.0, 1.0, 1.0, S::linear, false,
      "Snares on the carry head (1) or thrown off (0)", ParamKind::toggle },
    { P::snareCount, "snare_count", "Snare wires", "", 1.0, 40.0, 20.0, S::linear, true,
      "Number of snare wires", ParamKind::integer },
    { P::shellDepth, "shell_depth", "Shell depth", "m", 0.05, 0.25, 0.14, S::linear, false,
      "Depth of the shell: the enclosed air's volume and so its stiffness" },
    { P::airModel, "air_model", "Air model", "", 0.0, 1.0, 1.0, S::linear, true,
      "Enclosed air: none (heads uncoupled) or the reduced cavity", ParamKind::choice, "none|cavity" },
}};

constexpr bool tableInOrder()
{
    for (std::size_t i = 0; i < kSpecs.size(); ++i)
        if (static_cast<std::size_t>(kSpecs[i].id) != i)
            return false;
    return true;
}
static_assert(tableInOrder(), "parameter table must be in ParamId order");
} // namespace

const std::array<ParameterSpec, kNumParameters>& parameterSpecs() { return kSpecs; }

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
        msg << "parameter " << s.key << " = " << value << " is outside its range [" << s.minValue << ", "
            << s.maxValue << "]" << (s.unit.empty() ? "" : " ") << s.unit
            << (s.kind == ParamKind::continuous ? "" : " or not a whole number");
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
        out << s.key << "  " << s.minValue << "  " << s.maxValue << "  " << s.defaultValue << "  "
            << (s.unit.empty() ? "-" : s.unit) << "  " << (s.scale == ParamScale::logarithmic ? "log" : "lin")
            << "  " << s.name << ": " << s.help << (s.choices.empty() ? "" : " [") << s.choices
            << (s.choices.empty() ? "" : "]") << (s.needsNewGrid ? " (rebuilds the model)" : "") << "\n";
    return out.str();
}

} // namespace snaresim
