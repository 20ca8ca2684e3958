#pragma once
// The heads' in-phase and anti-phase mode pair, measured from a struck drum (shared by the
// cavity and air-box tests).

#include "SpectrumPeaks.h"
#include "TestDrums.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace snaresim::test
{

struct ModePair
{
    double inPhase = 0.0, antiPhase = 0.0;
};

// The sums of each head's displacements (its swept volume / h^2), one value a step, after a
// 2 m/s strike at the centre: the heads' axisymmetric modes only.
struct SweptVolumes
{
    std::vector<double> batter, carry;
    double sampleRate_Hz = 0.0;
};

inline SweptVolumes sweptVolumes(const DrumConfig& cfg, int steps = 1 << 15)
{
    Drum drum(cfg);
    drum.strike(2.0, 0.0, 0.0);
    SweptVolumes v;
    v.sampleRate_Hz = cfg.sampleRate_Hz;
    for (int n = 0; n < steps; ++n)
    {
        drum.step();
        double b = 0.0, c = 0.0;
        for (int i = 0; i < drum.batter().grid().numNodes(); ++i)
            b += drum.batter().nowAt(i);
        for (int i = 0; i < drum.carry().grid().numNodes(); ++i)
            c += drum.carry().nowAt(i);
        v.batter.push_back(b);
        v.carry.push_back(c);
    }
    return v;
}

// In-phase and anti-phase peaks of the two heads' swept volumes.
inline ModePair measuredPairs(const SweptVolumes& v, ModePair expected)
{
    const std::vector<double>& vb = v.batter;
    const std::vector<double>& vc = v.carry;
    const auto B = hannSpectrum(vb), C = hannSpectrum(vc);
    const double binHz = v.sampleRate_Hz / (2.0 * (double) B.size());
    // In-phase modes show in the sum of the swept volumes, anti-phase ones in the difference
    // (the cavity's dV). The peak taken is the strongest within 5 % of `near`, within 80 dB of
    // the spectrum's strongest, whose batter/carry cross-spectrum has the matching phase;
    // with no `near`, the strongest such peak within 30 dB.
    auto find = [&](double sign, double near) {
        std::vector<std::complex<double>> X(B.size());
        for (size_t i = 0; i < B.size(); ++i)
            X[i] = B[i] + sign * C[i];
        auto found = peaks(X, binHz, 100.0, 1000.0);
        if (found.empty())
            return 0.0;
        const double floor = found.front().logMagnitude - std::log(near > 0.0 ? 1e4 : 30.0);
        for (const auto& p : found) // strongest first
        {
            const double phase = std::abs(std::arg(B[p.bin] * std::conj(C[p.bin])));
            const bool matches = sign > 0 ? phase < 0.5 * std::numbers::pi : phase > 0.5 * std::numbers::pi;
            const bool bothMove = std::abs(C[p.bin]) > 1e-3 * std::abs(B[p.bin]);
            const bool inWindow = near > 0.0 ? std::abs(p.frequency - near) < 0.05 * near : true;
            if (p.logMagnitude >= floor && matches && (sign > 0 || bothMove) && inWindow)
                return p.frequency;
        }
        return 0.0;
    };
    ModePair pair { find(+1.0, expected.inPhase), find(-1.0, expected.antiPhase) };
    return pair;
}

// The same, of a drum: cfg as given (the caller turns the snares off and the losses off).
inline ModePair measuredPairs(const DrumConfig& cfg, ModePair expected) { return measuredPairs(sweptVolumes(cfg), expected); }

// How fast a mode fades (dB/s), from the sum (sign +1, in-phase) or difference (-1,
// anti-phase) of the two sums (SpectrumPeaks.h, bandDecay_dB_per_s).
inline double modeDecay_dB_per_s(const SweptVolumes& v, double sign, double f_Hz)
{
    std::vector<double> x(v.batter.size());
    for (size_t i = 0; i < x.size(); ++i)
        x[i] = v.batter[i] + sign * v.carry[i];
    return bandDecay_dB_per_s(x, v.sampleRate_Hz, f_Hz);
}

} // namespace snaresim::test
