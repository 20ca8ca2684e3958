#pragma once
// --energy-plot: a picture like Fig. 2 of Torin, Hamilton & Bilbao (DAFx-14), two panels
// against time in ms:
//   left:  (h^n - h^0) / h^0, h^n = the energy balance (EnergyLedger::balance(), so that
//          strikes and retrieved mallets do not show as jumps) and h^0 = the total energy
//          right after the first strike (the deviation is taken from the balance there);
//   right: each term of the ledger (the default drum's: batter, carry, mallets, snares,
//          cavity, outside) and the total, the legend naming them as the ledger does.
// Fed with the ledger of every sample while rendering; keeps the minimum and maximum of
// each series per time bucket (at most a few thousand), so any render length fits.

#include "EnergyLedger.h"

#include <juce_graphics/juce_graphics.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

namespace snaresim::render
{

class EnergyPlot
{
public:
    static constexpr int width = 1400;
    static constexpr int height = 600;

    // firstStrikeSample: the sample of the first strike played (none: no reference h^0).
    // layout: a ledger with the terms the rows will have (the drum's energy()).
    EnergyPlot(std::int64_t numSamples, double sampleRate_Hz, std::optional<std::int64_t> firstStrikeSample, const EnergyLedger& layout);

    // rows[i] is the ledger after sample firstSample + i (with the terms of the layout).
    void add(std::int64_t firstSample, std::span<const EnergyLedger> rows);

    juce::Image draw() const;

    // Layout, in pixels: the plot areas of the left (balance) and right (component) panels.
    static juce::Rectangle<float> balanceArea() { return { 120.0f, 50.0f, 530.0f, 470.0f }; }
    static juce::Rectangle<float> componentArea() { return { 790.0f, 50.0f, 440.0f, 470.0f }; }

    // The balance panel's y range for a curve from lo to hi (its lowest and highest values):
    // centred on 0 when the curve stays within round-off of it, then widened by 8 % of the span
    // on each side, so the curve's extremes lie 8 / 116 of the height inside the frame.
    static std::pair<double, double> balanceRange(double lo, double hi)
    {
        const double extent = std::max({ std::abs(lo), std::abs(hi), 1.0e-17 });
        if (lo >= -0.25 * extent && hi <= 0.25 * extent) // hardly any spread: centre it
            lo = -extent, hi = extent;
        const double pad = 0.08 * std::max(hi - lo, extent);
        return { lo - pad, hi + pad };
    }

    // The component panel's y range, logarithmic: from the decade above 1.05 times the largest
    // energy plotted, componentDecades decades down.
    static constexpr int componentDecades = 7;
    static double componentTop(double largest) { return largest > 0.0 ? std::pow(10.0, std::ceil(std::log10(largest * 1.05))) : 1.0; }

private:
    // Series: the balance (left panel), then the ledger's terms, then the total.
    static constexpr int balance = 0, firstTerm = 1;
    int lastTerm() const { return (int) termNames.size(); }
    int total() const { return lastTerm() + 1; }
    int numSeries() const { return lastTerm() + 2; }

    struct Bucket
    {
        double min = 0.0, max = 0.0;
        std::int64_t minAt = 0, maxAt = 0;
        bool filled = false;
    };

    void drawBalancePanel(juce::Graphics& g, juce::Rectangle<float> area) const;
    void drawComponentPanel(juce::Graphics& g, juce::Rectangle<float> area, juce::Rectangle<float> legend) const;

    Bucket& bucketAt(std::size_t index, int series) { return buckets[index * (std::size_t) numSeries() + (std::size_t) series]; }
    const Bucket& bucketAt(std::size_t index, int series) const
    {
        return buckets[index * (std::size_t) numSeries() + (std::size_t) series];
    }

    std::int64_t samples;
    double sampleRate;
    std::optional<std::int64_t> firstStrike;
    std::vector<std::string_view> termNames;
    std::size_t numBuckets;
    std::vector<Bucket> buckets; // numBuckets x numSeries()
    std::vector<double> values;  // one row's series (scratch)

    bool haveReference = false;
    double referenceTotal = 0.0;   // h^0
    double referenceBalance = 0.0; // the balance at the same sample
    std::int64_t referenceSample = 0;
    std::int64_t nonfiniteRows = 0;
};

} // namespace snaresim::render
