#pragma once
// --energy-plot: a picture like Fig. 2 of Torin, Hamilton & Bilbao (DAFx-14), two panels
// against time in ms:
//   left:  (h^n - h^0) / h^0, h^n = the energy balance (EnergyLedger::balance(), so that
//          strikes and retrieved mallets do not show as jumps) and h^0 = the total energy
//          right after the first strike (the deviation is taken from the balance there);
//   right: the energy of each component (batter, carry, mallets, snares, cavity) and the total.
// Fed with the ledger of every sample while rendering; keeps the minimum and maximum of
// each series per time bucket (at most a few thousand), so any render length fits.

#include "EnergyLedger.h"

#include <juce_graphics/juce_graphics.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace snaresim::render
{

class EnergyPlot
{
public:
    static constexpr int width = 1400;
    static constexpr int height = 600;

    // firstStrikeSample: the sample of the first strike played (none: no reference h^0).
    EnergyPlot(std::int64_t numSamples, double sampleRate_Hz, std::optional<std::int64_t> firstStrikeSample);

    // rows[i] is the ledger after sample firstSample + i.
    void add(std::int64_t firstSample, std::span<const EnergyLedger> rows);

    juce::Image draw() const;

private:
    enum Series
    {
        balance,
        batter,
        carry,
        mallets,
        snares,
        cavity,
        total,
        numSeries
    };

    struct Bucket
    {
        double min = 0.0, max = 0.0;
        std::int64_t minAt = 0, maxAt = 0;
        bool filled = false;
    };

    void drawBalancePanel(juce::Graphics& g, juce::Rectangle<float> area) const;
    void drawComponentPanel(juce::Graphics& g, juce::Rectangle<float> area, juce::Rectangle<float> legend) const;

    std::int64_t samples;
    double sampleRate;
    std::optional<std::int64_t> firstStrike;
    std::vector<std::array<Bucket, numSeries>> buckets;

    bool haveReference = false;
    double referenceTotal = 0.0;   // h^0
    double referenceBalance = 0.0; // the balance at the same sample
    std::int64_t referenceSample = 0;
    std::int64_t nonfiniteRows = 0;
};

} // namespace snaresim::render
