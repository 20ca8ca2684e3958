#pragma once
// The parameter schema: the one declaration of every user-facing parameter (ID, name, unit,
// range, skew, default, choices, editor group, what a change needs) and of the saved state's
// versions. The default drum (DrumConfig{}), the player's live/rebuild decision, the plug-in's
// parameters, its state, its editor and the renderer's --set / --list-params all follow from
// it; how values are written and read as text is in ParameterText.h. Nothing else declares a
// parameter.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>

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
    bandwidth,
    snareSolver,
    // the air box (appended: hosts that number parameters keep their automation)
    airLoss,
    // how the host's offline renders play (appended likewise)
    offlineAirBox,
    // the heads' arithmetic (appended likewise)
    headPrecision,
    // the outside air of the reduced model (appended likewise)
    outsideAir,
    // where the microphones stand (appended likewise)
    micTopHeight,
    micBottomPosition,
    micBottomHeight,
    micRoomDistance,
    micRoomAngle,
    // the plug-in's real-time fallback (appended likewise)
    keepUp,
    // the near field of the outside air, apart from its channels (appended likewise)
    nearField,
    // the snares' contact damping (appended likewise)
    snareDamping,
    // the snares' contact stiffness (appended likewise)
    snareStiffness,
    // the room (appended likewise)
    roomTime,
    roomVolume,
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
    toggle, // 0 or 1
    choice  // 0 .. n-1, names in ParameterSpec::choices ("a|b|c")
};

// What a change of the parameter needs from the running model.
enum class ChangeNeeds
{
    coefficients, // new coefficients on the same grid: live, sample-accurate (Drum::applyLive)
    newGrid,      // the same components on other grids: a model built off the audio thread
    newModel      // other components or solvers: a model built off the audio thread
};

struct ParameterSpec
{
    ParamId id;
    std::string_view key;  // stable ID used by the plugin, the renderer and saved states
    std::string_view name; // human-readable name
    std::string_view unit; // SI unit (or "" for a pure number)
    double minValue;
    double maxValue;
    double defaultValue;
    ParamScale scale;
    ChangeNeeds needs;
    std::string_view help;
    ParamKind kind = ParamKind::continuous;
    std::string_view choices = ""; // choice names "a|b|c"; toggles "off|on"
    std::string_view group = "";   // key into parameterGroups()

    // True when a change needs a model built off the audio thread.
    constexpr bool rebuildsModel() const { return needs != ChangeNeeds::coefficients; }
};

// The editor's groups, in the order it shows them.
struct ParameterGroup
{
    std::string_view key;
    std::string_view title;
};
std::span<const ParameterGroup> parameterGroups();
// The title of a group key; the key itself when unknown.
std::string_view groupTitle(std::string_view key);

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

// Saved states: the version written now, and how older versions' parameters map onto today's
// (a renamed key, its value converted). A key that is neither today's nor migrated is ignored.
inline constexpr int kStateVersion = 5;
struct ParameterMigration
{
    int beforeVersion; // applies to states older than this
    std::string_view oldKey;
    ParamId id;
    double (*convert)(double); // nullptr: the value as it was
};
std::span<const ParameterMigration> parameterMigrations();
// A parameter that states older than beforeVersion may not hold, and the value that keeps their
// drum: a key that did not exist yet, or a default that changed since.
struct ImpliedParameter
{
    int beforeVersion;
    ParamId id;
    double value;
};
std::span<const ImpliedParameter> impliedParameters();
// Today's ID and value for a key read from a state of stateVersion; empty when unknown.
std::optional<std::pair<ParamId, double>> migrateParameter(int stateVersion, std::string_view key, double value);
// Today's ID and value for a key that is no longer today's (any version's migration); empty
// for today's keys and unknown ones. Preset files and --set read old keys with it.
std::optional<std::pair<ParamId, double>> migrateOldKey(std::string_view key, double value);

// The damping control's law: the heads' lowest modes ring for
// T60 = 4 s * (0.15 / 4)^(d / 100), so 0 % gives 4 s and 100 % gives 0.15 s.
double dampingT60(double dampingPercent);
// Its inverse, clamped to 0..100 %; the default damping for a T60 that is not positive.
double dampingFromT60(double t60Seconds);

// A value from a host or a saved state, made safe for the engine: finite, in range, whole for
// toggles, choices and integers (a non-finite value gives the default).
double sanitise(const ParameterSpec& spec, double raw) noexcept;

// Formats the table for --list-params: one line per parameter.
std::string describeParameters();

} // namespace snaresim
