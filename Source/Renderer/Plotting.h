#pragma once
// Small drawing helpers shared by the PNG outputs (EnergyPlot.h, Spectrogram.h): a plot
// area with its data ranges, "nice" tick positions, axes with labels, and writing a
// juce::Image as PNG into an AtomicFile's temporary file. juce::Image / juce::Graphics
// (software renderer) need no display.

#include "AtomicFile.h"

#include <juce_graphics/juce_graphics.h>

#include <functional>
#include <string>
#include <vector>

namespace snaresim::render::plot
{

// UTF-8 text for JUCE (labels use a few non-ASCII signs: superscripts, minus, en dash).
juce::String toJuce(const std::string& text);

// A rectangle of the image showing x in [x0, x1] and y in [y0, y1] (y upwards).
struct Axes
{
    juce::Rectangle<float> area;
    double x0 = 0.0, x1 = 1.0;
    double y0 = 0.0, y1 = 1.0;
    bool logX = false, logY = false; // positive ranges only

    float xToPixel(double x) const;
    float yToPixel(double y) const;
};

// About maxCount evenly spaced round values (1, 2, 2.5, 5 x 10^k) inside [lo, hi].
std::vector<double> niceTicks(double lo, double hi, int maxCount);

// The spacing niceTicks chose (the difference of two neighbours; 0 with fewer than two).
double tickStep(const std::vector<double>& ticks);

// A tick label in plain decimals with as many digits as the step needs; 0 is "0".
std::string decimalLabel(double value, double step);

// The text font (the system's sans serif), height in pixels.
juce::Font font(float height, bool bold = false);

struct Tick
{
    double value = 0.0;
    std::string label; // empty: a tick without a label
    bool major = true; // minor ticks are shorter and get no grid line
};

std::vector<Tick> labelled(const std::vector<double>& values, const std::function<std::string(double)>& label);

// Ticks labelled in scientific notation with one mantissa precision for all ("-2.5e-15",
// "5.0e-16"); 0 is "0".
std::vector<Tick> scientificTicks(const std::vector<double>& values);

// Frame, grid lines (light grey, major ticks only), ticks and tick labels outside the
// area, the axis titles (y rotated) and a title above the area.
struct AxisText
{
    std::string title;
    std::string xTitle;
    std::string yTitle;
};
void drawAxes(juce::Graphics& g, const Axes& axes, const std::vector<Tick>& xTicks, const std::vector<Tick>& yTicks, const AxisText& text,
              bool grid = true);

// Text rotated by -90 degrees (reading upwards), centred on (x, y).
void drawVerticalText(juce::Graphics& g, const std::string& text, float x, float y, const juce::Font& font);

// A white RGB image of this size.
juce::Image whiteImage(int width, int height);

// Writes the image as PNG into file.temporary() (the caller commits). Throws UserError.
void writePng(const juce::Image& image, const AtomicFile& file);

} // namespace snaresim::render::plot
