// The whole drum (eq. 1-50, the air box replaced by the reduced cavity): energy, collisions, the snares'
// sound, and the cavity's coupling of the heads.

#include "ModePairs.h"
#include "SpectrumPeaks.h"
#include "TestDrums.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace snaresim;

namespace
{
struct Drift
{
    double relative = 0.0;  // largest relative variation of the energy balance
    double corrected = 0.0; // share of the strike's energy the quadratised scheme's psi resets removed
};

// Runs a lossless drum for `steps` after a strike: the largest relative variation of the energy
// balance (the total, plus what left with the retrieved mallet or through psi resets).
Drift losslessDrift(DrumConfig cfg, double speed, int steps, SolverStats& stats)
{
    Drum drum(cfg.lossless());
    drum.setEnergyTracking(true);
    drum.strike(speed, 0.3, 0.0);
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    Drift d;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        d.relative = std::max(d.relative, std::abs(drum.energy().balance() - b0) / e0);
    }
    d.corrected = drum.energy().dissipated_J / e0; // lossless: only the resets dissipate
    stats = drum.solverStats();
    return d;
}

CollisionScheme schemeOf(int i) { return i == 0 ? CollisionScheme::newton : CollisionScheme::quadratised; }
const char* nameOf(CollisionScheme s) { return s == CollisionScheme::newton ? "Newton" : "quadratised"; }

// Share of a signal's energy above f_Hz (its Hann-windowed spectrum).
double shareAbove(const std::vector<double>& x, double sampleRate_Hz, double f_Hz)
{
    const auto X = test::hannSpectrum(x, 1);
    const double binHz = sampleRate_Hz / (2.0 * (double) X.size());
    double above = 0.0, all = 0.0;
    for (size_t i = 1; i < X.size(); ++i)
    {
        all += std::norm(X[i]);
        if ((double) i * binHz > f_Hz)
            above += std::norm(X[i]);
    }
    return above / all;
}
} // namespace

TEST_CASE("lossless whole drum conserves energy to round-off (20 snares, cavity)", "[drum][energy]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = schemeOf(GENERATE(0, 1));
    SolverStats stats;
    const Drift drift = losslessDrift(cfg, 5.0, 44100, stats);
    INFO(nameOf(cfg.snares.scheme) << ": relative energy variation " << drift.relative << ", max Newton iterations " << stats.maxIterations
                                   << ", removed by psi resets " << drift.corrected);
    CHECK(drift.relative < 1e-11);
    CHECK(stats.fallbacks == 0);
    if (cfg.snares.scheme == CollisionScheme::newton)
        CHECK(drift.corrected == 0.0);
    else
        CHECK(drift.corrected < 0.05); // the passive correction stays a small share of the strike
}

TEST_CASE("lossless whole drum with the paper's 7 snares and mallet conserves energy", "[drum][energy]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.count = 7;
    cfg.snares.scheme = schemeOf(GENERATE(0, 1));
    cfg.mallet.mass_kg = 0.028; // the paper's energy test: M = 0.028 kg at 5 m/s, 7 snares
    SolverStats stats;
    const Drift drift = losslessDrift(cfg, 5.0, 44100, stats);
    INFO(nameOf(cfg.snares.scheme) << ": relative energy variation " << drift.relative);
    CHECK(drift.relative < 1e-11);
}

TEST_CASE("the snares' contact damping only takes energy and the ledger books what it takes", "[drum][energy][snares]")
{
    // The drum lossless but for the collisions' damping (Hunt and Crossley, lambda): energy +
    // losses constant to round-off, the energy never rising, and the damping's work the losses
    // (with Newton the elastic contact loses nothing; quadratised, psi's resets add theirs).
    const CollisionScheme scheme = schemeOf(GENERATE(0, 1));
    double lost[2] = {};
    for (const double lambda : { 0.0, 5.0 })
    {
        DrumConfig cfg = test::wholeDrum().lossless();
        cfg.snares.scheme = scheme;
        cfg.snares.contactDamping_s_per_m = lambda;
        Drum drum(cfg);
        drum.setEnergyTracking(true);
        drum.strike(5.0, 0.3, 0.0);
        const double e0 = drum.energy().total(), b0 = drum.energy().balance();
        double previous = e0, worstRise = 0.0, worstBalance = 0.0;
        for (int n = 0; n < 22050; ++n)
        {
            drum.step();
            const double e = drum.energy().total();
            worstRise = std::max(worstRise, (e - previous) / e0);
            worstBalance = std::max(worstBalance, std::abs(drum.energy().balance() - b0) / e0);
            previous = e;
        }
        lost[lambda > 0.0] = drum.energy().dissipated_J / e0;
        INFO(nameOf(scheme) << ", lambda " << lambda << " s/m: largest rise " << worstRise << ", balance drift " << worstBalance
                            << ", lost " << lost[lambda > 0.0] << " of the strike");
        CHECK(worstRise < 1e-12); // round-off: the lossless parts hold their energy to it
        CHECK(worstBalance < 1e-11);
        CHECK(drum.solverStats().fallbacks == 0);
    }
    if (scheme == CollisionScheme::newton)
        CHECK(lost[0] == 0.0);
    CHECK(lost[1] > lost[0] + 1e-3);
}

TEST_CASE("a softer snare contact keeps the energy identity and takes the snares' clicks above 12 kHz down", "[drum][energy][snares]")
{
    // The snares' stiffness kappa_s (eq. 16) a hundred times lower. Lossless, the balance holds
    // to round-off. A collision lasts as kappa_s^(-1/(beta + 1)) (Hertz): a few microseconds for
    // the paper's stiff contact, a click as broad as the band; 6.3 times longer here, so its
    // click carries less above 12 kHz in the strike's first 50 ms (6 dB at least; 13 dB with
    // Newton, 25 dB quadratised, on the machine this was written on); it presses deeper.
    const CollisionScheme scheme = schemeOf(GENERATE(0, 1));
    const double stiff = test::wholeDrum().snares.stiffness, soft = stiff * 1e-2;
    double deepest[2] = {}, high[2] = {};
    for (const double kappa : { stiff, soft })
    {
        DrumConfig cfg = test::wholeDrum().lossless();
        cfg.snares.scheme = scheme;
        cfg.snares.stiffness = kappa;
        Drum drum(cfg);
        drum.setEnergyTracking(true);
        drum.strike(5.0, 0.3, 0.0);
        const double e0 = drum.energy().total(), b0 = drum.energy().balance();
        double drift = 0.0;
        std::vector<double> x;
        for (int n = 0; n < (int) (0.05 * cfg.sampleRate_Hz); ++n)
        {
            x.push_back(drum.step());
            drift = std::max(drift, std::abs(drum.energy().balance() - b0) / e0);
        }
        const int i = kappa == soft;
        high[i] = shareAbove(x, cfg.sampleRate_Hz, 12000.0);
        deepest[i] = drum.solverStats().maxSnarePenetration_m;
        INFO(nameOf(scheme) << ", kappa_s " << kappa << ": balance drift " << drift << ", share above 12 kHz " << high[i]
                            << ", deepest penetration " << deepest[i] * 1e6 << " um");
        CHECK(drift < 1e-11);
        CHECK(drum.solverStats().fallbacks == 0);
    }
    INFO(nameOf(scheme) << ": above 12 kHz the soft contact carries " << 10.0 * std::log10(high[1] / high[0]) << " dB against the stiff");
    CHECK(high[1] < 0.25 * high[0]);
    CHECK(deepest[1] > deepest[0]);
}

TEST_CASE("with losses the whole drum's energy never rises and energy + losses is constant", "[drum][energy]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = schemeOf(GENERATE(0, 1));
    Drum drum(cfg);
    drum.setEnergyTracking(true);
    drum.strike(5.0, 0.3, 0.0);
    const double e0 = drum.energy().total(), b0 = drum.energy().balance();
    double previous = e0, worstRise = 0.0, worstBalance = 0.0;
    double kept = -1.0; // the drum's energy when the mallet has been taken back
    int keptAt = 0;
    const int steps = 44100;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        const double e = drum.energy().total();
        worstRise = std::max(worstRise, (e - previous) / e0);
        worstBalance = std::max(worstBalance, std::abs(drum.energy().balance() - b0) / e0);
        previous = e;
        if (kept < 0.0 && ! drum.mallet(0).inPlay())
        {
            kept = e;
            keptAt = n;
        }
    }
    const double end = drum.energy().total();
    // Every mode of the heads and wires loses energy at 2 sigma0 or faster on average (sigma0 of
    // the heads from the damping, 8 /s for the wires; sigma1 only adds), half of it being
    // kinetic: over the rest of the second the drum keeps at most exp(-2 sigma0 t) of what the
    // strike left, sigma0 the smallest of the components'.
    const double sigma0 = std::min({ cfg.batter.sigma0_per_s, cfg.carry.sigma0_per_s, cfg.snares.sigma0_per_s });
    const double bound = std::exp(-2.0 * sigma0 * (steps - 1 - keptAt) / cfg.sampleRate_Hz);
    INFO(nameOf(cfg.snares.scheme) << ": largest rise " << worstRise << ", balance drift " << worstBalance << "; kept " << kept
                                   << " J at step " << keptAt << ", " << end << " J at the end (bound " << bound * kept
                                   << " J), dissipated " << drum.energy().dissipated_J << " J");
    CHECK(worstRise <= 1e-15);
    CHECK(worstBalance < 1e-10);
    REQUIRE(kept > 0.0);
    CHECK(end < bound * kept);
    CHECK(drum.energy().dissipated_J > kept - end); // the losses took it (and more while the mallet was on)
}

TEST_CASE("snares lose contact and strike the head again, with small penetration", "[drum][snares]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = schemeOf(GENERATE(0, 1));
    Drum drum(cfg);
    drum.strike(5.0, 0.3, 0.0);
    const int points = drum.snareContact().numPoints();
    std::vector<int> state(points, 0); // 0 never touched, 1 touching, 2 apart after touching, 3 struck again
    int restrikes = 0;
    const int steps20ms = (int) (0.020 * cfg.sampleRate_Hz);
    for (int n = 0; n < steps20ms; ++n)
    {
        drum.step();
        const auto& gap = drum.snareContact().gaps();
        for (int p = 0; p < points; ++p)
        {
            const bool touching = gap[(size_t) p] > 0.0;
            int& s = state[(size_t) p];
            if (s == 0 && touching)
                s = 1;
            else if (s == 1 && ! touching)
                s = 2;
            else if (s == 2 && touching)
            {
                s = 3;
                ++restrikes;
            }
        }
    }
    const double hc = drum.carry().grid().spacing();
    const double penetration = drum.solverStats().maxSnarePenetration_m;
    INFO(nameOf(cfg.snares.scheme) << ": " << restrikes << " of " << points << " points struck again; largest penetration "
                                   << penetration * 1e3 << " mm, h_c " << hc * 1e3 << " mm");
    CHECK(restrikes > points / 4);
    CHECK(penetration > 0.0);
    CHECK(penetration < 0.01 * hc);
    CHECK(drum.solverStats().fallbacks == 0);
}

namespace
{
// Share of the output's energy above 2 kHz, 100-400 ms after a fortissimo strike.
double highBandShare(bool snaresOn, CollisionScheme scheme)
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = scheme;
    cfg.snares.engaged = snaresOn;
    Drum drum(cfg);
    drum.strike(5.0, 0.3, 0.0);
    const int from = (int) (0.1 * cfg.sampleRate_Hz), to = (int) (0.4 * cfg.sampleRate_Hz);
    std::vector<double> x;
    for (int n = 0; n < to; ++n)
    {
        const double y = drum.step();
        if (n >= from)
            x.push_back(y);
    }
    return shareAbove(x, cfg.sampleRate_Hz, 2000.0);
}
} // namespace

TEST_CASE("each snare point's gap is its wire node's height above the head node it maps to", "[drum][snares]")
{
    // The contact stores its points grouped by head node, not in wire order: gapAt must still
    // find every wire node's own gap, u - w_c, through a strike and its buzz.
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = schemeOf(GENERATE(0, 1));
    Drum drum(cfg);
    drum.strike(5.0, 0.3, 0.0);
    const auto& wires = drum.snareWires();
    const auto& grid = drum.carry().grid();
    int touched = 0;
    double worst = 0.0, largest = 0.0;
    for (int n = 0; n < (int) (0.010 * cfg.sampleRate_Hz); ++n)
    {
        drum.step();
        for (int i = 0; i < wires.count(); ++i)
            for (int l = 1; l < wires.intervals(); ++l)
            {
                const int node = grid.nearestInterior(wires.nodeX(l), wires.wireY(i));
                const double expected = wires.uNow[(size_t) (i * wires.nodesPerWire() + l)] - drum.carry().nowAt(node);
                const double gap = drum.snareContact().gapAt(i, l);
                worst = std::max(worst, std::abs(gap - expected));
                largest = std::max(largest, std::abs(expected));
                touched += gap > 0.0 ? 1 : 0;
            }
    }
    INFO("largest |gap| " << largest << " m, worst mismatch " << worst << " m");
    REQUIRE(touched > 0);
    CHECK(worst <= 1e-12 * largest);
}

TEST_CASE("the snares audibly matter: much more energy above 2 kHz when engaged", "[drum][snares]")
{
    const CollisionScheme scheme = schemeOf(GENERATE(0, 1));
    const double on = highBandShare(true, scheme), off = highBandShare(false, scheme);
    INFO(nameOf(scheme) << ": share above 2 kHz: snares on " << on << ", off " << off);
    CHECK(on > 3.0 * off);
}

TEST_CASE("the quadratised snare solve follows Newton's through the first contact", "[drum][snares]")
{
    // Both schemes discretise eq. (15)-(16) on the same grids; they differ in O(k^2) terms, so
    // the carry head's motion agrees closely while the snares are pressed down and thrown off
    // (the first 3.5 ms), before the chaotic re-strikes let the two drift apart.
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = CollisionScheme::newton; // the schema's default is the quadratised one
    Drum newton(cfg);
    cfg.snares.scheme = CollisionScheme::quadratised;
    Drum quadratised(cfg);
    REQUIRE(newton.config().snares.scheme == CollisionScheme::newton);
    newton.strike(5.0, 0.3, 0.0);
    quadratised.strike(5.0, 0.3, 0.0);
    double diff = 0.0, ref = 0.0;
    int touching = 0;
    for (int n = 0; n < (int) (0.0035 * cfg.sampleRate_Hz); ++n)
    {
        newton.step();
        quadratised.step();
        const double x = newton.output(Mic::bottom), y = quadratised.output(Mic::bottom);
        diff += (x - y) * (x - y);
        ref += x * x;
        touching = std::max(touching, quadratised.solverStats().snareContacts);
    }
    INFO("relative difference of the bottom microphone " << std::sqrt(diff / ref) << ", most points touching " << touching);
    CHECK(touching > quadratised.snareContact().numPoints() / 2);
    CHECK(std::sqrt(diff / ref) < 0.02);
    CHECK(quadratised.solverStats().maxSnareIterations == 0); // one linear solve per step, no iteration
}

namespace
{
using test::ModePair;

ModePair modalEstimate(const DrumConfig& cfg, double depth);

// In-phase and anti-phase peaks of the two heads' swept volumes (snares off, lossless).
ModePair measuredPairs(AirModel model, double depth, ModePair expected)
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.engaged = false;
    cfg.cavity.model = model;
    cfg.cavity.shellDepth_m = depth;
    cfg.cavity.gridShellDepth_m = 0.05; // one grid for every depth compared
    return test::measuredPairs(cfg.lossless(), expected);
}

// The same pair from the continuous model: the axisymmetric modes J0(j0n r/R) of both heads
// (modal mass rho pi R^2 J1(j0n)^2, frequency j0n c / (2 pi R)) coupled by the air spring
// K a_i a_j, with a_n = 2 pi R^2 J1(j0n) / j0n the swept area of mode n and
// K = rho_a c_a^2 / V0 (only axisymmetric modes sweep a volume). A mode is in phase when both
// heads' swept volumes move together.
ModePair modalEstimate(const DrumConfig& cfg, double depth)
{
    constexpr int N = 10;
    const double j0[N] = { 2.404825557695773, 5.520078110286311, 8.653727912911013, 11.79153443901428, 14.93091770848779,
                           18.07106396791092, 21.21163662987926, 24.35247153074930, 27.49347913204025, 30.63460646843198 };
    const double R = cfg.batter.radius_m;
    const double K = cfg.cavity.airDensity_kg_per_m3 * std::pow(cfg.cavity.soundSpeed_m_per_s, 2) / (std::numbers::pi * R * R * depth);
    Eigen::MatrixXd stiffness = Eigen::MatrixXd::Zero(2 * N, 2 * N), mass = Eigen::MatrixXd::Zero(2 * N, 2 * N);
    Eigen::VectorXd area(2 * N);
    const MembraneSpec* heads[2] = { &cfg.batter, &cfg.carry };
    for (int h = 0; h < 2; ++h)
        for (int n = 0; n < N; ++n)
        {
            const int i = h * N + n;
            const double J1 = std::cyl_bessel_j(1.0, j0[n]);
            const double rho = heads[h]->density_kg_per_m2, c = std::sqrt(heads[h]->tension_N_per_m / rho);
            mass(i, i) = rho * std::numbers::pi * R * R * J1 * J1;
            stiffness(i, i) = std::pow(j0[n] * c / R, 2) * mass(i, i);
            area(i) = 2.0 * std::numbers::pi * R * R * J1 / j0[n];
        }
    Eigen::VectorXd signedArea = area;
    signedArea.tail(N) *= -1.0; // dV = V_b - V_c
    stiffness += K * signedArea * signedArea.transpose();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(stiffness, mass);
    ModePair pair;
    for (int e = 0; e < 2 * N; ++e)
    {
        const Eigen::VectorXd v = modes.eigenvectors().col(e);
        const double vb = area.head(N).dot(v.head(N)), vc = area.tail(N).dot(v.tail(N));
        const double f = std::sqrt(modes.eigenvalues()(e)) / (2.0 * std::numbers::pi);
        if (pair.inPhase == 0.0 && vb * vc > 0.0)
            pair.inPhase = f;
        if (pair.antiPhase == 0.0 && vb * vc < 0.0)
            pair.antiPhase = f;
    }
    return pair;
}
} // namespace

TEST_CASE("the cavity couples the heads: the lowest mode splits into an in-phase and an anti-phase pair", "[drum][cavity]")
{
    const DrumConfig cfg = test::wholeDrum();
    const double f01b = 2.404825557695773 * std::sqrt(cfg.batter.tension_N_per_m / cfg.batter.density_kg_per_m2) /
                        (2.0 * std::numbers::pi * cfg.batter.radius_m);

    const ModePair none = measuredPairs(AirModel::none, 0.14, { f01b, 0.0 });
    INFO("no air: in-phase " << none.inPhase << " Hz, anti-phase " << none.antiPhase << " Hz");
    CHECK(none.inPhase == Approx(f01b).epsilon(0.01)); // the batter alone; the carry head stays still
    CHECK(none.antiPhase == 0.0);

    const ModePair deepEstimate = modalEstimate(cfg, 0.14), shallowEstimate = modalEstimate(cfg, 0.07);
    const ModePair deep = measuredPairs(AirModel::cavity, 0.14, deepEstimate);
    const ModePair shallow = measuredPairs(AirModel::cavity, 0.07, shallowEstimate);
    INFO("14 cm shell: " << deep.inPhase << " / " << deep.antiPhase << " Hz (modal estimate " << deepEstimate.inPhase << " / "
                         << deepEstimate.antiPhase << ")");
    INFO("7 cm shell: " << shallow.inPhase << " / " << shallow.antiPhase << " Hz (estimate " << shallowEstimate.inPhase << " / "
                        << shallowEstimate.antiPhase << ")");
    CHECK(deep.inPhase == Approx(deepEstimate.inPhase).epsilon(0.02));
    CHECK(deep.antiPhase == Approx(deepEstimate.antiPhase).epsilon(0.02));
    CHECK(shallow.inPhase == Approx(shallowEstimate.inPhase).epsilon(0.02));
    CHECK(shallow.antiPhase == Approx(shallowEstimate.antiPhase).epsilon(0.02));
    CHECK(shallow.antiPhase > 1.1 * deep.antiPhase); // a shallower shell stiffens the air spring
}

TEST_CASE("the Newton solves converge within their caps through a fortissimo strike", "[drum][solver]")
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.scheme = CollisionScheme::newton;
    cfg.strikeSpeedMax_m_per_s = 10.0;
    Drum drum(cfg);
    drum.strike(10.0, 0.3, 0.0);
    for (int n = 0; n < 22050; ++n)
        REQUIRE(std::isfinite(drum.step()));
    const auto& s = drum.solverStats();
    INFO("max iterations " << s.maxIterations << " (snares " << s.maxSnareIterations << ")");
    CHECK(s.fallbacks == 0);
    CHECK(s.maxIterations < MalletContact::maxNewtonIterations);
    CHECK(s.maxSnareIterations > 0);
}
