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

// In-phase and anti-phase peaks of the two heads' swept volumes (snares off, lossless).
// cfg: the drum as given (the caller turns the snares off and the losses off).
inline ModePair measuredPairs(const DrumConfig& cfg, ModePair expected)
{
    Drum drum(cfg);
    drum.strike(2.0, 0.0, 0.0);
    std::vector<double> vb, vc;
    for (int n = 0; n < (1 << 15); ++n)
    {
        drum.step();
        double b = 0.0, c = 0.0;
        for (double w : drum.batter().displacement())
            b += w;
        for (double w : drum.carry().displacement())
            c += w;
        vb.push_back(b);
        vc.push_back(c);
    }
    const auto B = hannSpectrum(vb), C = hannSpectrum(vc);
    const double binHz = cfg.sampleRate_Hz / (2.0 * (double) B.size());
    // In-phase modes show in the sum of the swept volumes, anti-phase ones in the difference
    // (the cavity's dV). The peak taken is the strongest within 5 % of `near`, within 60 dB of
    // the spectrum's strongest, whose batter/carry cross-spectrum has the matching phase;
    // with no `near`, the strongest such peak within 30 dB.
    auto find = [&](double sign, double near) {
        std::vector<std::complex<double>> X(B.size());
        for (size_t i = 0; i < B.size(); ++i)
            X[i] = B[i] + sign * C[i];
        auto found = peaks(X, binHz, 100.0, 1000.0);
        if (found.empty())
            return 0.0;
        const double floor = found.front().logMagnitude - std::log(near > 0.0 ? 1000.0 : 30.0);
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


} // namespace snaresim::test
