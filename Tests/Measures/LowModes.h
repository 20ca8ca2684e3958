#pragma once
// The drum's lowest modes: the heads' (0,1) pair (in phase and anti-phase, from their swept
// volumes after a strike at the centre, ModePairs.h) and each head's (1,1) mode (from its first
// moment sum(x w) after a strike at 0.5 R on the x axis), their frequencies and decay rates. Shared by the
// outside air's tests and airbox_figures, so the reduced model and the air box are measured
// alike.

#include "ModePairs.h"
#include "SpectrumPeaks.h"
#include "TestDrums.h"

#include <vector>

namespace snaresim::test
{

struct Mode
{
    double frequency_Hz = 0.0;
    double decay_dB_per_s = 0.0;
};

struct LowModes
{
    Mode inPhase, antiPhase, batter11, carry11;
};

// Per step after a 2 m/s strike at (0.5 R, 0): each head's sum(w) and sum(x w) (x in units of R).
struct HeadMoments
{
    std::vector<double> vb, vc, xb, xc;
    double sampleRate_Hz = 0.0;
};

inline HeadMoments headMoments(const DrumConfig& cfg, int steps)
{
    Drum drum(cfg);
    drum.strike(2.0, 0.5, 0.0);
    HeadMoments m;
    m.sampleRate_Hz = cfg.sampleRate_Hz;
    auto sums = [](const Membrane& head, double& v, double& x) {
        const CircularGrid& g = head.grid();
        v = x = 0.0;
        for (int iy = 0; iy < g.width(); ++iy)
            for (int ix = 0; ix < g.width(); ++ix)
            {
                const double w = head.nowAt(g.index(ix, iy));
                v += w;
                x += w * g.x(ix) / g.radius();
            }
    };
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        double v, x;
        sums(drum.batter(), v, x);
        m.vb.push_back(v);
        m.xb.push_back(x);
        sums(drum.carry(), v, x);
        m.vc.push_back(v);
        m.xc.push_back(x);
    }
    return m;
}

// The strongest peak of x within [lo, hi] Hz and its decay.
inline Mode strongestMode(const std::vector<double>& x, double fs, double lo, double hi)
{
    const auto X = hannSpectrum(x, 8);
    const auto found = peaks(X, fs / (2.0 * (double) X.size()), lo, hi);
    if (found.empty())
        return {};
    const double f = found.front().frequency;
    return { f, bandDecay_dB_per_s(x, fs, f) };
}

// The (1,1) modes: the batter's is the strongest peak of its first moment (150-500 Hz); the
// carry head's the peak of its first moment (150-800 Hz, within 30 dB of its strongest) where
// it moves most against the batter (the strike drives the carry head's first moment at the
// batter's (1,1) frequency too, through the air).
inline void tiltModes(const HeadMoments& m, LowModes& out)
{
    const double fs = m.sampleRate_Hz;
    out.batter11 = strongestMode(m.xb, fs, 150.0, 500.0);
    const auto B = hannSpectrum(m.xb, 8), C = hannSpectrum(m.xc, 8);
    const auto found = peaks(C, fs / (2.0 * (double) C.size()), 150.0, 800.0);
    double best = -1e300, f = 0.0;
    for (const auto& p : found)
        if (p.logMagnitude > found.front().logMagnitude - std::log(1000.0 / 30.0) &&
            p.logMagnitude - std::log(std::abs(B[p.bin]) + 1e-300) > best)
        {
            best = p.logMagnitude - std::log(std::abs(B[p.bin]) + 1e-300);
            f = p.frequency;
        }
    out.carry11 = { f, f > 0.0 ? bandDecay_dB_per_s(m.xc, fs, f) : 0.0 };
}

// expected: where to look for the pair (ModePairs.h, measuredPairs), 0 for anywhere.
inline LowModes lowModes(const DrumConfig& cfg, int steps = 1 << 15, ModePair expected = {})
{
    LowModes out;
    const SweptVolumes v = sweptVolumes(cfg, steps);
    const ModePair pair = measuredPairs(v, expected);
    // a mode not found stays 0 Hz, 0 dB/s
    out.inPhase = { pair.inPhase, pair.inPhase > 0.0 ? modeDecay_dB_per_s(v, +1.0, pair.inPhase) : 0.0 };
    out.antiPhase = { pair.antiPhase, pair.antiPhase > 0.0 ? modeDecay_dB_per_s(v, -1.0, pair.antiPhase) : 0.0 };
    tiltModes(headMoments(cfg, steps), out);
    return out;
}

} // namespace snaresim::test
