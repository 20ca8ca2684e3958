#pragma once
// The paper's section 5.2 (7 wires, a mallet of M = 0.028 kg at 5 m/s, lossless, the Newton
// solve, grids at the bound): when the wires swing down and come back to the carry head, in
// the first 25 ms. Shared by the air-box tests and the figure program (AirFigures.cpp).

#include "Drum.h"

#include <cmath>

namespace snaresim::test
{

struct SnareTimes
{
    double lowest_ms = 0.0, lowestMean_mm = 0.0;       // the wires' mean at its lowest (first 25 ms)
    double swingLowest_ms = 0.0, swingLowest_mm = 0.0; // the same in the first swing (before back_ms)
    double left_ms = 0.0;                              // every point has left the head (after the first contact)
    double back_ms = 0.0;                              // first contact after every point has left the head (after the first contact)
    double clean_ms = 0.0;                             // first contact after at least 1 ms with none (after the first contact)
    double carryLowest_ms = 0.0, carryLowest_mm = 0.0; // the carry head's mean under the wires at its lowest
    int points = 0;
};

// The run's drum, as the renderer's options of docs/MODEL.md make it (p: other parameters).
inline DrumConfig section52Config(AirModel model, ParameterSet p = {})
{
    p.set(ParamId::snareCount, 7.0);
    p.set(ParamId::strikeSpeedMax, 5.0);
    p.set(ParamId::malletMass, 0.028);
    p.set(ParamId::bandwidth, qualityBandwidth_Hz(1.0));
    p.set(ParamId::snareSolver, 1.0);
    p.set(ParamId::headPrecision, 0.0); // the reference: energy to double round-off
    DrumConfig cfg = makeDrumConfig(p, 44100.0).lossless();
    cfg.cavity.model = model;
    return cfg;
}

inline SnareTimes section52(const DrumConfig& cfg)
{
    Drum drum(cfg);
    drum.playNote(38, 127); // as the renderer's --hit 0:127: the main strike at strike_speed_max
    const auto& wires = drum.snareWires();
    const int M = wires.intervals();
    SnareTimes t;
    t.points = wires.count() * (M - 1);
    // the carry head's nodes under the wires' nodes
    std::vector<int> under;
    for (int i = 0; i < wires.count(); ++i)
        for (int l = 0; l <= M; ++l)
            under.push_back(drum.carry().grid().nearestInterior(wires.nodeX(l), wires.wireY(i)));
    double lowest = 0.0, carryLowest = 0.0;
    bool touched = false, left = false;
    int quietSteps = 0;
    const int steps = (int) std::lround(0.025 * cfg.sampleRate_Hz);
    for (int n = 1; n <= steps; ++n)
    {
        drum.step();
        const double ms = 1e3 * n / cfg.sampleRate_Hz;
        double mean = 0.0, carry = 0.0;
        for (size_t j = 0; j < under.size(); ++j)
        {
            mean += wires.uNow[j];
            carry += drum.carry().nowAt(under[j]);
        }
        mean /= (double) under.size();
        carry /= (double) under.size();
        if (mean < lowest)
        {
            lowest = mean;
            t.lowest_ms = ms;
            if (t.back_ms == 0.0)
            {
                t.swingLowest_ms = ms;
                t.swingLowest_mm = 1e3 * mean;
            }
        }
        if (carry < carryLowest)
        {
            carryLowest = carry;
            t.carryLowest_ms = ms;
        }
        const int touching = drum.solverStats().snareContacts;
        if (touching == 0)
        {
            if (touched && ! left)
                t.left_ms = ms;
            left = left || touched;
            quietSteps += touched ? 1 : 0;
        }
        else
        {
            touched = true;
            if (left && t.back_ms == 0.0)
                t.back_ms = ms;
            if (quietSteps >= 0.001 * cfg.sampleRate_Hz && t.clean_ms == 0.0)
                t.clean_ms = ms;
            quietSteps = 0;
        }
    }
    t.lowestMean_mm = 1e3 * lowest;
    t.carryLowest_mm = 1e3 * carryLowest;
    return t;
}

} // namespace snaresim::test
