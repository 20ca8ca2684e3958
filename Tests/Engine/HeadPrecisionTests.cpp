// Heads in single precision (HeadPrecision::single_precision) against the double-precision
// reference: the output where the drum is not chaotic, the sound's features where it is (the
// snares), and the lossless energy. The mode test at both precisions is in MembraneTests.cpp.

#include "Parameters.h"
#include "TestDrums.h"

#include <catch2/catch.hpp>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

using namespace snaresim;

namespace
{
// The product's drum at a Quality (bandwidth, Hz): its finest, qualityBandwidth_Hz(1.0), or its
// default; without the outside air, struck on the snares' axis: the heads' arithmetic alone. (With
// the outside air, on the axis, float round-off breaks the drum's mirror symmetry where the
// double drum keeps it, and the snares' tail darkens as for any strike off the axis:
// docs/MODEL.md, "Heads in single precision".)
const double kFinest_Hz = qualityBandwidth_Hz(1.0);
const double kDefault_Hz = spec(ParamId::bandwidth).defaultValue;

DrumConfig productDrum(double bandwidth_Hz, bool snares, HeadPrecision precision)
{
    ParameterSet p;
    p.set(ParamId::bandwidth, bandwidth_Hz);
    p.set(ParamId::snaresEngaged, snares ? 1.0 : 0.0);
    p.set(ParamId::headPrecision, precision == HeadPrecision::single_precision ? 1.0 : 0.0);
    p.set(ParamId::outsideAir, 0.0);
    return makeDrumConfig(p, 48000.0);
}

// The mix after one fortissimo strike at the schema's strike point, its speed times `nudge`:
// `seconds` of the output's samples (at the host's rate, which the default Quality simulates at
// two thirds of).
std::vector<double> strike(const DrumConfig& cfg, double seconds, double nudge = 1.0)
{
    Drum drum(cfg);
    drum.strike(cfg.strikeSpeedMax_m_per_s * nudge, cfg.strikeRadius_frac, 0.0);
    std::vector<double> x((size_t) (seconds * cfg.outputRate()));
    for (auto& v : x)
        v = drum.step();
    return x;
}

double dBBelow(const std::vector<double>& reference, const std::vector<double>& other)
{
    double signal = 0.0, error = 0.0;
    for (size_t i = 0; i < reference.size(); ++i)
    {
        signal += reference[i] * reference[i];
        error += (reference[i] - other[i]) * (reference[i] - other[i]);
    }
    return 10.0 * std::log10(signal / std::max(error, 1e-300));
}

// The features scripts/snare_features.py reports for a strike that starts at sample 0.
struct Features
{
    double centroid_Hz = 0.0;                // power spectrum of 50-300 ms, Hann window
    double bands[4] = {};                    // shares of 0-300 ms in < 1, 1-2, 2-5, > 5 kHz
    double fall20_ms = 0.0, fall40_ms = 0.0; // the 10 ms RMS envelope stays this far below its peak after
};

Features features(const std::vector<double>& x, double fs)
{
    Features f;
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> X;
    {
        const size_t a = (size_t) (0.05 * fs), b = (size_t) (0.3 * fs);
        std::vector<double> seg(b - a);
        for (size_t i = 0; i < seg.size(); ++i)
            seg[i] = x[a + i] * 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * (double) i / (double) (seg.size() - 1)));
        fft.fwd(X, seg);
        double num = 0.0, den = 0.0;
        for (size_t k = 0; k <= seg.size() / 2; ++k)
        {
            const double p = std::norm(X[k]), hz = (double) k * fs / (double) seg.size();
            num += hz * p;
            den += p;
        }
        f.centroid_Hz = num / den;
    }
    {
        std::vector<double> seg(x.begin(), x.begin() + (std::ptrdiff_t)(0.3 * fs));
        fft.fwd(X, seg);
        const double edges[] = { 0.0, 1000.0, 2000.0, 5000.0, 1e9 };
        double total = 0.0;
        for (size_t k = 0; k <= seg.size() / 2; ++k)
        {
            const double p = std::norm(X[k]), hz = (double) k * fs / (double) seg.size();
            total += p;
            for (int j = 0; j < 4; ++j)
                if (hz >= edges[j] && hz < edges[j + 1])
                    f.bands[j] += p;
        }
        for (double& b : f.bands)
            b /= total;
    }
    {
        const size_t w = (size_t) (0.005 * fs);
        std::vector<double> env(x.size(), 0.0);
        double sum = 0.0;
        for (size_t i = 0; i < x.size(); ++i)
        {
            sum += x[i] * x[i];
            if (i >= 2 * w)
                sum -= x[i - 2 * w] * x[i - 2 * w];
            if (i >= w)
                env[i - w] = std::sqrt(std::max(sum, 0.0) / (double) (2 * w));
        }
        const double peak = *std::max_element(env.begin(), env.end());
        auto fall = [&](double dB) {
            const double level = peak * std::pow(10.0, -dB / 20.0);
            size_t last = 0;
            for (size_t i = 0; i + w < env.size(); ++i)
                if (env[i] > level)
                    last = i;
            return 1e3 * (double) last / fs;
        };
        f.fall20_ms = fall(20.0);
        f.fall40_ms = fall(40.0);
    }
    return f;
}

// The mean features of `draws` strikes whose speeds differ by 0.1 % steps: the snares make the
// drum chaotic, so one render is one draw from a spread (the double drum's tail centroid moves
// by 6 % at Quality 2 when the speed moves in its 13th digit); the mean of draws that part from
// the first contact is what two drums can be compared by.
Features meanFeatures(double bandwidth_Hz, HeadPrecision precision, double seconds, double fs, int draws)
{
    Features mean;
    for (int i = 0; i < draws; ++i)
    {
        const Features f = features(strike(productDrum(bandwidth_Hz, true, precision), seconds, 1.0 + 1e-3 * i), fs);
        mean.centroid_Hz += f.centroid_Hz / draws;
        for (int j = 0; j < 4; ++j)
            mean.bands[j] += f.bands[j] / draws;
        mean.fall20_ms += f.fall20_ms / draws;
        mean.fall40_ms += f.fall40_ms / draws;
    }
    return mean;
}

// Features a listener, or the comparison with recorded drums (docs/MODEL.md), would not tell
// apart: tail centroid within 5 %, band shares within one point, the falls within 5 % (the
// just-noticeable difference of a decay time, ISO 3382-1 Annex A).
bool close(const Features& a, const Features& b)
{
    bool ok = std::abs(a.centroid_Hz / b.centroid_Hz - 1.0) < 0.05;
    for (int j = 0; j < 4; ++j)
        ok = ok && std::abs(a.bands[j] - b.bands[j]) < 0.01;
    return ok && std::abs(a.fall20_ms / b.fall20_ms - 1.0) < 0.05 && std::abs(a.fall40_ms / b.fall40_ms - 1.0) < 0.05;
}

std::string describe(const Features& f)
{
    std::ostringstream s;
    s << "centroid " << f.centroid_Hz << " Hz, bands " << f.bands[0] << " " << f.bands[1] << " " << f.bands[2] << " " << f.bands[3]
      << ", falls " << f.fall20_ms << " / " << f.fall40_ms << " ms";
    return s.str();
}
} // namespace

TEST_CASE("single-precision heads play the double-precision drum to within 80 dB over 2 s (snares off)", "[precision][slow]")
{
    // Without the snares the drum is not chaotic, so the two outputs can be compared sample by
    // sample. One step's rounding in float is 2^-24 (-144 dB); a random walk of 96 000 of them
    // reaches about -94 dB. 80 dB leaves room for their correlation and still fails for a
    // systematic error: float coefficients near 2 multiplying w (the double scheme's form)
    // shift the modes and gave 43 dB at Quality 2. At the finest and the default Quality.
    const double bandwidth = GENERATE(kFinest_Hz, kDefault_Hz);
    const auto reference = strike(productDrum(bandwidth, false, HeadPrecision::double_precision), 2.0);
    const auto single = strike(productDrum(bandwidth, false, HeadPrecision::single_precision), 2.0);
    const double below = dBBelow(reference, single);
    INFO("Quality " << bandwidth << " Hz: the difference is " << below << " dB below the signal");
    CHECK(below > 80.0);
}

TEST_CASE("single-precision heads keep the snare drum's sound: centroid, band shares and decay", "[precision][slow]")
{
    // The mean features of 18 strikes (meanFeatures) with single-precision heads against the
    // same with double ones, at the finest and the default Quality; the two Qualities must
    // differ, or the test would not tell.
    // One draw spreads by 5 % in the centroid and 4.5 % in the 20 dB fall (Quality 2; 30 draws,
    // release and the clang sanitizer build), so 18 draws put those tolerances at 3 or more
    // standard errors of the difference. The 40 dB fall follows the body's decay and barely moves
    // from draw to draw (the means of 18: 862.1 / 861.9 ms at the finest Quality, 957.5 / 957.5
    // at the default, double / single). The features need 1.25 s to hold that fall.
    const double fs = 48000.0, seconds = 1.25;
    const int draws = 18;
    const double bandwidth = GENERATE(kFinest_Hz, kDefault_Hz);
    const auto reference = meanFeatures(bandwidth, HeadPrecision::double_precision, seconds, fs, draws);
    const auto single = meanFeatures(bandwidth, HeadPrecision::single_precision, seconds, fs, draws);
    INFO("Quality " << bandwidth << " Hz: double " << describe(reference) << "; single " << describe(single));
    CHECK(close(single, reference));
    // the falls lie inside the render (a fall to its end would compare the render's length)
    CHECK(reference.fall40_ms < 1e3 * seconds - 20.0);
    CHECK(single.fall40_ms < 1e3 * seconds - 20.0);
    if (bandwidth == kDefault_Hz)
    {
        const auto finer = meanFeatures(kFinest_Hz, HeadPrecision::double_precision, seconds, fs, 6);
        INFO("the finest Quality, double: " << describe(finer));
        CHECK_FALSE(close(finer, reference));
    }
}

TEST_CASE("a lossless drum with single-precision heads holds its energy to float round-off", "[precision][energy]")
{
    // The energy identity is exact for the stored state: in float every step rounds w at each
    // node by up to 2^-24 of it, a relative change of the energy of that order, and over n steps
    // a random walk of them: bound 2^-24 sqrt(n). The double path holds 1e-11 (WholeDrumTests.cpp).
    DrumConfig cfg = test::wholeDrum();
    cfg.batter.precision = cfg.carry.precision = HeadPrecision::single_precision;
    cfg.snares.scheme = GENERATE(CollisionScheme::quadratised, CollisionScheme::newton);
    Drum drum(cfg.lossless());
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.0);
    const int steps = 44100;
    const double drift = test::balanceDrift(drum, steps), bound = test::floatDriftBound(steps);
    INFO("relative energy variation " << drift << " (bound " << bound << ")");
    CHECK(drift < bound);
    CHECK(drift > 1e-11); // float round-off is seen: the heads do run in single precision
}

TEST_CASE("the air box keeps its heads in double precision", "[precision][airbox]")
{
    // Its embedding updates the heads with the air in double (HeadEmbedding): asked for single
    // heads, a drum in the air box runs double ones, and its config says so; with the cavity it
    // runs what it is asked for: the batter in single, the carry head (which the snares strike)
    // in double either way.
    ParameterSet p;
    p.set(ParamId::headPrecision, 1.0);
    p.set(ParamId::airModel, (double) AirModel::cavity);
    const DrumConfig cavity = makeDrumConfig(p, 48000.0);
    CHECK(cavity.batter.precision == HeadPrecision::single_precision);
    CHECK(Drum(cavity).batter().singlePrecision());
    CHECK_FALSE(Drum(cavity).carry().singlePrecision());

    p.set(ParamId::airModel, (double) AirModel::airbox);
    DrumConfig asked = makeDrumConfig(p, 48000.0);
    CHECK(asked.batter.precision == HeadPrecision::single_precision); // the parameter as set
    asked.airBox.size_m = { 0.0, 0.0, 0.0 };                          // the drum plus its margins: quick to build
    const Drum drum(asked);
    CHECK_FALSE(drum.batter().singlePrecision());
    CHECK_FALSE(drum.carry().singlePrecision());
    CHECK(drum.config().batter.precision == HeadPrecision::double_precision);
    CHECK(drum.config().carry.precision == HeadPrecision::double_precision);
}
