#include "SnarePlot.h"

#include "Formatted.h"
#include "Plotting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace snaresim::render
{
namespace
{

const juce::Colour kBand { 0xfff4c2c2 };     // wires: minimum to maximum
const juce::Colour kWireMean { 0xffb2182b }; // wires: mean
const juce::Colour kCarry { 0xff1f4e9c };    // carry head under the wires
const juce::Colour kContactFill { 0xffc6dbef };
const juce::Colour kContactLine { 0xff08519c };
const juce::Colour kNote { 0xff404040 };

constexpr float kWireMeanThickness = 2.4f;
constexpr float kCarryThickness = 1.5f;

// A signed number with a typographic minus sign.
std::string signedText(const char* format, double value)
{
    const auto text = formatted(format, std::abs(value));
    return (value < 0.0 && text.find_first_not_of("0.") != std::string::npos ? "\xe2\x88\x92" : "") + text;
}

// Time ticks: a grid line about every 30 px, labels on the multiples of a coarser round step
// (about every 120 px), so that times can be read to a grid step without crowded labels.
std::vector<plot::Tick> timeTicks(double durationMs, float pixels)
{
    const auto fine = plot::niceTicks(0.0, durationMs, std::max(2, (int) (pixels / 30.0f)));
    const double coarseStep = plot::tickStep(plot::niceTicks(0.0, durationMs, std::max(2, (int) (pixels / 120.0f))));
    std::vector<plot::Tick> ticks;
    for (const double v : fine)
    {
        const double q = coarseStep > 0.0 ? v / coarseStep : 0.0;
        const bool labelled = coarseStep <= 0.0 || std::abs(q - std::round(q)) < 1.0e-6;
        ticks.push_back({ v, labelled ? plot::decimalLabel(v, coarseStep) : "", true });
    }
    return ticks;
}

// A legend row: a sample of the style at (x, y) and up to two lines of text beside it.
enum class Swatch
{
    line,
    thinLine,
    band,
    fill
};

float legendRow(juce::Graphics& g, float x, float y, float width, Swatch swatch, juce::Colour colour, const std::string& text, int lines)
{
    const float rowHeight = lines > 1 ? 40.0f : 24.0f;
    const float cy = y + rowHeight / 2.0f;
    switch (swatch)
    {
        case Swatch::line:
            g.setColour(colour);
            g.drawLine(x + 10.0f, cy, x + 40.0f, cy, kWireMeanThickness + 0.6f);
            break;
        case Swatch::thinLine:
            g.setColour(colour);
            g.drawLine(x + 10.0f, cy, x + 40.0f, cy, kCarryThickness + 0.6f);
            break;
        case Swatch::band:
            g.setColour(colour);
            g.fillRect(juce::Rectangle<float>(x + 10.0f, cy - 7.0f, 30.0f, 14.0f));
            break;
        case Swatch::fill:
            g.setColour(kContactFill);
            g.fillRect(juce::Rectangle<float>(x + 10.0f, cy - 7.0f, 30.0f, 14.0f));
            g.setColour(colour);
            g.drawLine(x + 10.0f, cy - 7.0f, x + 40.0f, cy - 7.0f, 1.6f);
            break;
    }
    g.setColour(juce::Colour(0xff202020));
    g.setFont(plot::font(15.0f));
    g.drawFittedText(plot::toJuce(text), juce::Rectangle<float>(x + 48.0f, y, width - 52.0f, rowHeight).toNearestInt(),
                     juce::Justification::centredLeft, lines, 1.0f);
    return rowHeight;
}

} // namespace

SnarePlot::SnarePlot(const Drum& drum, std::int64_t numSamples, double sampleRate_Hz, std::optional<std::int64_t> firstStrikeSample)
    : sampleRate(sampleRate_Hz), struck(firstStrikeSample.has_value()), engaged(drum.snaresEngaged())
{
    const auto samples = std::max<std::int64_t>(numSamples, 1);
    timeFrom = firstStrikeSample ? std::clamp<std::int64_t>(*firstStrikeSample, 0, samples - 1) : 0;
    const auto window = std::max<std::int64_t>(1, std::llround(windowSeconds * sampleRate));
    timeTo = std::min(samples, timeFrom + window);

    const auto& snares = drum.snareWires();
    const auto& grid = drum.carry().grid();
    wires = snares.count();
    stride = snares.nodesPerWire();
    interiorPerWire = std::max(0, snares.intervals() - 1);
    for (int i = 0; i < wires; ++i)
        for (int l = 1; l < snares.intervals(); ++l)
        {
            wireNodes.push_back(i * stride + l);
            headNodes.push_back(grid.nearestInterior(snares.nodeX(l), snares.wireY(i)));
        }
    rows.reserve((std::size_t)(timeTo - timeFrom + 1));
}

void SnarePlot::add(std::int64_t time, const Drum& drum)
{
    if (time < timeFrom || time > timeTo)
        return;

    const auto& u = drum.snareWires().uNow;
    const Membrane& carry = drum.carry();
    double sum = 0.0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
    double carrySum = 0.0;
    int carryCount = 0;
    for (std::size_t k = 0; k < wireNodes.size(); ++k)
    {
        const double v = u[(std::size_t) wireNodes[k]];
        sum += v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        if (headNodes[k] >= 0)
        {
            carrySum += carry.nowAt(headNodes[k]);
            ++carryCount;
        }
    }

    Row row;
    row.time_ms = (double) (time - timeFrom) / sampleRate * 1000.0;
    const double n = std::max<double>(1.0, (double) wireNodes.size());
    row.mean_mm = sum / n * 1000.0;
    row.min_mm = wireNodes.empty() ? 0.0 : lo * 1000.0;
    row.max_mm = wireNodes.empty() ? 0.0 : hi * 1000.0;
    row.carry_mm = carryCount > 0 ? carrySum / carryCount * 1000.0 : 0.0;
    row.contacts = drum.snaresEngaged() ? drum.solverStats().snareContacts : 0;
    if (! std::isfinite(row.mean_mm) || ! std::isfinite(row.min_mm) || ! std::isfinite(row.max_mm) || ! std::isfinite(row.carry_mm))
    {
        ++nonfiniteRows;
        return;
    }
    rows.push_back(row);
}

juce::Image SnarePlot::draw() const
{
    auto image = plot::whiteImage(width, height);
    juce::Graphics g(image);

    const double durationMs = (double) (timeTo - timeFrom) / sampleRate * 1000.0;
    drawWirePanel(g, wireArea(), durationMs);
    drawContactPanel(g, contactArea(), durationMs);
    drawLegend(g, 935.0f, 50.0f);
    return image;
}

void SnarePlot::drawWirePanel(juce::Graphics& g, juce::Rectangle<float> area, double durationMs) const
{
    // The range: every plotted value (the carry head alone with the snares thrown off).
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& r : rows)
    {
        lo = std::min(lo, engaged ? std::min(r.min_mm, r.carry_mm) : r.carry_mm);
        hi = std::max(hi, engaged ? std::max(r.max_mm, r.carry_mm) : r.carry_mm);
    }
    if (rows.empty())
        lo = hi = 0.0;
    if (const double span = hi - lo; span > 1.0e-9)
    {
        lo -= 0.06 * span;
        hi += 0.06 * span;
    }
    else
    {
        const double extent = std::max(std::abs(hi), 1.0e-3);
        lo -= extent;
        hi += extent;
    }

    plot::Axes axes { area, 0.0, durationMs, lo, hi };
    const auto yValues = plot::niceTicks(lo, hi, 8);
    const double yStep = plot::tickStep(yValues);
    const auto title = std::string(struck ? "Snare wires after the first strike: " : "Snare wires (no strike played): ") +
                       std::to_string(wires) + (wires == 1 ? " wire x " : " wires x ") + std::to_string(interiorPerWire) +
                       " interior nodes, " + formatted("%.0f", sampleRate) + " Hz";
    plot::drawAxes(g, axes, timeTicks(durationMs, area.getWidth()),
                   plot::labelled(yValues, [&](double v) { return plot::decimalLabel(v, yStep); }),
                   { title, "", "displacement (mm), up positive" });

    juce::Graphics::ScopedSaveState state(g);
    g.reduceClipRegion(area.toNearestInt());

    auto point = [&](double t, double v) { return juce::Point<float>(axes.xToPixel(t), axes.yToPixel(v)); };
    auto curve = [&](auto value) {
        juce::Path path;
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
            const auto p = point(rows[i].time_ms, value(rows[i]));
            if (i == 0)
                path.startNewSubPath(p);
            else
                path.lineTo(p);
        }
        if (rows.size() == 1)
            path.lineTo(path.getCurrentPosition().translated(1.0f, 0.0f));
        return path;
    };

    if (engaged && ! rows.empty())
    {
        juce::Path band;
        band.startNewSubPath(point(rows.front().time_ms, rows.front().max_mm));
        for (const auto& r : rows)
            band.lineTo(point(r.time_ms, r.max_mm));
        for (auto r = rows.rbegin(); r != rows.rend(); ++r)
            band.lineTo(point(r->time_ms, r->min_mm));
        band.closeSubPath();
        g.setColour(kBand);
        g.fillPath(band);
        g.strokePath(band, juce::PathStrokeType(1.0f)); // a band one sample wide stays visible

        g.setColour(kWireMean);
        g.strokePath(curve([](const Row& r) { return r.mean_mm; }), juce::PathStrokeType(kWireMeanThickness));
    }
    if (! rows.empty())
    {
        g.setColour(kCarry);
        g.strokePath(curve([](const Row& r) { return r.carry_mm; }), juce::PathStrokeType(kCarryThickness));
    }

    // The lowest wire mean, marked.
    if (struck && engaged && ! rows.empty())
    {
        const auto lowest = std::min_element(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.mean_mm < b.mean_mm; });
        const auto p = point(lowest->time_ms, lowest->mean_mm);
        g.setColour(juce::Colours::black);
        g.drawEllipse(juce::Rectangle<float>(10.0f, 10.0f).withCentre(p), 1.6f);
    }
}

void SnarePlot::drawContactPanel(juce::Graphics& g, juce::Rectangle<float> area, double durationMs) const
{
    const int points = (int) wireNodes.size();
    const double top = std::max(points, 1);
    plot::Axes axes { area, 0.0, durationMs, 0.0, contactAxisTop(points) };
    const auto yValues = plot::niceTicks(0.0, top, 4);
    const double yStep = plot::tickStep(yValues);
    plot::drawAxes(g, axes, timeTicks(durationMs, area.getWidth()),
                   plot::labelled(yValues, [&](double v) { return plot::decimalLabel(v, yStep); }),
                   { "Wire points touching the carry head (gap > 0), of " + std::to_string(points),
                     struck ? "time after the first strike (ms)" : "time (ms)", "points" });

    juce::Graphics::ScopedSaveState state(g);
    g.reduceClipRegion(area.toNearestInt());
    if (! rows.empty())
    {
        // A step curve: each count holds until the next state.
        juce::Path line;
        for (std::size_t i = 0; i < rows.size(); ++i)
        {
            const float x = axes.xToPixel(rows[i].time_ms);
            const float y = axes.yToPixel(rows[i].contacts);
            if (i == 0)
                line.startNewSubPath(x, y);
            else
                line.lineTo(x, y);
            const float next = i + 1 < rows.size() ? axes.xToPixel(rows[i + 1].time_ms) : x + 1.0f;
            line.lineTo(next, y);
        }
        juce::Path fill(line);
        fill.lineTo(line.getCurrentPosition().x, axes.yToPixel(0.0));
        fill.lineTo(axes.xToPixel(rows.front().time_ms), axes.yToPixel(0.0));
        fill.closeSubPath();
        g.setColour(kContactFill);
        g.fillPath(fill);
        g.setColour(kContactLine);
        g.strokePath(line, juce::PathStrokeType(1.3f));
    }
}

void SnarePlot::drawLegend(juce::Graphics& g, float x, float y) const
{
    const float boxWidth = 255.0f;

    // The curves of the top panel.
    {
        const float heightNeeded = (engaged ? 40.0f + 24.0f : 0.0f) + 40.0f + 12.0f;
        const juce::Rectangle<float> box(x, y, boxWidth, heightNeeded);
        g.setColour(juce::Colours::white);
        g.fillRect(box);
        g.setColour(juce::Colour(0xffb0b0b0));
        g.drawRect(box, 1.0f);
        float row = y + 6.0f;
        if (engaged)
        {
            row += legendRow(g, x, row, boxWidth, Swatch::band, kBand, "wires: lowest to highest interior node", 2);
            row += legendRow(g, x, row, boxWidth, Swatch::line, kWireMean, "wires: mean", 1);
        }
        legendRow(g, x, row, boxWidth, Swatch::thinLine, kCarry, "carry head under the wires: mean", 2);
        y = box.getBottom() + 16.0f;
    }

    // Notes and what the data says, read from it, below the legend (never over the curves).
    std::vector<std::string> lines;
    if (! struck)
        lines.push_back("no strike played in the render");
    if (! engaged)
        lines.insert(lines.end(), { "snares thrown off", "(snares_engaged = 0): the carry", "head alone, no contact" });
    if (rows.empty())
        lines.push_back("no finite state to show");
    if (nonfiniteRows > 0)
        lines.push_back("non-finite states left out");
    if (struck && engaged && ! rows.empty())
    {
        const auto lowestMean =
            std::min_element(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.mean_mm < b.mean_mm; });
        const auto lowestNode = std::min_element(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.min_mm < b.min_mm; });
        lines.insert(lines.end(),
                     { "lowest wire mean (circled):",
                       "  " + signedText("%.3f", lowestMean->mean_mm) + " mm at " + formatted("%.2f", lowestMean->time_ms) + " ms",
                       "lowest wire node:",
                       "  " + signedText("%.3f", lowestNode->min_mm) + " mm at " + formatted("%.2f", lowestNode->time_ms) + " ms" });
    }
    g.setFont(plot::font(15.0f));
    g.setColour(kNote);
    for (const auto& line : lines)
    {
        g.drawText(plot::toJuce(line), juce::Rectangle<float>(x + 4.0f, y, boxWidth, 20.0f), juce::Justification::centredLeft, false);
        y += 21.0f;
    }

    // The bottom panel's curve, beside it.
    const juce::Rectangle<float> box(x, 478.0f, boxWidth, 40.0f + 12.0f);
    g.setColour(juce::Colours::white);
    g.fillRect(box);
    g.setColour(juce::Colour(0xffb0b0b0));
    g.drawRect(box, 1.0f);
    legendRow(g, x, box.getY() + 6.0f, boxWidth, Swatch::fill, kContactLine, "wire points touching the carry head", 2);
}

} // namespace snaresim::render
