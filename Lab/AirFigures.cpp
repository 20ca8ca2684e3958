// The air box's figures in docs/MODEL.md (not a test; Lab/airbox_figures.py runs it).
//
//   airbox_figures band OUT_DIR [SECONDS] [BOX_SIDE_M]
//       The paper's section 5.3: the struck batter alone in the box, sigma_a = 0 and 2e-6 m;
//       writes OUT_DIR/band-sigma0.wav and band-sigma2e-6.wav (the microphone's pressure,
//       32-bit float, 1 = 1 Pa) and prints the band's peak and decay rates.
//   airbox_figures pairs
//       The batter's (0,1) mode alone, in vacuum and in the 0.6 m box, against the added mass
//       of a baffled membrane; the heads' (0,1) pair in the cavity and in the box: frequencies
//       and decay rates.
//   airbox_figures modes [BOX_SIDE_M] [STEPS]
//       The drum's lowest modes (the (0,1) pair, each head's (1,1)) with lossless heads, snares
//       off: in the cavity alone, with the outside air, and in the air box (absorbing walls).
//   airbox_figures modes-model Mm Rm Md Rd Ms Rs Mt Rt ANTI_NEAR [MODES_UP_TO_HZ]
//       The same for the cavity with outside air of the given channels (the calibration's
//       inner loop, Lab/calibrate_outside_air.py), and the cavity's modes up to a frequency.
//   airbox_figures whole-drum [STIFFNESS MASS_KG] [same-grids] [coarser=F] [no-near-field] [modes=HZ]
//       The whole real-time drum (cavity and outside air) against the 1.3 m air box at the three
//       microphones, octave bands of 300 ms (the microphones' test's drum and strike), with the
//       mallet's stiffness and mass given (default: the test's); same-grids puts the box's heads
//       on the real-time drum's grids, coarser=F widens the real-time grids by F, no-near-field
//       leaves the near field out, modes=HZ adds the cavity's modes up to HZ. Then the heads'
//       motion under the microphones (rho_a c v), the same way.
//   airbox_figures head-modes [the options of whole-drum]
//       The same two drums mode by mode: each head's displacement on its vacuum modes' shapes
//       (j_mn < 12.5), the peak near each mode's vacuum frequency and its level in four windows.
//   airbox_figures s52
//       The paper's section 5.2 in the cavity and in the box, and the variations that test
//       what moves the wires' timing: when they are lowest and when they are back on the head.

#include "AirBandRun.h"
#include "BatterModes.h"
#include "Bessel.h"
#include "LowModes.h"
#include "MicBands.h"
#include "ModePairs.h"
#include "Pluck01.h"
#include "Section52.h"
#include "SpectrumPeaks.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

using namespace snaresim;

namespace
{
void writeWav(const std::string& path, const std::vector<double>& x, double sampleRate_Hz)
{
    FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr)
    {
        std::fprintf(stderr, "cannot write %s\n", path.c_str());
        std::exit(1);
    }
    const auto put32 = [f](std::uint32_t v) { std::fwrite(&v, 4, 1, f); };
    const auto put16 = [f](std::uint16_t v) { std::fwrite(&v, 2, 1, f); };
    const auto bytes = (std::uint32_t)(4 * x.size());
    std::fwrite("RIFF", 1, 4, f);
    put32(36 + bytes);
    std::fwrite("WAVEfmt ", 1, 8, f);
    put32(16);
    put16(3); // IEEE float
    put16(1);
    put32((std::uint32_t) sampleRate_Hz);
    put32((std::uint32_t)(4 * sampleRate_Hz));
    put16(4);
    put16(32);
    std::fwrite("data", 1, 4, f);
    put32(bytes);
    for (double v : x)
    {
        const float s = (float) v;
        std::fwrite(&s, 4, 1, f);
    }
    std::fclose(f);
}

int band(const std::string& dir, double seconds, double side)
{
    test::AirBandSetup setup;
    setup.seconds = seconds;
    setup.box_m = { side, side, side };
    const double fs = setup.sampleRate_Hz;
    // The axial band (0.196 Fs) and the side-diagonal one (0.304 Fs, sin(pi f / fs) = sqrt(2/3)),
    // fitted over 50-300 ms (the weaker band stays far above the spectrum's floor there) and,
    // the axial one, over the whole record from 50 ms (its decay slows as it goes on).
    struct Fit
    {
        const char* what;
        double lo, hi, t1;
    };
    const Fit fits[3] = { { "0.196 Fs", 0.17, 0.22, 0.3 }, { "0.304 Fs", 0.28, 0.33, 0.3 }, { "0.196 Fs", 0.17, 0.22, seconds - 0.01 } };
    test::BandDecay decay[2][3];
    for (int run = 0; run < 2; ++run)
    {
        setup.sigma_m = run == 0 ? 0.0 : 2e-6;
        const std::vector<double> p = test::runAirBand(setup);
        writeWav(dir + (run == 0 ? "/band-sigma0.wav" : "/band-sigma2e-6.wav"), p, fs);
        const test::Frames F = test::stft(p, fs);
        for (int b = 0; b < 3; ++b)
        {
            const Fit& f = fits[b];
            test::BandDecay& d = decay[run][b];
            d = test::bandDecay(F, 0.05, f.t1, f.lo * fs, f.hi * fs, run == 0 ? 0.0 : decay[0][b].peak_Hz);
            std::printf("sigma_a = %-6g m, band at %s: peak %.0f Hz (%.4f Fs), level %.1f dB at 50 ms, decay %.1f dB/s over 50-%.0f ms "
                        "(T60 %.2f s)\n",
                        setup.sigma_m, f.what, d.peak_Hz, d.peak_Hz / fs, d.level_dB, d.rate_dB_per_s, 1e3 * f.t1, 60.0 / d.rate_dB_per_s);
        }
    }
    for (int b = 0; b < 3; ++b)
        std::printf("sigma_a adds %.1f dB/s at %.0f Hz over 50-%.0f ms (predicted from eq. 25: %.1f dB/s)\n",
                    decay[1][b].rate_dB_per_s - decay[0][b].rate_dB_per_s, decay[0][b].peak_Hz, 1e3 * fits[b].t1,
                    test::sigmaDecay_dB_per_s(decay[0][b].peak_Hz, 2e-6, fs));
    return 0;
}
// The lossless batter (T = 3050 N/m, grid at its bound) at rest in its (0,1) shape, alone in
// vacuum (box == nullptr) or embedded in the 0.6 m box; its centre's displacement.
std::vector<double> batterAlone(const AirBoxSpec* box, int steps)
{
    const double k = 1.0 / 44100.0;
    MembraneSpec spec;
    spec.tension_N_per_m = 3050.0;
    std::unique_ptr<AirBox> air = box ? std::make_unique<AirBox>(*box, k) : nullptr;
    Membrane head(spec, k);
    std::unique_ptr<HeadEmbedding> embed = air ? std::make_unique<HeadEmbedding>(*air, head, 0.0) : nullptr;
    test::pluck01(head);
    const int centre = head.grid().nearestInterior(0.0, 0.0);
    std::vector<double> w;
    for (int n = 0; n < steps; ++n)
    {
        if (air)
            air->computeNext();
        head.computeFree();
        if (embed)
            embed->step();
        if (air)
            air->advance();
        head.advance();
        w.push_back(head.nowAt(centre));
    }
    return w;
}

double strongestPeak(const std::vector<double>& x, double fs, double lo, double hi)
{
    const size_t pad = 8;
    const auto found = test::peaks(test::hannSpectrum(x, pad), fs / (double) (pad * x.size()), lo, hi);
    return found.empty() ? 0.0 : found.front().frequency;
}

// The air's added mass on the (0,1) mode J0(j01 r / a) of a membrane in an infinite baffle,
// one side, at low frequency (incompressible): rho_a / (2 pi) int_0^inf |V(kappa)|^2 dkappa,
// V the mode's Hankel transform; its own modal mass rho pi a^2 J1(j01)^2.
double bafffledAddedMass(double a, double rhoAir)
{
    const double j01 = 2.404825557695773, k0 = j01 / a, c = 2.0 * std::numbers::pi * a * k0 * std::cyl_bessel_j(1.0, j01);
    double sum = 0.0;
    const double dk = 0.002 / a;
    for (double kappa = 0.5 * dk; kappa < 5000.0 / a; kappa += dk)
    {
        const double V = c * std::cyl_bessel_j(0.0, kappa * a) / (k0 * k0 - kappa * kappa);
        sum += V * V * dk;
    }
    return rhoAir / (2.0 * std::numbers::pi) * sum;
}

int pairs()
{
    const double fs = 44100.0;
    const int steps = 1 << 15;
    // The batter alone.
    {
        AirBoxSpec box;
        box.sigma_m = 0.0;
        box.shell = false;
        std::vector<double> w[3];
        const char* names[3] = { "vacuum", "air box 0.6 m, reflecting walls", "air box 0.6 m, absorbing walls" };
        w[0] = batterAlone(nullptr, steps);
        box.walls = AirWalls::reflecting;
        w[1] = batterAlone(&box, steps);
        box.walls = AirWalls::absorbing;
        w[2] = batterAlone(&box, steps);
        const double f0 = strongestPeak(w[0], fs, 100.0, 300.0);
        std::printf("batter alone, lossless, (0,1) mode:\n");
        for (int i = 0; i < 3; ++i)
        {
            const double f = strongestPeak(w[i], fs, 60.0, 300.0);
            const double rate = test::bandDecay_dB_per_s(w[i], fs, f);
            std::printf("  %-34s %6.1f Hz (%+5.1f %%), decay %6.2f dB/s (T60 %s)\n", names[i], f, 100.0 * (f / f0 - 1.0), rate,
                        rate > 0.5 ? std::to_string(60.0 / rate).substr(0, 5).c_str() : "none");
        }
        const double a = 0.1778, rho = 0.353, rhoAir = 1.21;
        const double modal = rho * std::numbers::pi * a * a * std::pow(std::cyl_bessel_j(1.0, 2.404825557695773), 2.0);
        const double one = bafffledAddedMass(a, rhoAir);
        std::printf("  estimate: modal mass %.5f kg; baffled membrane, air on one side %.5f kg: %.1f Hz (%+.1f %%); "
                    "both sides %.5f kg: %.1f Hz (%+.1f %%)\n",
                    modal, one, f0 / std::sqrt(1.0 + one / modal), 100.0 * (1.0 / std::sqrt(1.0 + one / modal) - 1.0), 2.0 * one,
                    f0 / std::sqrt(1.0 + 2.0 * one / modal), 100.0 * (1.0 / std::sqrt(1.0 + 2.0 * one / modal) - 1.0));
        std::printf("  added mass the air-box figure implies: %.5f kg (%.2f of one baffled side)\n",
                    modal * (std::pow(f0 / strongestPeak(w[1], fs, 60.0, 300.0), 2.0) - 1.0),
                    modal * (std::pow(f0 / strongestPeak(w[1], fs, 60.0, 300.0), 2.0) - 1.0) / one);
        // The absorbing walls (eq. 51) are exact only for waves that meet them head on; near
        // the head the field is mostly not radiating, so a small box's walls take more than the
        // head radiates. Larger boxes, 2^14 steps each:
        for (double side : { 1.0, 1.4 })
        {
            box.size_m = { side, side, side };
            const std::vector<double> x = batterAlone(&box, 1 << 14);
            const double f = strongestPeak(x, fs, 60.0, 300.0);
            std::printf("  air box %.1f m, absorbing walls     %6.1f Hz (%+5.1f %%), decay %6.2f dB/s\n", side, f, 100.0 * (f / f0 - 1.0),
                        test::bandDecay_dB_per_s(x, fs, f));
        }
    }
    // The pair.
    {
        DrumConfig cfg = test::wholeDrum();
        cfg.sampleRate_Hz = fs;
        cfg.snares.engaged = false;
        cfg.cavity.gridShellDepth_m = 0.05; // the heads' grids of the engine's pair tests
        struct Case
        {
            const char* name;
            DrumConfig cfg;
        };
        DrumConfig cavity = cfg, box = cfg;
        cavity.cavity.model = AirModel::cavity;
        box.cavity.model = AirModel::airbox;
        DrumConfig absorbing = box.lossless(), absorbing0 = box.lossless(), cavityLossy = cavity, boxLossy = box;
        absorbing.airBox.walls = AirWalls::absorbing;
        absorbing.airBox.sigma_m = 2e-6;
        absorbing0.airBox.walls = AirWalls::absorbing;
        const Case cases[] = {
            { "cavity, lossless", cavity.lossless() },
            { "air box, reflecting walls, lossless", box.lossless() },
            { "air box, absorbing walls, sigma_a 2e-6 m", absorbing },
            { "air box, absorbing walls, sigma_a 0", absorbing0 },
            { "cavity, the heads' default losses", cavityLossy },
            { "air box, default (absorbing, losses)", boxLossy },
        };
        std::printf("the heads' (0,1) pair, 14 cm shell, snares off (lossless heads unless said):\n");
        test::ModePair reference;
        for (const Case& c : cases)
        {
            const test::SweptVolumes v = test::sweptVolumes(c.cfg, steps);
            const bool inBox = c.cfg.cavity.model == AirModel::airbox;
            const test::ModePair p = test::measuredPairs(v, inBox && reference.antiPhase > 0.0 ? test::ModePair { 0.0, reference.antiPhase }
                                                                                               : test::ModePair {});
            if (inBox && reference.antiPhase == 0.0)
                reference = p;
            const double ri = test::modeDecay_dB_per_s(v, +1.0, p.inPhase), ra = test::modeDecay_dB_per_s(v, -1.0, p.antiPhase);
            std::printf("  %-42s in phase %6.1f Hz, %7.2f dB/s (T60 %6.2f s); anti-phase %6.1f Hz, %7.2f dB/s (T60 %6.2f s)\n", c.name,
                        p.inPhase, ri, 60.0 / ri, p.antiPhase, ra, 60.0 / ra);
            std::fflush(stdout);
        }
        // Larger boxes (absorbing walls, lossless heads), 2^14 steps each.
        for (double side : { 1.0, 1.4, 1.8 })
        {
            DrumConfig c = absorbing;
            c.airBox.size_m = { side, side, side };
            const test::SweptVolumes v = test::sweptVolumes(c, 1 << 14);
            const test::ModePair p = test::measuredPairs(v, { 0.0, reference.antiPhase });
            const double ri = test::modeDecay_dB_per_s(v, +1.0, p.inPhase), ra = test::modeDecay_dB_per_s(v, -1.0, p.antiPhase);
            std::printf("  air box %.1f m, absorbing walls, lossless heads in phase %6.1f Hz, %7.2f dB/s (T60 %6.2f s); "
                        "anti-phase %6.1f Hz, %7.2f dB/s (T60 %6.2f s)\n",
                        side, p.inPhase, ri, 60.0 / ri, p.antiPhase, ra, 60.0 / ra);
            std::fflush(stdout);
        }
    }
    return 0;
}
// The pair's test drum (the pair tables' grids), snares off, lossless heads; the air's own
// losses (the box's absorbing walls, the outside air's resistances) kept.
DrumConfig modesDrum(AirModel model, bool outside)
{
    DrumConfig cfg = test::wholeDrum();
    cfg.sampleRate_Hz = 44100.0;
    cfg.snares.engaged = false;
    cfg.cavity.gridShellDepth_m = 0.05;
    cfg.cavity.model = model;
    cfg.outside.enabled = outside;
    DrumConfig run = cfg.lossless();
    run.airBox = cfg.airBox;
    run.outside = cfg.outside;
    return run;
}

void printPeaks(const char* name, const std::vector<double>& x, double fs)
{
    const auto X = test::hannSpectrum(x, 8);
    const auto found = test::peaks(X, fs / (2.0 * (double) X.size()), 80.0, 1000.0);
    std::printf("  %-6s", name);
    for (size_t i = 0; i < std::min<size_t>(6, found.size()); ++i)
        std::printf(" %7.1f Hz %6.1f dB", found[i].frequency, 20.0 / std::log(10.0) * (found[i].logMagnitude - found[0].logMagnitude));
    std::printf("\n");
}

void printAllPeaks(const test::HeadMoments& m)
{
    std::vector<double> sum(m.vb.size()), diff(m.vb.size());
    for (size_t i = 0; i < sum.size(); ++i)
    {
        sum[i] = m.vb[i] + m.vc[i];
        diff[i] = m.vb[i] - m.vc[i];
    }
    printPeaks("sum", sum, m.sampleRate_Hz);
    printPeaks("diff", diff, m.sampleRate_Hz);
    printPeaks("xb", m.xb, m.sampleRate_Hz);
    printPeaks("xc", m.xc, m.sampleRate_Hz);
}

void printModes(const char* name, const test::LowModes& m)
{
    const auto one = [](const char* what, const test::Mode& x) {
        std::printf(" %s %7.2f Hz %7.1f dB/s;", what, x.frequency_Hz, x.decay_dB_per_s);
    };
    std::printf("%-34s", name);
    one("in phase", m.inPhase);
    one("anti-phase", m.antiPhase);
    one("batter (1,1)", m.batter11);
    one("carry (1,1)", m.carry11);
    std::printf("\n");
    std::fflush(stdout);
}

int modes(double side, int steps, double antiNear)
{
    DrumConfig box = modesDrum(AirModel::airbox, false);
    box.airBox.walls = AirWalls::absorbing;
    box.airBox.sigma_m = 0.0;
    box.airBox.size_m = { side, side, side };
    box.airBox.threads = 2;
    const test::LowModes air = test::lowModes(box, steps, { 0.0, antiNear });
    printModes("cavity (no carry (1,1): not excited)", test::lowModes(modesDrum(AirModel::cavity, false), steps));
    printModes("cavity + outside air", test::lowModes(modesDrum(AirModel::cavity, true), steps, { 0.0, air.antiPhase.frequency_Hz }));
    char name[64];
    std::snprintf(name, sizeof name, "air box %.1f m, absorbing walls", side);
    printModes(name, air);
    return 0;
}

int modesModel(char** v)
{
    DrumConfig cfg = modesDrum(AirModel::cavity, true);
    RadiationChannelSpec* ch[4] = { &cfg.outside.monopole, &cfg.outside.dipole, &cfg.outside.tiltSum, &cfg.outside.tiltDiff };
    for (int i = 0; i < 4; ++i)
        *ch[i] = { std::atof(v[2 * i]), std::atof(v[2 * i + 1]) };
    if (v[8] && v[9])
        cfg.cavity.modesUpTo_Hz = std::atof(v[9]);
    printModes("model", test::lowModes(cfg, 1 << 15, { 0.0, v[8] ? std::atof(v[8]) : 0.0 }));
    return 0;
}

int s52()
{
    using test::section52Config;
    struct Case
    {
        const char* name;
        DrumConfig cfg;
    };
    std::vector<Case> cases;
    cases.push_back({ "cavity", section52Config(AirModel::cavity) });
    cases.push_back({ "air box (0.6 m, reflecting walls)", section52Config(AirModel::airbox) });
    {
        // The outside air as mass on the heads: the (0,1) added mass of one baffled side
        // (HeadEmbeddingTests.cpp: 0.0043 kg on a modal mass of rho pi R^2 J1(j01)^2), as a
        // uniform surface density, on both heads of the cavity's drum.
        DrumConfig c = section52Config(AirModel::cavity);
        const double added = 0.0043 / (std::numbers::pi * 0.1778 * 0.1778 * std::pow(std::cyl_bessel_j(1.0, 2.404825557695773), 2.0));
        c.batter.density_kg_per_m2 += added;
        c.carry.density_kg_per_m2 += added;
        cases.push_back({ "cavity, heads + the outside air's (0,1) mass", c });
    }
    {
        DrumConfig c = section52Config(AirModel::airbox);
        c.airBox.walls = AirWalls::absorbing;
        cases.push_back({ "air box, absorbing walls", c });
    }
    {
        DrumConfig c = section52Config(AirModel::airbox);
        c.airBox.size_m = { 1.0, 1.0, 1.0 };
        cases.push_back({ "air box 1.0 m", c });
    }
    {
        DrumConfig c = section52Config(AirModel::airbox);
        c.airBox.gridCoarseness = 1.5;
        cases.push_back({ "air box, air grid 1.5 x the bound", c });
    }
    {
        DrumConfig c = section52Config(AirModel::airbox);
        c.batter.gridCoarseness = c.carry.gridCoarseness = 2.0;
        cases.push_back({ "air box, heads' grids 2 x the bound", c });
    }
    const auto with = [](AirModel m, ParamId id, double value, bool absorbing) {
        ParameterSet p;
        p.set(id, value);
        DrumConfig c = section52Config(m, p);
        if (absorbing)
            c.airBox.walls = AirWalls::absorbing;
        return c;
    };
    cases.push_back({ "cavity, wires at 10 N", with(AirModel::cavity, ParamId::snareTension, 10.0, false) });
    cases.push_back({ "air box, wires at 10 N", with(AirModel::airbox, ParamId::snareTension, 10.0, false) });
    cases.push_back({ "air box, absorbing walls, wires at 10 N", with(AirModel::airbox, ParamId::snareTension, 10.0, true) });
    cases.push_back({ "cavity, carry head at 1000 N/m", with(AirModel::cavity, ParamId::carryTension, 1000.0, false) });
    cases.push_back({ "air box, carry head at 1000 N/m", with(AirModel::airbox, ParamId::carryTension, 1000.0, false) });
    cases.push_back({ "cavity, centre strike", with(AirModel::cavity, ParamId::strikePosition, 0.0, false) });
    cases.push_back({ "air box, centre strike", with(AirModel::airbox, ParamId::strikePosition, 0.0, false) });
    std::printf("section 5.2 (7 wires, 5 m/s, M = 0.028 kg, lossless, Newton, grids at the bound; paper: lowest 6 ms, back about 9 ms)\n");
    std::printf("%-46s %12s %12s %10s %10s %10s %16s\n", "", "first swing", "lowest (mm)", "all off", "back on", "clean hit",
                "carry lowest");
    for (const Case& c : cases)
    {
        const test::SnareTimes t = test::section52(c.cfg);
        std::printf("%-46s %9.2f ms %12.3f %7.2f ms %7.2f ms %7.2f ms %7.2f ms %.3f mm\n", c.name, t.swingLowest_ms, t.swingLowest_mm,
                    t.left_ms, t.back_ms, t.clean_ms, t.carryLowest_ms, t.carryLowest_mm);
        std::fflush(stdout);
    }
    return 0;
}
// The real-time drum (cavity and outside air) and the 1.3 m air box, as whole-drum and head-modes
// take them from their options.
struct TwoDrums
{
    DrumConfig realTime, box;
};

TwoDrums twoDrums(char** v, int count)
{
    DrumConfig cfg = test::micDrum();
    TwoDrums d;
    bool nearField = true, sameGrids = false;
    double coarser = 1.0, modesUpTo_Hz = 0.0;
    int numbers = 0;
    for (int i = 0; i < count; ++i)
    {
        const std::string a = v[i];
        if (a == "same-grids")
            sameGrids = true;
        else if (a == "no-near-field")
            nearField = false;
        else if (a.rfind("coarser=", 0) == 0)
            coarser = std::atof(a.c_str() + 8);
        else if (a.rfind("modes=", 0) == 0)
            modesUpTo_Hz = std::atof(a.c_str() + 6);
        else if (numbers++ == 0)
            cfg.mallet.stiffness = std::atof(a.c_str());
        else
            cfg.mallet.mass_kg = std::atof(a.c_str());
    }
    d.realTime = cfg;
    d.realTime.outside.enabled = d.realTime.outside.nearField = true;
    if (! nearField)
        d.realTime.outside.nearFieldUpTo_per_m = 0.0;
    d.realTime.cavity.modesUpTo_Hz = modesUpTo_Hz;
    d.realTime.batter.gridCoarseness *= coarser;
    d.realTime.carry.gridCoarseness *= coarser;
    d.box = sameGrids ? test::onGridsOf(test::inBox(cfg), d.realTime) : test::inBox(cfg);
    std::printf("mallet %.3g N/m^alpha, %.3g kg; real-time grids x%.3g%s%s, cavity modes %s\n", cfg.mallet.stiffness, cfg.mallet.mass_kg,
                coarser, sameGrids ? ", the box's heads on the same grids" : "", nearField ? "" : ", no near field",
                modesUpTo_Hz > 0.0 ? ("to " + std::to_string((int) modesUpTo_Hz) + " Hz").c_str() : "none");
    return d;
}

int wholeDrum(char** v, int count)
{
    const TwoDrums d = twoDrums(v, count);
    const double fs = d.box.sampleRate_Hz;
    const int samples = (int) std::lround(0.3 * fs);
    const test::Recording inBox = test::record(d.box, samples), rt = test::record(d.realTime, samples);
    std::printf("octave bands 125 Hz - 4 kHz, 300 ms\n");
    test::worstDifference("the real-time drum (cavity and outside air)", rt.drum, inBox.drum, fs, test::kOctaves.back(), stdout);
    test::worstDifference("its heads' motion under the microphones (rho_a c v)", rt.plane, inBox.plane, fs, test::kOctaves.back(), stdout);
    return 0;
}

// Each head's displacement projected on its vacuum modes' shapes J_m(j_mn r / R) cos(m theta)
// (j_mn < 12.5) after the microphones' strike, in both drums: the mode's strongest peak from 30 %
// below to 5 % above its vacuum frequency and its level (RMS of the coordinate, dB) over four windows.
int headModes(char** v, int count)
{
    const TwoDrums d = twoDrums(v, count);
    struct Shape
    {
        bool carry;
        int m, n;
        double j;
    };
    std::vector<Shape> shapes;
    for (const bool carry : { false, true })
        for (int m = 0; m <= 7; ++m)
            for (int n = 1; besselZero(m, n) < 12.5; ++n)
                shapes.push_back({ carry, m, n, besselZero(m, n) });
    const double fs = d.box.sampleRate_Hz;
    const int steps = (int) std::lround(0.3 * fs);
    std::array<std::vector<std::vector<double>>, 2> coordinates;
    for (const int which : { 0, 1 })
    {
        Drum drum(which == 0 ? d.realTime : d.box);
        drum.strike(3.0, 0.3, 0.0);
        std::vector<std::vector<double>> node;
        for (const Shape& s : shapes)
            node.push_back(test::vacuumShape(s.carry ? drum.carry().grid() : drum.batter().grid(), s.m, s.j));
        coordinates[(size_t) which].assign(shapes.size(), {});
        for (int n = 0; n < steps; ++n)
        {
            drum.step();
            for (size_t q = 0; q < shapes.size(); ++q)
            {
                const Membrane& head = shapes[q].carry ? drum.carry() : drum.batter();
                double sum = 0.0;
                for (size_t i = 0; i < node[q].size(); ++i)
                    sum += node[q][i] * head.nowAt((int) i);
                coordinates[(size_t) which][q].push_back(sum);
            }
        }
    }
    const double windows[][2] = { { 0.0, 0.01 }, { 0.01, 0.03 }, { 0.05, 0.1 }, { 0.2, 0.3 } };
    std::printf("%-14s %9s | %-38s | %-38s\n", "mode", "vacuum", "real time: peak, dB 0-10/10-30/50-100/200-300 ms", "air box");
    for (size_t q = 0; q < shapes.size(); ++q)
    {
        const Shape& s = shapes[q];
        const MembraneSpec& head = s.carry ? d.box.carry : d.box.batter;
        const double vacuum = s.j * std::sqrt(head.tension_N_per_m / head.density_kg_per_m2) / (2.0 * std::numbers::pi * head.radius_m);
        std::printf("%-6s (%d,%d)   %7.0f Hz", s.carry ? "carry" : "batter", s.m, s.n, vacuum);
        for (const auto& drumCoordinates : coordinates)
        {
            const std::vector<double>& x = drumCoordinates[q];
            // the air lowers a mode by up to 25 % (the carry head's (1,1))
            const auto found = test::peaks(test::hannSpectrum(x, 8), fs / (8.0 * (double) x.size()), 0.7 * vacuum, 1.05 * vacuum);
            const double peak = found.empty() ? 0.0 : found.front().frequency;
            std::printf(" | %6.0f Hz", peak);
            for (const auto& w : windows)
            {
                double e = 1e-300;
                const int a = (int) (w[0] * fs), b = (int) (w[1] * fs);
                for (int i = a; i < b; ++i)
                    e += x[(size_t) i] * x[(size_t) i];
                std::printf(" %6.1f", 10.0 * std::log10(e / (b - a)));
            }
        }
        std::printf("\n");
    }
    return 0;
}
} // namespace

int main(int argc, char** argv)
{
    const std::string what = argc > 1 ? argv[1] : "";
    if (what == "s52")
        return s52();
    if (what == "pairs")
        return pairs();
    if (what == "modes")
        return modes(argc > 2 ? std::atof(argv[2]) : 1.4, argc > 3 ? std::atoi(argv[3]) : 1 << 15, argc > 4 ? std::atof(argv[4]) : 340.0);
    if (what == "modes-model" && argc >= 11)
        return modesModel(argv + 2);
    if (what == "whole-drum")
        return wholeDrum(argv + 2, argc - 2);
    if (what == "head-modes")
        return headModes(argv + 2, argc - 2);
    if (what == "band" && argc >= 3)
        return band(argv[2], argc > 3 ? std::atof(argv[3]) : 1.0, argc > 4 ? std::atof(argv[4]) : 0.6);
    std::fprintf(stderr, "usage: airbox_figures band OUT_DIR [SECONDS] [BOX_SIDE_M] | pairs | modes [BOX_SIDE_M] [STEPS] | modes-model Mm "
                         "Rm Md Rd Ms Rs Mt Rt ANTI_NEAR [MODES_UP_TO_HZ] | whole-drum [STIFFNESS MASS_KG] [same-grids] [coarser=F] "
                         "[no-near-field] [modes=HZ] | head-modes [the same options] | s52\n");
    return 2;
}
