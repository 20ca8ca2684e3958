#pragma once
// The paper's section 5.3: the batter alone in the air box (no shell, no carry head, no
// snares), struck, heard by a pressure microphone above it on a diagonal. The 7-point scheme
// at its stability bound has a band near 0.196 Fs that decays slowly: there the axial waves
// reach the edge of the grid's band (sin(pi f k) = lambda = 1/sqrt(3)), their group velocity
// falls to 0 and they hardly reach the absorbing walls. sigma_a damps every air mode of
// frequency f by the same rate (below), so it shortens that band. Shared by the engine test
// (AirLossTests.cpp) and the figure program (AirFigures.cpp).
//
// The rate sigma_a adds. A mode of the scheme (eq. 25) at frequency f is an eigenvector of the
// 7-point Laplacian D with eigenvalue -K^2, and sin^2(pi f k) = (c k K / 2)^2 for every such
// mode whatever its direction (the dispersion relation), so K^2 = 4 sin^2(pi f k) / (c k)^2.
// Its update psi^{n+1} + (c^2 k^2 K^2 + b - 2) psi^n + (1 - b) psi^{n-1} = 0, b = c sigma k K^2,
// has roots of modulus sqrt(1 - b): the amplitude falls by -ln(1 - b) / (2 k) per second,
// about c sigma K^2 / 2, and in dB 20 log10(e) times that.

#include "AirBox.h"
#include "DrumConfig.h"
#include "HeadEmbedding.h"
#include "Membrane.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace snaresim::test
{

struct AirBandSetup
{
    double sampleRate_Hz = 44100.0;
    double sigma_m = 0.0;      // sigma_a of the run
    double gridSigma_m = 2e-6; // the grid of eq. 41 for this sigma_a, whatever sigma_m is (the same grid for every run)
    std::array<double, 3> box_m { 0.6, 0.6, 0.6 };
    std::array<double, 3> mic_m { 0.1, 0.1, 0.1 }; // on a diagonal above the head (the head at z = 0)
    double seconds = 1.0;
};

// Grid-dependent rate (dB/s) at which sigma_a damps every air mode of frequency f (above).
inline double sigmaDecay_dB_per_s(double f_Hz, double sigma_m, double sampleRate_Hz, double c = 343.0)
{
    const double k = 1.0 / sampleRate_Hz;
    const double s = std::sin(std::numbers::pi * f_Hz * k);
    const double K2 = 4.0 * s * s / (c * c * k * k);
    const double b = c * sigma_m * k * K2;
    return 20.0 * std::log10(std::exp(1.0)) * -std::log(1.0 - b) / (2.0 * k);
}

// The default batter (T = 3050 N/m) with sigma1 = 1e-3 m^2/s, which damps its own modes near
// 8 kHz within a few ms, on the grid of its stability bound, so that its band reaches Nyquist.
inline MembraneSpec bandBatter(double sampleRate_Hz)
{
    MembraneSpec s = makeDrumConfig(ParameterSet {}, sampleRate_Hz).batter;
    s.sigma1_m2_per_s = 1.0e-3;
    s.gridTension_N_per_m = 0.0;
    s.gridSigma1_m2_per_s = -1.0;
    s.gridCoarseness = 1.0;
    s.precision = HeadPrecision::double_precision; // embedded in the air box
    return s;
}

// Runs the struck batter in the box; returns the microphone's pressure (Pa), one value a step.
// The strike is impulsive: at rest, given a raised-cosine velocity of 5 mm radius (1 m/s at its
// centre) at 0.3 R from the centre, which reaches the head's whole band.
inline std::vector<double> runAirBand(const AirBandSetup& setup)
{
    const double k = 1.0 / setup.sampleRate_Hz;
    AirBoxSpec spec;
    spec.shell = false;
    spec.walls = AirWalls::absorbing;
    spec.sigma_m = setup.sigma_m;
    spec.gridSigma_m = setup.gridSigma_m;
    spec.size_m = setup.box_m;
    AirBox air(spec, k);
    Membrane head(bandBatter(setup.sampleRate_Hz), k);
    HeadEmbedding embed(air, head, 0.0);

    const CircularGrid& g = head.grid();
    const double x0 = 0.3 * g.radius(), a = 0.005;
    for (int level = 0; level < 2; ++level) // w^{n-1} = -k v, then w^n = 0
    {
        for (int iy = 0; iy < g.width(); ++iy)
            for (int ix = 0; ix < g.width(); ++ix)
            {
                const int i = g.index(ix, iy);
                const double r = std::hypot(g.x(ix) - x0, g.x(iy));
                if (g.mask()[(size_t) i] != 0.0 && r < a)
                {
                    const double c = std::cos(0.5 * std::numbers::pi * r / a);
                    head.setNextAt(i, level == 0 ? -k * c * c : 0.0);
                }
            }
        head.advance();
    }

    const auto steps = (size_t) std::lround(setup.seconds * setup.sampleRate_Hz);
    std::vector<double> p;
    p.reserve(steps);
    for (size_t n = 0; n < steps; ++n)
    {
        air.computeNext();
        head.computeFree();
        embed.step();
        p.push_back(air.pressure(setup.mic_m[0], setup.mic_m[1], setup.mic_m[2]));
        air.advance();
        head.advance();
    }
    return p;
}

// Short-time power spectra as the paper's Fig. 4: Hann window of 512 samples, 75 % overlap.
struct Frames
{
    static constexpr int window = 512, hop = 128;
    std::vector<std::vector<double>> power; // [frame][bin 0..256]
    double binHz = 0.0, frameSeconds = 0.0; // bin spacing; time between frames
    double centre(size_t frame) const { return frameSeconds * (double) frame + 0.5 * window * frameSeconds / hop; } // s
};

inline Frames stft(const std::vector<double>& x, double sampleRate_Hz)
{
    Frames F;
    F.binHz = sampleRate_Hz / Frames::window;
    F.frameSeconds = Frames::hop / sampleRate_Hz;
    Eigen::FFT<double> fft;
    std::vector<double> in(Frames::window);
    std::vector<std::complex<double>> out;
    for (size_t start = 0; start + Frames::window <= x.size(); start += Frames::hop)
    {
        for (int i = 0; i < Frames::window; ++i)
            in[(size_t) i] = x[start + (size_t) i] * 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * i / Frames::window));
        fft.fwd(out, in);
        std::vector<double> p(Frames::window / 2 + 1);
        for (size_t b = 0; b < p.size(); ++b)
            p[b] = std::norm(out[b]);
        F.power.push_back(std::move(p));
    }
    return F;
}

struct BandDecay
{
    double peak_Hz = 0.0;       // the band's peak (mean power over the fit's frames)
    double rate_dB_per_s = 0.0; // how fast the band's level falls (least squares over the frames)
    double level_dB = 0.0;      // the band's level at the fit's first frame, dB above the loudest frame's whole spectrum
};

// The strongest bin of the mean spectrum over frames centred in [t0, t1] within [fLo, fHi]
// (or `atHz` when given), the band +-2 bins around it, and the slope of its level over those frames.
inline BandDecay bandDecay(const Frames& F, double t0, double t1, double fLo, double fHi, double atHz = 0.0)
{
    std::vector<size_t> frames;
    for (size_t f = 0; f < F.power.size(); ++f)
        if (F.centre(f) >= t0 && F.centre(f) <= t1)
            frames.push_back(f);
    const size_t bins = F.power.front().size();
    size_t best = (size_t) std::lround(atHz / F.binHz);
    if (atHz <= 0.0)
    {
        std::vector<double> mean(bins, 0.0);
        for (size_t f : frames)
            for (size_t b = 0; b < bins; ++b)
                mean[b] += F.power[f][b];
        best = (size_t) std::ceil(fLo / F.binHz);
        for (size_t b = best; b <= (size_t) (fHi / F.binHz) && b < bins; ++b)
            if (mean[b] > mean[best])
                best = b;
    }
    double loudest = 0.0;
    for (const auto& p : F.power)
    {
        double s = 0.0;
        for (double v : p)
            s += v;
        loudest = std::max(loudest, s);
    }
    // least squares of the band's level (dB) against time
    double st = 0, sy = 0, stt = 0, sty = 0;
    const double n = (double) frames.size();
    BandDecay d;
    d.peak_Hz = (double) best * F.binHz;
    for (size_t f : frames)
    {
        double s = 0.0;
        for (size_t b = best - 2; b <= best + 2; ++b)
            s += F.power[f][b];
        const double t = F.centre(f), y = 10.0 * std::log10(s / loudest + 1e-300);
        if (f == frames.front())
            d.level_dB = y;
        st += t;
        sy += y;
        stt += t * t;
        sty += t * y;
    }
    d.rate_dB_per_s = -(n * sty - st * sy) / (n * stt - st * st);
    return d;
}

} // namespace snaresim::test
