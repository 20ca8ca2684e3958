// The one parameter declaration: consistent, in range, and mapped onto the physics.

#include "Drum.h"
#include "DrumConfig.h"
#include "Presets.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>

using namespace snaresim;

TEST_CASE("every parameter has a unique key and a default inside its range", "[parameters]")
{
    std::set<std::string> keys;
    for (const auto& s : parameterSpecs())
    {
        INFO(std::string(s.key));
        CHECK(keys.insert(std::string(s.key)).second);
        CHECK(s.minValue < s.maxValue);
        CHECK(s.defaultValue >= s.minValue);
        CHECK(s.defaultValue <= s.maxValue);
        CHECK(findParameter(s.key) == s.id);
        CHECK(describeParameters().find(std::string(s.key)) != std::string::npos);
    }
    CHECK_FALSE(findParameter("no_such_parameter").has_value());
}

TEST_CASE("out-of-range and non-finite values are refused or clamped", "[parameters]")
{
    ParameterSet p;
    CHECK_THROWS_AS(p.set(ParamId::batterTension, 1.0e6), std::out_of_range);
    CHECK_THROWS_AS(p.set(ParamId::batterTension, std::nan("")), std::out_of_range);
    CHECK(p.get(ParamId::batterTension) == spec(ParamId::batterTension).defaultValue);
    p.setClamped(ParamId::batterTension, 1.0e6);
    CHECK(p.get(ParamId::batterTension) == spec(ParamId::batterTension).maxValue);
    p.setClamped(ParamId::batterTension, std::nan(""));
    CHECK(p.get(ParamId::batterTension) == spec(ParamId::batterTension).defaultValue);
}

TEST_CASE("the defaults give the 14 x 5.5 inch drum of docs/MODEL.md", "[parameters]")
{
    const DrumConfig c = makeDrumConfig(ParameterSet {}, 48000.0);
    CHECK(c.batter.tension_N_per_m == 3050.0);
    CHECK(c.batter.density_kg_per_m2 == Approx(0.353));
    CHECK(c.mallet.mass_kg == 0.028);
    CHECK(c.batter.sigma0_per_s == Approx(3.0 * std::log(10.0) / (4.0 * std::pow(0.15 / 4.0, 0.19)))); // damping 19 %
    CHECK(c.mallet.stiffness == 4.0e9);
    CHECK(c.batter.sigma1_m2_per_s == Approx(1.15e-3));
    CHECK(c.snares.tension_N == 10.0);
    CHECK(c.batter.precision == HeadPrecision::single_precision);
    // The grid is designed for the largest tension the control allows.
    CHECK(c.batter.gridTension_N_per_m == spec(ParamId::batterTension).maxValue);
    // Real time by default: the quadratised snare solve, the grids of the default bandwidth, the
    // outside air on, without its near field.
    CHECK(c.snares.scheme == CollisionScheme::quadratised);
    CHECK(c.batter.gridCoarseness == gridCoarsenessFor(spec(ParamId::bandwidth).defaultValue));
    CHECK(c.snares.gridCoarseness == c.batter.gridCoarseness);
    CHECK(c.outside.enabled);
    CHECK_FALSE(c.outside.nearField);
}

TEST_CASE("the quality and solver settings reach the heads, the wires and the snare solve", "[parameters]")
{
    ParameterSet p;
    p.set(ParamId::snareSolver, 1.0);
    p.set(ParamId::bandwidth, qualityBandwidth_Hz(3.0));
    const DrumConfig c = makeDrumConfig(p, 48000.0);
    CHECK(c.snares.scheme == CollisionScheme::newton);
    CHECK(c.carry.gridCoarseness == 3.0);
    CHECK(c.snares.gridCoarseness == 3.0);
    // The wire grid is the stability bound of eq. (40) times the coarseness, fitted to the
    // (fitted) wire length L with a whole number of intervals: M = floor(L / (coarseness h_min)),
    // h_s = L / M (18 and 57 intervals here); every interior node of every wire is a contact point.
    const double k = 1.0 / 48000.0;
    auto checkWireGrid = [k](const DrumConfig& cfg, const Drum& drum) {
        const double L = cfg.fittedSnares().length_m;
        const int M = (int) std::floor(L / (cfg.snares.gridCoarseness * SnareWires::minimumSpacing(cfg.snares, k)));
        INFO("coarseness " << cfg.snares.gridCoarseness << ": " << M << " intervals of " << L / M << " m");
        CHECK(drum.snareWires().intervals() == M);
        CHECK(drum.snareWires().spacing() == Approx(L / M).epsilon(1e-12));
        CHECK(drum.snareWires().spacing() >= cfg.snares.gridCoarseness * SnareWires::minimumSpacing(cfg.snares, k));
        CHECK(drum.snareContact().numPoints() == cfg.snares.count * (M - 1));
    };
    const Drum coarse(c);
    checkWireGrid(c, coarse);
    p.set(ParamId::bandwidth, qualityBandwidth_Hz(1.0));
    const DrumConfig f = makeDrumConfig(p, 48000.0);
    const Drum fine(f);
    checkWireGrid(f, fine);
    CHECK(fine.snareWires().spacing() < 1.1 * SnareWires::minimumSpacing(c.snares, k));
    CHECK(fine.snareContact().numPoints() > 2 * coarse.snareContact().numPoints());
}

TEST_CASE("presets are found by name and apply their values", "[parameters]")
{
    ParameterSet p;
    REQUIRE(applyPreset("tight funk", p)); // names are case-insensitive
    CHECK(p.get(ParamId::batterTension) == 4800.0);
    CHECK_FALSE(applyPreset("no such preset", p));
    CHECK(p.get(ParamId::batterTension) == 4800.0); // an unknown name leaves the values alone
    for (const auto& preset : factoryPresets())
    {
        INFO("preset " << std::string(preset.name));
        ParameterSet q;
        q.set(ParamId::outputGain, -12.0); // no preset sets it: applying one resets it
        REQUIRE(applyPreset(preset.name, q));
        // The preset's values, and the defaults for the rest.
        for (const auto& s : parameterSpecs())
        {
            double expected = s.defaultValue;
            for (const auto& [id, value] : preset.values)
                if (id == s.id)
                    expected = value;
            INFO("parameter " << std::string(s.key));
            CHECK(q.get(s.id) == expected);
        }
        DrumConfig cfg;
        CHECK_NOTHROW(cfg = makeDrumConfig(q, 44100.0));
        CHECK(cfg.batter.tension_N_per_m == q.get(ParamId::batterTension));
        CHECK(cfg.snares.engaged == (q.get(ParamId::snaresEngaged) >= 0.5));
    }
}

TEST_CASE("DrumConfig{} is the schema's default drum simulated at 48 kHz", "[parameters]")
{
    // Built both ways, the two drums play the same strike sample for sample: the schema's
    // default at 48 kHz is simulated at 32 kHz (HostRateInterpolator.h); the same config at a
    // 48 kHz step is DrumConfig{}.
    DrumConfig atFull = makeDrumConfig(ParameterSet {}, 48000.0);
    CHECK(atFull.sampleRate_Hz == 32000.0);
    CHECK(atFull.outputRate() == 48000.0);
    atFull.sampleRate_Hz = 48000.0;
    atFull.outputRate_Hz = 0.0;
    Drum a { DrumConfig {} };
    Drum b { atFull };
    a.strikeAtDefaultPoint(3.0);
    b.strikeAtDefaultPoint(3.0);
    int differing = 0;
    double peak = 0.0;
    for (int n = 0; n < 4800; ++n)
    {
        const double x = a.step(), y = b.step();
        differing += x != y ? 1 : 0;
        peak = std::max(peak, std::abs(x));
    }
    CHECK(differing == 0);
    CHECK(peak > 1.0e-3);
}

namespace
{
// A parameter set with one value moved to the far end of its range from the default.
ParameterSet movedOne(ParamId id)
{
    ParameterSet p;
    const auto& s = spec(id);
    p.set(id, s.maxValue - s.defaultValue > s.defaultValue - s.minValue ? s.maxValue : s.minValue);
    return p;
}

struct GridShape
{
    int batterNodes, carryNodes, wireIntervals, contactPoints;
    CollisionScheme scheme;
    AirModel air;
    double airSpacing; // 0 without the air box
    bool singleHeads;
    bool outsideAir;
    bool nearField;
    bool operator==(const GridShape&) const = default;
};

GridShape shapeOf(const Drum& d)
{
    return { d.batter().grid().numInterior(),
             d.carry().grid().numInterior(),
             d.snareWires().intervals(),
             d.snareContact().numPoints(),
             d.config().snares.scheme,
             d.config().cavity.model,
             d.airBox().active() ? d.airBox().air().spacing() : 0.0,
             d.batter().singlePrecision(),
             d.outsideAir().active(),
             d.nearFieldAir().active() };
}
} // namespace

TEST_CASE("a change the schema calls live is one: applied to a running drum it plays as a drum built with it", "[parameters]")
{
    // What a change needs is declared once (ChangeNeeds). For each parameter declared as
    // needing coefficients only, a drum built with the defaults and then given the moved value
    // by applyLive plays a strike exactly as a drum built with the moved value.
    int checked = 0;
    for (const auto& s : parameterSpecs())
    {
        if (s.rebuildsModel())
            continue;
        INFO(std::string(s.key));
        const auto moved = movedOne(s.id);
        Drum live { makeDrumConfig(ParameterSet {}, 48000.0) };
        live.applyLive(mapParameters(moved, 48000.0));
        Drum built { makeDrumConfig(moved, 48000.0) };
        REQUIRE(shapeOf(live) == shapeOf(built));
        live.strikeAtDefaultPoint(3.0);
        built.strikeAtDefaultPoint(3.0);
        int differing = 0;
        for (int n = 0; n < 960; ++n)
            differing += live.step() != built.step() ? 1 : 0;
        CHECK(differing == 0);
        ++checked;
    }
    CHECK(checked > 0);
}

TEST_CASE("a change the schema says rebuilds the model changes the grids or the solver", "[parameters]")
{
    // On the default drum, or (for what only the air box uses) on the default drum in the air box.
    int checked = 0;
    for (const auto& s : parameterSpecs())
    {
        if (! s.rebuildsModel())
            continue;
        INFO(std::string(s.key));
        bool changed = false;
        for (const double air : { spec(ParamId::airModel).defaultValue, (double) AirModel::airbox })
        {
            ParameterSet base;
            base.set(ParamId::airModel, air);
            ParameterSet moved = movedOne(s.id);
            if (s.id != ParamId::airModel)
                moved.set(ParamId::airModel, air);
            const GridShape a = shapeOf(Drum { makeDrumConfig(base, 48000.0) });
            const GridShape b = shapeOf(Drum { makeDrumConfig(moved, 48000.0) });
            const bool gridsDiffer = a.batterNodes != b.batterNodes || a.carryNodes != b.carryNodes || a.wireIntervals != b.wireIntervals ||
                                     a.contactPoints != b.contactPoints || a.airSpacing != b.airSpacing;
            changed = s.needs == ChangeNeeds::newGrid ? gridsDiffer
                                                      : (a.scheme != b.scheme || a.air != b.air || a.singleHeads != b.singleHeads ||
                                                         a.outsideAir != b.outsideAir || a.nearField != b.nearField);
            if (changed)
                break;
        }
        CHECK(changed);
        ++checked;
    }
    CHECK(checked > 0);
}

TEST_CASE("old states' keys migrate as the schema says", "[parameters]")
{
    CHECK(kStateVersion == 5);
    const auto decay = migrateParameter(1, "batter_decay", 4.0);
    REQUIRE(decay.has_value());
    CHECK(decay->first == ParamId::damping);
    CHECK(decay->second == Approx(0.0).margin(1e-12));
    CHECK(migrateParameter(0, "listen_position", 0.7) == std::pair { ParamId::micTopPosition, 0.7 });
    CHECK(migrateParameter(1, "batter_high_damping", 2e-3) == std::pair { ParamId::highDamping, 2e-3 });
    CHECK_FALSE(migrateParameter(2, "batter_decay", 1.0).has_value()); // today's states have no such key
    CHECK(migrateParameter(2, "damping", 40.0) == std::pair { ParamId::damping, 40.0 });
    CHECK_FALSE(migrateParameter(1, "no_such_key", 1.0).has_value());
    // Quality was the grids' coarseness (versions 0 to 2): its bandwidth now
    CHECK(migrateParameter(2, "grid_coarseness", 2.0) == std::pair { ParamId::bandwidth, qualityBandwidth_Hz(2.0) });
    CHECK_FALSE(migrateParameter(3, "grid_coarseness", 2.0).has_value());
    // The damping law and its inverse agree.
    for (double d : { 0.0, 12.5, 25.0, 80.0, 100.0 })
        CHECK(dampingFromT60(dampingT60(d)) == Approx(d).margin(1e-9));
    CHECK(dampingT60(0.0) == 4.0);
    CHECK(dampingT60(100.0) == Approx(0.15));
}
