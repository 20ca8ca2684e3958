#pragma once
// --snare-plot: the snare wires against time, for the first 25 ms after the first strike
// (the whole render when it ends sooner; from the render's start when no strike is played),
// time in ms after the strike:
//   top:    the mean displacement (mm, up positive) of every wire's interior nodes, the band
//           between their minimum and maximum, and the carry head's mean displacement under
//           them (w at the head node each interior wire node maps to: the interior node of
//           the carry head's grid nearest to it, CircularGrid::nearestInterior, as
//           SnareContact maps them);
//   bottom: the number of wire points touching the carry head (gap xi = u - w_c > 0).
// Fed with the drum's state at every time index of the window. The count is the engine's
// SolverStats::snareContacts, the points with xi^{n+1} > 0 of the step just taken: after
// Drum::step() the time levels have been rotated, so SnareContact::gaps() then holds the
// gaps of two steps earlier, not those of the state read here.

#include "Drum.h"

#include <juce_graphics/juce_graphics.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

namespace snaresim::render
{

class SnarePlot
{
public:
    static constexpr int width = 1200;
    static constexpr int height = 700;
    static constexpr double windowSeconds = 0.025;

    // drum: the drum to be rendered (for the wires' layout); firstStrikeSample: the sample of
    // the first strike played (none: the window starts at time 0).
    SnarePlot(const Drum& drum, std::int64_t numSamples, double sampleRate_Hz, std::optional<std::int64_t> firstStrikeSample);

    // The window in time indices: the drum's state at time n exists after the step of sample
    // n - 1 (time 0: before the first step). [firstTime(), lastTime()], both inclusive.
    std::int64_t firstTime() const { return timeFrom; }
    std::int64_t lastTime() const { return timeTo; }

    // The drum's state at time index `time` (ignored outside the window).
    void add(std::int64_t time, const Drum& drum);

    juce::Image draw() const;

    // Layout, in pixels: the plot areas of the top (wires) and bottom (contact count) panels.
    static juce::Rectangle<float> wireArea() { return { 100.0f, 50.0f, 810.0f, 340.0f }; }
    static juce::Rectangle<float> contactArea() { return { 100.0f, 478.0f, 810.0f, 150.0f }; }
    // The contact panel's y axis runs from 0 to 1.08 times the number of wire points; its x axis,
    // like the top panel's, from 0 to the window's length in ms after the first strike.
    static double contactAxisTop(int points) { return std::max(points, 1) * 1.08; }

private:
    struct Row
    {
        double time_ms = 0.0; // after the first strike
        double mean_mm = 0.0, min_mm = 0.0, max_mm = 0.0;
        double carry_mm = 0.0;
        int contacts = 0;
    };

    void drawWirePanel(juce::Graphics& g, juce::Rectangle<float> area, double durationMs) const;
    void drawContactPanel(juce::Graphics& g, juce::Rectangle<float> area, double durationMs) const;
    void drawLegend(juce::Graphics& g, float x, float y) const;

    double sampleRate;
    bool struck;
    bool engaged;
    std::int64_t timeFrom = 0, timeTo = 0;
    int wires = 0, interiorPerWire = 0, stride = 0;
    std::vector<int> wireNodes; // wire-array index of each interior node
    std::vector<int> headNodes; // the carry-head node it maps to (-1: none)
    std::vector<Row> rows;
    std::int64_t nonfiniteRows = 0;
};

} // namespace snaresim::render
