// How parameter values are written and read as text (ParameterText.h): one rule for the host,
// the editor and the command line.

#include "Drum.h"
#include "DrumConfig.h"
#include "ParameterText.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

using namespace snaresim;

namespace
{
std::string text(ParamId id, double v) { return formatValue(spec(id), v); }
std::optional<double> read(ParamId id, std::string_view t, BareNumber bare = BareNumber::writtenUnit)
{
    return parseValue(spec(id), t, bare);
}
} // namespace

TEST_CASE("values are written in readable units", "[parameters][text]")
{
    CHECK(text(ParamId::batterTension, 3050.0) == "3050 N/m");
    CHECK(text(ParamId::snareTension, 30.0) == "30.0 N");
    CHECK(text(ParamId::damping, 25.0) == "25 %");
    CHECK(text(ParamId::shellDepth, 0.14) == "140 mm");
    CHECK(text(ParamId::malletMass, 0.028) == "28.0 g");
    CHECK(text(ParamId::airLoss, 2.0e-6) == "2.0 \xc2\xb5m");
    CHECK(text(ParamId::malletStiffness, 1.0e8) == "1.0e8 N/m^\xce\xb1");
    CHECK(text(ParamId::malletStiffness, 9.96e8) == "1.0e9 N/m^\xce\xb1"); // the mantissa rounds up to 10
    CHECK(text(ParamId::highDamping, 1.0e-3) == "1.0e-3 m\xc2\xb2/s");
    CHECK(text(ParamId::outputGain, -0.001) == "0.0 dB"); // no "-0.0"
    CHECK(text(ParamId::snareCount, 20.0) == "20");
    CHECK(text(ParamId::snaresEngaged, 1.0) == "On");
    CHECK(text(ParamId::snaresEngaged, 0.0) == "Off");
    CHECK(text(ParamId::airModel, 1.0) == "Cavity");
    CHECK(text(ParamId::snareSolver, 1.0) == "Newton");
}

TEST_CASE("text is read in the written unit, the schema's unit, or by name", "[parameters][text]")
{
    CHECK(read(ParamId::shellDepth, "140 mm") == Approx(0.14));
    CHECK(read(ParamId::shellDepth, "140") == Approx(0.14));
    CHECK(read(ParamId::shellDepth, " 0.12 m ") == Approx(0.12));
    CHECK(read(ParamId::shellDepth, "0.12", BareNumber::schemaUnit) == Approx(0.12));
    CHECK(read(ParamId::malletMass, "28 g") == Approx(0.028));
    CHECK(read(ParamId::airLoss, "5 \xc2\xb5m") == Approx(5.0e-6));
    CHECK(read(ParamId::airLoss, "5e-6 m") == Approx(5.0e-6));
    CHECK(read(ParamId::malletMass, "0.03 kg") == Approx(0.03));
    CHECK(read(ParamId::malletStiffness, "2e8 N/m^alpha") == Approx(2.0e8));
    CHECK(read(ParamId::malletStiffness, "2e8 N/m^\xce\xb1") == Approx(2.0e8));
    CHECK(read(ParamId::snareStiffness, "3e8 N/m^beta") == Approx(3.0e8));
    CHECK(read(ParamId::snareStiffness, "3e8 N/m^\xce\xb2") == Approx(3.0e8));
    CHECK(read(ParamId::outputGain, "+3 dB") == Approx(3.0));
    CHECK(read(ParamId::airModel, "cavity") == 1.0);
    CHECK(read(ParamId::airModel, "None") == 0.0);
    CHECK(read(ParamId::airModel, "1") == 1.0);
    CHECK(read(ParamId::snaresEngaged, "on") == 1.0);
    CHECK(read(ParamId::snaresEngaged, "FALSE") == 0.0);
    CHECK_FALSE(read(ParamId::shellDepth, "deep").has_value());
    CHECK_FALSE(read(ParamId::shellDepth, "140 furlongs").has_value());
    CHECK_FALSE(read(ParamId::airModel, "box").has_value());
    CHECK_FALSE(read(ParamId::outputGain, "nan").has_value());
    CHECK_FALSE(read(ParamId::outputGain, "").has_value());
}

TEST_CASE("every value's text reads back to that value within the text's precision", "[parameters][text]")
{
    std::mt19937 random(7);
    for (const auto& s : parameterSpecs())
    {
        INFO(std::string(s.key));
        const auto format = valueFormat(s);
        std::uniform_real_distribution<double> within(s.minValue, s.maxValue);
        for (int i = 0; i < 200; ++i)
        {
            double v = i == 0 ? s.minValue : i == 1 ? s.maxValue : i == 2 ? s.defaultValue : within(random);
            if (s.kind != ParamKind::continuous)
                v = std::round(v);
            const auto written = formatValue(s, v);
            const auto back = parseValue(s, written, BareNumber::writtenUnit);
            INFO(v << " written " << written);
            REQUIRE(back.has_value());
            CHECK(formatValue(s, *back) == written);
            if (s.kind != ParamKind::continuous)
                CHECK(*back == v);
            else if (format.scientific)
                CHECK(std::abs(*back - v) <= 0.051 * std::abs(v));
            else
                CHECK(std::abs(*back - v) <= 0.5 * std::pow(10.0, -format.decimals) / format.scale * (1.0 + 1e-9));
        }
        if (s.kind == ParamKind::toggle || s.kind == ParamKind::choice)
            CHECK(numChoiceNames(s) == (int) s.maxValue + 1);
    }
}

TEST_CASE("Quality is the highest frequency the heads' and wires' grids carry, in kHz", "[parameters][text]")
{
    CHECK(text(ParamId::bandwidth, spec(ParamId::bandwidth).defaultValue) == "7.8 kHz");
    CHECK(read(ParamId::bandwidth, "7.8 kHz") == Approx(7800.0));
    CHECK(read(ParamId::bandwidth, "12") == Approx(12000.0)); // a bare number in the written unit
    double previous = 1.0e9;
    for (const double asked : { 21100.0, 15000.0, 10000.0, spec(ParamId::bandwidth).defaultValue, 5000.0, 3750.0 })
    {
        // from the drum as built and simulated at 48 kHz: each grid's top mode at its highest
        // tension (the coarser grids are simulated at 32 kHz, HostRateInterpolator.h)
        ParameterSet p;
        p.set(ParamId::bandwidth, asked);
        DrumConfig cfg = makeDrumConfig(p, 48000.0);
        cfg.sampleRate_Hz = 48000.0;
        cfg.outputRate_Hz = 0.0;
        const Drum drum(cfg);
        const double k = 1.0 / 48000.0;
        auto top = [&](double sine) { return std::asin(std::min(1.0, sine)) / (std::numbers::pi * k); };
        const double batter = top(std::sqrt(2.0) * k * std::sqrt(cfg.batter.gridTension_N_per_m / cfg.batter.density_kg_per_m2) /
                                  drum.batter().grid().spacing());
        const double carry = top(std::sqrt(2.0) * k * std::sqrt(cfg.carry.gridTension_N_per_m / cfg.carry.density_kg_per_m2) /
                                 drum.carry().grid().spacing());
        // the wires' grid is whole intervals of the wire: at most the spacing asked
        const double wires =
            top(k * std::sqrt(cfg.snares.gridTension_N / cfg.snares.linearDensity_kg_per_m) / SnareWires::gridSpacing(cfg.snares, k));
        const double carried = std::min({ batter, carry, wires });
        INFO("asked " << asked << " Hz: batter " << batter << ", carry " << carry << ", wires " << wires);
        // what the finest stable grids carry caps it; the coarseness is taken to a millionth
        CHECK(carried == Approx(std::min(asked, qualityBandwidth_Hz(1.0))).epsilon(2e-6));
        CHECK(carried < previous); // less bandwidth, coarser grids
        CHECK(cfg.batter.gridCoarseness >= 1.0);
        previous = carried;
    }
    CHECK(qualityBandwidth_Hz(1.0) > 19000.0); // at the stability bounds (the outside air's reserve widens them): near Nyquist
    CHECK(qualityBandwidth_Hz(1.0) < spec(ParamId::bandwidth).maxValue);
}

TEST_CASE("Quality's old coarseness and its bandwidth give the same grids", "[parameters][text]")
{
    // States and preset files of the old Quality (grid_coarseness) migrate to the bandwidth it
    // carried, which builds the grids of that coarseness exactly.
    for (const double c : { 1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0 })
    {
        INFO("coarseness " << c);
        CHECK(gridCoarsenessFor(qualityBandwidth_Hz(c)) == c);
        CHECK(gridCoarsenessFor((double) (float) qualityBandwidth_Hz(c)) == c); // as a host's float holds it
        const auto migrated = migrateParameter(2, "grid_coarseness", c);
        REQUIRE(migrated);
        CHECK(migrated->first == ParamId::bandwidth);
        CHECK(migrated->second == qualityBandwidth_Hz(c));
        const auto old = readOldKey("grid_coarseness", std::to_string(c));
        REQUIRE(old);
        // into the range, as a state's is: Quality 4 carried a little less than the lowest bandwidth
        CHECK(old->second == Approx(std::max(qualityBandwidth_Hz(c), spec(ParamId::bandwidth).minValue)).epsilon(1e-12));
    }
    CHECK(qualityBandwidth_Hz(4.0) < spec(ParamId::bandwidth).minValue);
    CHECK(gridCoarsenessFor(spec(ParamId::bandwidth).minValue) < 4.0);
    CHECK(gridCoarsenessFor(spec(ParamId::bandwidth).maxValue) == 1.0);
    CHECK(gridCoarsenessFor(std::nan("")) == 1.0);
    CHECK(! migrateParameter(3, "grid_coarseness", 2.0)); // today's states have no such key
    CHECK(! readOldKey("bandwidth", "7000"));             // today's key is not an old one
    CHECK(! readOldKey("no_such_key", "1"));
    CHECK_THROWS_AS(readOldKey("grid_coarseness", "fine"), std::invalid_argument);
}
