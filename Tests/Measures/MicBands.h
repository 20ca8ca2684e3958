#pragma once
// The drum's three microphones after a 3 m/s strike at 0.3 R, heard as the drum gives them and
// as the radiation model gives them on the drum's own heads, and octave-band levels of the first
// 300 ms: shared by the microphones' test (PressureMicrophoneTests.cpp) and airbox_figures.
#include "Drum.h"
#include "Membrane.h"
#include "TestDrums.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

namespace snaresim::test
{
inline constexpr std::array<double, 6> kOctaves { 125.0, 250.0, 500.0, 1000.0, 2000.0, 4000.0 };
using Levels = std::array<double, kOctaves.size()>;

// Energy of x in each octave band (edges f / sqrt 2, f sqrt 2), in dB (Parseval on the whole
// record, zero-padded to a power of two).
inline Levels octaveLevels(const std::vector<double>& x, double fs)
{
    size_t n = 1;
    while (n < 2 * x.size())
        n *= 2;
    std::vector<double> padded(n, 0.0);
    std::copy(x.begin(), x.end(), padded.begin());
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> X;
    fft.fwd(X, padded);
    Levels out {};
    for (size_t b = 0; b < kOctaves.size(); ++b)
    {
        const double lo = kOctaves[b] / std::sqrt(2.0), hi = kOctaves[b] * std::sqrt(2.0);
        double e = 1e-300;
        for (size_t i = (size_t) std::ceil(lo * (double) n / fs); i <= (size_t) (hi * (double) n / fs); ++i)
            e += std::norm(X[i]);
        out[b] = 10.0 * std::log10(e);
    }
    return out;
}

struct Recording
{
    std::array<std::vector<double>, 3> drum;  // the drum's microphones (MicSignals)
    std::array<std::vector<double>, 3> model; // PressureMicrophones on the drum's own heads
    std::array<std::vector<double>, 3> plane; // rho_a c times the head's velocity under each microphone
};

inline Recording record(const DrumConfig& cfg, int samples)
{
    Drum drum(cfg);
    drum.strike(3.0, 0.3, 0.0);
    Recording r;
    // the point of the facing head under each microphone (the room mic's: the batter's nearest)
    const double R = cfg.batter.radius_m, rhoC = cfg.cavity.airDensity_kg_per_m3 * cfg.cavity.soundSpeed_m_per_s;
    std::array<GridDistribution, 3> under;
    const AirPoint* points[3] = { &cfg.mics.top, &cfg.mics.bottom, &cfg.mics.room };
    for (int m = 0; m < 3; ++m)
    {
        const Membrane& head = m == 1 ? drum.carry() : drum.batter();
        double x = points[m]->x_m, y = points[m]->y_m;
        const double r = std::hypot(x, y);
        if (r > 0.9 * R)
            x *= 0.9 * R / r, y *= 0.9 * R / r;
        under[(size_t) m].reserve(4);
        head.grid().makeDistribution(x, y, 0.0, under[(size_t) m]);
    }
    for (int n = 0; n < samples; ++n)
    {
        drum.step();
        const MicSignals& s = drum.lastSignals();
        r.drum[0].push_back(s.top_Pa);
        r.drum[1].push_back(s.bottom_Pa);
        r.drum[2].push_back(s.room_Pa);
        for (int m = 0; m < 3; ++m)
        {
            r.model[(size_t) m].push_back(drum.microphones().pressure((PressureMicrophones::Position) m));
            const Membrane& head = m == 1 ? drum.carry() : drum.batter();
            const double v = (head.sampleNext(under[(size_t) m]) - head.sampleNow(under[(size_t) m])) * cfg.sampleRate_Hz;
            r.plane[(size_t) m].push_back((m == 1 ? -rhoC : rhoC) * v);
        }
    }
    return r;
}

// The test drum: snares off (no chaos: one render stands for all), a room mic 0.35 m from the
// batter's centre at 45 degrees, inside a 1.3 m box with absorbing walls (a smaller box's walls
// move the room mic's lowest band by a decibel or more).
inline DrumConfig micDrum()
{
    DrumConfig cfg = test::wholeDrum();
    cfg.snares.engaged = false;
    const double H = cfg.cavity.shellDepth_m, d = 0.35;
    cfg.mics.room = { d * std::sqrt(0.5), 0.0, 0.5 * H + d * std::sqrt(0.5) };
    return cfg;
}

// cfg with its heads on the grids of `reference`'s (the same spacing): the air's kinetic reserves
// widen a drum's grids, and a chattering stick hears the difference.
inline DrumConfig onGridsOf(DrumConfig cfg, const DrumConfig& reference)
{
    const DrumConfig before = cfg;
    for (const bool batter : { true, false })
    {
        MembraneSpec& head = batter ? cfg.batter : cfg.carry;
        head.gridCoarseness *= Membrane::gridSpacing(batter ? reference.batter : reference.carry, 1.0 / reference.sampleRate_Hz,
                                                     reference.kineticReserve(batter)) /
                               Membrane::gridSpacing(head, 1.0 / before.sampleRate_Hz, before.kineticReserve(batter));
    }
    return cfg;
}

inline DrumConfig inBox(DrumConfig cfg)
{
    cfg.cavity.model = AirModel::airbox;
    cfg.airBox.walls = AirWalls::absorbing;
    cfg.airBox.size_m = { 1.3, 1.3, 1.3 };
    cfg.airBox.threads = 2;
    return cfg;
}

inline const char* const kNames[3] = { "top", "bottom", "room" };

// Largest |level difference| over the bands up to upTo_Hz (all by default), each band printed
// to out (none: nullptr).
inline double worstDifference(const char* what, const std::array<std::vector<double>, 3>& a, const std::array<std::vector<double>, 3>& b,
                              double fs, double upTo_Hz = kOctaves.back(), std::FILE* out = nullptr)
{
    double worst = 0.0;
    for (int m = 0; m < 3; ++m)
    {
        const Levels la = octaveLevels(a[(size_t) m], fs), lb = octaveLevels(b[(size_t) m], fs);
        if (out)
            std::fprintf(out, "%s, %s mic, dB against the air box:", what, kNames[m]);
        for (size_t i = 0; i < la.size(); ++i)
        {
            if (out)
                std::fprintf(out, " %+.1f", la[i] - lb[i]);
            if (kOctaves[i] <= upTo_Hz)
                worst = std::max(worst, std::abs(la[i] - lb[i]));
        }
        if (out)
            std::fprintf(out, "\n");
    }
    return worst;
}
} // namespace snaresim::test
