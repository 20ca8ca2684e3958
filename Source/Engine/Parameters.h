#pragma once
// The one declaration of every user-facing parameter: ID, range, unit, default.
// The plugin builds its AudioProcessorValueTreeState from this table, the renderer's
// --list-params / --set read it, and the tests use it. Nothing else declares a parameter.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace snaresim
{

enum class ParamId : std::size_t
{
    // the three main controls
    batterTension,
    snareTension,
    damping,
    // heads and shell
    carryTension,
    carryFollows,
    highDamping,
    shellDepth,
    airModel,
    // snares
    snaresEngaged,
    snareCount,
    // mallet and playing
    strikePosition,
    strikeSpeedMax,
    malletMass,
    malletStiffness,
    malletExponent,
    malletContactRadius,
    // microphones and output
    micTop,
    micBottom,
    micRoom,
    micTopPosition,
    outputGain,
    // model
    gridCoarseness,
    snareSolver,
    count
};

enum class ParamScale
{
    linear,
    logarithmic
};

enum class ParamKind
{
    continuous,
    integer,
    toggle,     // 0 or 1
    choice      // 0 .. n-1, names in ParameterSpec::choices ("a|b|c")
};

struct ParameterSpec
{
    ParamId id;
    std::string_view key;   // stable ID used by the plugin, the renderer and saved states
    std::string_view name;  // human-readable name
    std::string_view unit;  // SI unit (or "" for a pure number)
    double minValue;
    double maxValue;
    double defaultValue;
    ParamScale scale;
    bool needsNewGrid;      // true when a change requires rebuilding the model (not only coefficients)
    std::string_view help;
    ParamKind kind = ParamKind::continuous;
    std::string_view choices = "";
    std::string_view group = "";  // editor group: "main", "heads", "snares", "mallet", "output", "model"
};

inline constexpr std::size_t kNumParameters = static_cast<std::size_t>(ParamId::count);

// The table itself (defined in Parameters.cpp, in ParamId order).
const std::array<ParameterSpec, kNumParameters>& parameterSpecs();

const ParameterSpec& spec(ParamId id);

// Look up a parameter by its key; empty when unknown.
std::optional<ParamId> findParameter(std::string_view key);

// A full set of parameter values, initialised to the defaults.
class ParameterSet
{
public:
    ParameterSet();

    double get(ParamId id) const { return values[static_cast<std::size_t>(id)]; }

    // Sets a value; throws std::out_of_range with a readable message when it is outside the
    // declared range or not finite.
    void set(ParamId id, double value);

    // Sets a value, clamping it into range (non-finite values give the default). For hosts.
    void setClamped(ParamId id, double value);

private:
    std::array<double, kNumParameters> values {};
};

// A value from a host or a saved state, made safe for the engine: finite, in range, whole for
// toggles, choices and integers (a non-finite value gives the default).
double sanitise(const ParameterSpec& spec, double raw) noexcept;

// Formats the table for --list-params: one line per parameter.
std::string describeParameters();

} // namespace snaresim
