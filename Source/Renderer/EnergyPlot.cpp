#include "EnergyPlot.h"

#include "Formatted.h"
#include "Plotting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>

namespace snaresim::render
{
namespace
{

constexpr std::int64_t kMaxBuckets = 4000;             // about 7 per pixel column of a panel
constexpr int kDecades = EnergyPlot::componentDecades; // shown by the component panel

struct SeriesStyle
{
    juce::Colour colour;
    float thickness;
};

// The balance (left panel) and the total; the ledger's terms take the palette's colours in order.
const SeriesStyle kBalanceStyle { juce::Colour(0xff1f4e9c), 1.5f };
const SeriesStyle kTotalStyle { juce::Colour(0xff000000), 2.2f };
const juce::Colour kTermColours[] = { juce::Colour(0xff1f77b4), juce::Colour(0xffff7f0e), juce::Colour(0xff2ca02c),
                                      juce::Colour(0xffd62728), juce::Colour(0xff9467bd), juce::Colour(0xff8c564b),
                                      juce::Colour(0xffe377c2), juce::Colour(0xff7f7f7f), juce::Colour(0xffbcbd22),
                                      juce::Colour(0xff17becf) };
constexpr float kTermThickness = 1.6f;

} // namespace

EnergyPlot::EnergyPlot(std::int64_t numSamples, double sampleRate_Hz, std::optional<std::int64_t> firstStrikeSample,
                       const EnergyLedger& layout)
    : samples(std::max<std::int64_t>(numSamples, 1)), sampleRate(sampleRate_Hz), firstStrike(firstStrikeSample)
{
    for (const auto& term : layout.terms())
        termNames.push_back(term.name);
    numBuckets = (std::size_t) std::min(samples, kMaxBuckets);
    buckets.resize(numBuckets * (std::size_t) numSeries());
    values.resize((std::size_t) numSeries());
}

void EnergyPlot::add(std::int64_t firstSample, std::span<const EnergyLedger> rows)
{
    const auto bucketCount = (std::int64_t) numBuckets;
    for (std::size_t i = 0; i < rows.size(); ++i)
    {
        const auto n = firstSample + (std::int64_t) i;
        const auto& e = rows[i];
        values[balance] = e.balance();
        for (int t = 0; t < (int) termNames.size(); ++t)
            values[(std::size_t)(firstTerm + t)] = e[t];
        values[(std::size_t) total()] = e.total();
        if (! std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); }))
        {
            ++nonfiniteRows;
            continue;
        }

        // h^0: the total right after the first strike (its first row holding energy).
        if (! haveReference && firstStrike && n >= *firstStrike && values[(std::size_t) total()] > 0.0)
        {
            haveReference = true;
            referenceTotal = values[(std::size_t) total()];
            referenceBalance = values[balance];
            referenceSample = n;
        }

        const auto index = (std::size_t) std::clamp<std::int64_t>(n * bucketCount / samples, 0, bucketCount - 1);
        for (int s = 0; s < numSeries(); ++s)
        {
            auto& b = bucketAt(index, s);
            const double v = values[(std::size_t) s];
            if (! b.filled)
            {
                b = { v, v, n, n, true };
                continue;
            }
            if (v < b.min)
            {
                b.min = v;
                b.minAt = n;
            }
            if (v > b.max)
            {
                b.max = v;
                b.maxAt = n;
            }
        }
    }
}

juce::Image EnergyPlot::draw() const
{
    auto image = plot::whiteImage(width, height);
    juce::Graphics g(image);

    drawBalancePanel(g, balanceArea());
    drawComponentPanel(g, componentArea(), { 1248.0f, 50.0f, 140.0f, 0.0f });
    return image;
}

void EnergyPlot::drawBalancePanel(juce::Graphics& g, juce::Rectangle<float> area) const
{
    const double durationMs = (double) samples / sampleRate * 1000.0;

    // The curve, in (time ms, value) points: per bucket its minimum and maximum in time order.
    std::vector<juce::Point<double>> points;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    if (haveReference)
        for (std::size_t index = 0; index < numBuckets; ++index)
        {
            const auto& b = bucketAt(index, balance);
            if (! b.filled)
                continue;
            auto variation = [&](double h) { return (h - referenceBalance) / referenceTotal; };
            auto point = [&](std::int64_t at, double h) {
                points.push_back({ (double) at / sampleRate * 1000.0, variation(h) });
                lo = std::min(lo, points.back().y);
                hi = std::max(hi, points.back().y);
            };
            if (b.minAt <= b.maxAt)
            {
                point(b.minAt, b.min);
                if (b.maxAt != b.minAt)
                    point(b.maxAt, b.max);
            }
            else
            {
                point(b.maxAt, b.max);
                point(b.minAt, b.min);
            }
        }

    // A symmetric range around 0 when the curve stays within round-off of it; else the data's.
    if (points.empty())
        lo = -1.0e-15, hi = 1.0e-15;
    else
        std::tie(lo, hi) = balanceRange(lo, hi);

    plot::Axes axes { area, 0.0, durationMs, lo, hi };
    const auto xTicks = plot::niceTicks(0.0, durationMs, 8);
    const auto yTicks = plot::niceTicks(lo, hi, 8);
    const double xStep = plot::tickStep(xTicks);
    plot::drawAxes(
        g, axes, plot::labelled(xTicks, [&](double v) { return plot::decimalLabel(v, xStep); }), plot::scientificTicks(yTicks),
        { "Normalised variation of the energy balance", "time (ms)", "(h\xe2\x81\xbf \xe2\x88\x92 h\xe2\x81\xb0) / h\xe2\x81\xb0" });

    juce::Graphics::ScopedSaveState state(g);
    g.reduceClipRegion(area.toNearestInt());

    if (! haveReference)
    {
        g.setColour(juce::Colours::darkgrey);
        g.setFont(plot::font(17.0f));
        g.drawText(plot::toJuce(nonfiniteRows > 0 ? "the energy went non-finite" : "no strike played: h\xe2\x81\xb0 is undefined"), area,
                   juce::Justification::centred, false);
        return;
    }

    juce::Path path;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        const juce::Point<float> p { axes.xToPixel(points[i].x), axes.yToPixel(points[i].y) };
        if (i == 0)
            path.startNewSubPath(p);
        else
            path.lineTo(p);
    }
    if (points.size() == 1)
        path.lineTo(path.getCurrentPosition().translated(1.0f, 0.0f));
    g.setColour(kBalanceStyle.colour);
    g.strokePath(path, juce::PathStrokeType(kBalanceStyle.thickness));

    // What h^0 is.
    g.setFont(plot::font(15.0f));
    g.setColour(juce::Colour(0xff404040));
    const auto note = "h\xe2\x81\xb0 = " + formatted("%.4g", referenceTotal) + " J at " +
                      formatted("%.3f", (double) referenceSample / sampleRate * 1000.0) + " ms (after the first strike)" +
                      (nonfiniteRows > 0 ? "; non-finite rows skipped" : "");
    g.drawText(plot::toJuce(note), area.reduced(8.0f).withHeight(20.0f), juce::Justification::topLeft, false);
}

void EnergyPlot::drawComponentPanel(juce::Graphics& g, juce::Rectangle<float> area, juce::Rectangle<float> legend) const
{
    const double durationMs = (double) samples / sampleRate * 1000.0;
    auto styleOf = [&](int s) {
        if (s == total())
            return kTotalStyle;
        return SeriesStyle { kTermColours[(std::size_t)(s - firstTerm) % std::size(kTermColours)], kTermThickness };
    };

    // Logarithmic, kDecades below the decade above the largest energy: the strike's energy
    // (mostly the mallet's, which leaves with it) and the drum's ringing, orders of magnitude
    // smaller, both stay readable. Zero or negative values run off the bottom.
    double largest = 0.0;
    for (std::size_t index = 0; index < numBuckets; ++index)
        for (int s = firstTerm; s <= total(); ++s)
            if (const auto& b = bucketAt(index, s); b.filled)
                largest = std::max(largest, b.max);
    const double hi = componentTop(largest);
    const double lo = hi * std::pow(10.0, -kDecades);

    plot::Axes axes { area, 0.0, durationMs, lo, hi, false, true };
    const auto xTicks = plot::niceTicks(0.0, durationMs, 7);
    const double xStep = plot::tickStep(xTicks);
    std::vector<plot::Tick> yTicks;
    for (int d = 0; d <= kDecades; ++d)
    {
        const double decade = lo * std::pow(10.0, d);
        const int exponent = (int) std::lround(std::log10(decade));
        char label[32];
        if (exponent >= -3 && exponent <= 3)
            std::snprintf(label, sizeof label, "%.*f", std::max(0, -exponent), decade);
        else
            std::snprintf(label, sizeof label, "1e%d", exponent);
        yTicks.push_back({ decade, label, true });
        for (int m = 2; m <= 9 && d < kDecades; ++m)
            yTicks.push_back({ m * decade, "", false });
    }
    plot::drawAxes(g, axes, plot::labelled(xTicks, [&](double v) { return plot::decimalLabel(v, xStep); }), yTicks,
                   { "Energy of the components (upper envelope)", "time (ms)", "energy (J), logarithmic" });

    {
        juce::Graphics::ScopedSaveState state(g);
        g.reduceClipRegion(area.toNearestInt());
        for (int s = firstTerm; s <= total(); ++s)
        {
            // One point per pixel column: the largest value in it (the upper envelope, so
            // that an energy swinging through zero, such as the cavity's, reads as a line).
            const int columns = (int) area.getWidth();
            std::vector<double> peak((std::size_t) columns, -std::numeric_limits<double>::infinity());
            for (std::size_t index = 0; index < numBuckets; ++index)
            {
                const auto& b = bucketAt(index, s);
                if (! b.filled)
                    continue;
                const int column = std::clamp((int) ((double) b.maxAt / (double) samples * columns), 0, columns - 1);
                peak[(std::size_t) column] = std::max(peak[(std::size_t) column], b.max);
            }

            juce::Path path;
            bool started = false;
            for (int column = 0; column < columns; ++column)
            {
                const double v = peak[(std::size_t) column];
                if (v == -std::numeric_limits<double>::infinity())
                    continue;
                const juce::Point<float> p { area.getX() + (float) column + 0.5f, axes.yToPixel(std::max(v, lo * 1.0e-3)) };
                if (started)
                    path.lineTo(p);
                else
                    path.startNewSubPath(p);
                started = true;
            }
            if (! started)
                continue;
            const auto style = styleOf(s);
            g.setColour(style.colour);
            g.strokePath(path, juce::PathStrokeType(style.thickness));
        }
    }

    // The legend, beside the panel.
    const float rowHeight = 24.0f;
    auto box = legend.withHeight(rowHeight * (float) (total() - firstTerm + 1) + 12.0f);
    g.setColour(juce::Colours::white);
    g.fillRect(box);
    g.setColour(juce::Colour(0xffb0b0b0));
    g.drawRect(box, 1.0f);
    g.setFont(plot::font(15.0f));
    float y = box.getY() + 6.0f + rowHeight / 2.0f;
    for (int s = firstTerm; s <= total(); ++s, y += rowHeight)
    {
        // A term that never held energy (snares off, no cavity) stays off the scale.
        bool everPositive = false;
        for (std::size_t index = 0; index < numBuckets; ++index)
            everPositive = everPositive || (bucketAt(index, s).filled && bucketAt(index, s).max > 0.0);
        const auto name =
            (s == total() ? std::string("total") : std::string(termNames[(std::size_t)(s - firstTerm)])) + (everPositive ? "" : " = 0");

        const auto style = styleOf(s);
        g.setColour(style.colour);
        g.drawLine(box.getX() + 10.0f, y, box.getX() + 40.0f, y, style.thickness + 0.8f);
        g.setColour(juce::Colour(0xff202020));
        g.drawText(name, juce::Rectangle<float>(box.getX() + 48.0f, y - 10.0f, box.getWidth() - 52.0f, 20.0f),
                   juce::Justification::centredLeft, false);
    }
}

} // namespace snaresim::render
