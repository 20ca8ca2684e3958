#include "Plotting.h"

#include "Errors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace snaresim::render::plot
{
namespace
{

double mapped(double v, bool logarithmic) { return logarithmic ? std::log10(v) : v; }

const juce::Colour kFrame { 0xff303030 };
const juce::Colour kGrid { 0xffe4e4e4 };
const juce::Colour kText { 0xff202020 };

constexpr float kMajorTick = 6.0f;
constexpr float kMinorTick = 3.5f;

} // namespace

juce::String toJuce(const std::string& text) { return juce::String::fromUTF8(text.data(), (int) text.size()); }

float Axes::xToPixel(double x) const
{
    const double a = mapped(x0, logX), b = mapped(x1, logX);
    const double t = b != a ? (mapped(x, logX) - a) / (b - a) : 0.5;
    return area.getX() + (float) t * area.getWidth();
}

float Axes::yToPixel(double y) const
{
    const double a = mapped(y0, logY), b = mapped(y1, logY);
    const double t = b != a ? (mapped(y, logY) - a) / (b - a) : 0.5;
    return area.getBottom() - (float) t * area.getHeight();
}

std::vector<double> niceTicks(double lo, double hi, int maxCount)
{
    std::vector<double> ticks;
    if (! std::isfinite(lo) || ! std::isfinite(hi) || hi <= lo || maxCount < 1)
        return ticks;

    const double raw = (hi - lo) / maxCount;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10.0 * magnitude;
    for (const double m : { 1.0, 2.0, 2.5, 5.0 })
        if (m * magnitude >= raw * (1.0 - 1e-12))
        {
            step = m * magnitude;
            break;
        }

    const double first = std::ceil(lo / step - 1e-9);
    const double last = std::floor(hi / step + 1e-9);
    for (double i = first; i <= last; i += 1.0)
    {
        const double v = i * step;
        ticks.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    }
    return ticks;
}

double tickStep(const std::vector<double>& ticks) { return ticks.size() >= 2 ? ticks[1] - ticks[0] : 0.0; }

std::string decimalLabel(double value, double step)
{
    if (value == 0.0)
        return "0";
    int digits = 0;
    if (step > 0.0 && std::isfinite(step))
    {
        // Enough decimals that neighbours differ (2.5 x 10^k needs one more).
        const double scaled = step / std::pow(10.0, std::floor(std::log10(step)));
        digits = std::max(0, (int) -std::floor(std::log10(step) + 1e-9) + (std::abs(scaled - 2.5) < 1e-9 ? 1 : 0));
    }
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", std::min(digits, 12), value);
    return buffer;
}

namespace
{

// Decimals of the mantissa that tell multiples of step apart at value's exponent.
int scientificDigits(double value, double step)
{
    if (value == 0.0 || ! (step > 0.0) || ! std::isfinite(step))
        return 0;
    const double exponent = std::floor(std::log10(std::abs(value)));
    const double relative = step / std::pow(10.0, exponent); // m x 10^j, m in {1, 2, 2.5, 5}
    const double j = std::floor(std::log10(relative) + 1e-9);
    const double m = relative / std::pow(10.0, j);
    return std::clamp((int) std::max(0.0, -j) + (std::abs(m - 2.5) < 1e-6 ? 1 : 0), 0, 6);
}

std::string scientificText(double value, int digits)
{
    if (value == 0.0)
        return "0";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*e", digits, value);
    // "1.5e-15" rather than C's "1.5e-015" / "1.5e+01" forms: drop '+' and leading zeros.
    std::string text = buffer;
    const auto e = text.find('e');
    if (e != std::string::npos)
    {
        std::string exponent = text.substr(e + 1);
        const bool negative = ! exponent.empty() && exponent.front() == '-';
        if (! exponent.empty() && (exponent.front() == '-' || exponent.front() == '+'))
            exponent.erase(0, 1);
        exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
        text = text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
    }
    return text;
}

} // namespace

std::vector<Tick> scientificTicks(const std::vector<double>& values)
{
    const double step = tickStep(values);
    int digits = 0;
    for (const double v : values)
        digits = std::max(digits, scientificDigits(v, step));
    std::vector<Tick> ticks;
    for (const double v : values)
        ticks.push_back({ v, scientificText(v, digits), true });
    return ticks;
}

juce::Font font(float height, bool bold)
{
    return juce::Font(juce::Font::getDefaultSansSerifFontName(), height, bold ? juce::Font::bold : juce::Font::plain);
}

std::vector<Tick> labelled(const std::vector<double>& values, const std::function<std::string(double)>& label)
{
    std::vector<Tick> ticks;
    for (const double v : values)
        ticks.push_back({ v, label(v), true });
    return ticks;
}

void drawVerticalText(juce::Graphics& g, const std::string& text, float x, float y, const juce::Font& f)
{
    juce::Graphics::ScopedSaveState state(g);
    g.addTransform(juce::AffineTransform::rotation(-juce::MathConstants<float>::halfPi, x, y));
    g.setFont(f);
    const float width = f.getStringWidthFloat(toJuce(text)) + 4.0f;
    g.drawText(toJuce(text), juce::Rectangle<float>(x - width / 2.0f, y - f.getHeight() / 2.0f, width, f.getHeight()),
               juce::Justification::centred, false);
}

void drawAxes(juce::Graphics& g, const Axes& axes, const std::vector<Tick>& xTicks, const std::vector<Tick>& yTicks, const AxisText& text,
              bool grid)
{
    const auto& a = axes.area;
    const auto tickFont = font(15.0f);
    const auto titleFont = font(17.0f);

    auto insideX = [&](float px) { return px >= a.getX() - 0.5f && px <= a.getRight() + 0.5f; };
    auto insideY = [&](float py) { return py >= a.getY() - 0.5f && py <= a.getBottom() + 0.5f; };

    if (grid)
    {
        g.setColour(kGrid);
        for (const auto& t : xTicks)
            if (const float px = axes.xToPixel(t.value); t.major && insideX(px))
                g.drawLine(px, a.getY(), px, a.getBottom(), 1.0f);
        for (const auto& t : yTicks)
            if (const float py = axes.yToPixel(t.value); t.major && insideY(py))
                g.drawLine(a.getX(), py, a.getRight(), py, 1.0f);
    }

    g.setColour(kFrame);
    g.drawRect(a.expanded(0.5f), 1.0f);

    g.setFont(tickFont);
    float widestYLabel = 0.0f;
    for (const auto& t : xTicks)
    {
        const float px = axes.xToPixel(t.value);
        if (! insideX(px))
            continue;
        g.setColour(kFrame);
        g.drawLine(px, a.getBottom(), px, a.getBottom() + (t.major ? kMajorTick : kMinorTick), 1.0f);
        if (! t.label.empty())
        {
            g.setColour(kText);
            g.drawText(toJuce(t.label), juce::Rectangle<float>(px - 60.0f, a.getBottom() + 8.0f, 120.0f, 18.0f),
                       juce::Justification::centredTop, false);
        }
    }
    for (const auto& t : yTicks)
    {
        const float py = axes.yToPixel(t.value);
        if (! insideY(py))
            continue;
        g.setColour(kFrame);
        g.drawLine(a.getX() - (t.major ? kMajorTick : kMinorTick), py, a.getX(), py, 1.0f);
        if (! t.label.empty())
        {
            g.setColour(kText);
            g.drawText(toJuce(t.label), juce::Rectangle<float>(a.getX() - 128.0f, py - 9.0f, 120.0f, 18.0f),
                       juce::Justification::centredRight, false);
            widestYLabel = std::max(widestYLabel, tickFont.getStringWidthFloat(toJuce(t.label)));
        }
    }

    g.setColour(kText);
    g.setFont(titleFont);
    if (! text.xTitle.empty())
        g.drawText(toJuce(text.xTitle), juce::Rectangle<float>(a.getX(), a.getBottom() + 30.0f, a.getWidth(), 22.0f),
                   juce::Justification::centredTop, false);
    if (! text.yTitle.empty())
        drawVerticalText(g, text.yTitle, a.getX() - widestYLabel - 24.0f, a.getCentreY(), titleFont);
    if (! text.title.empty())
    {
        g.setFont(font(18.0f, true));
        g.drawText(toJuce(text.title), juce::Rectangle<float>(a.getX(), a.getY() - 32.0f, a.getWidth(), 24.0f),
                   juce::Justification::centred, false);
    }
}

juce::Image whiteImage(int width, int height)
{
    juce::Image image(juce::Image::RGB, width, height, false);
    image.clear(image.getBounds(), juce::Colours::white);
    return image;
}

void writePng(const juce::Image& image, const AtomicFile& file)
{
    const juce::File path(juce::String(std::filesystem::absolute(file.temporary()).string()));
    juce::FileOutputStream stream(path);
    if (! stream.openedOk())
        throw UserError("cannot write " + file.displayName() + ": " + stream.getStatus().getErrorMessage().toStdString());
    stream.setPosition(0);
    stream.truncate();

    juce::PNGImageFormat png;
    const bool written = png.writeImageToStream(image, stream);
    stream.flush();
    if (! written || stream.getStatus().failed())
    {
        const auto reason =
            stream.getStatus().failed() ? stream.getStatus().getErrorMessage().toStdString() : std::string("PNG encoding failed");
        throw UserError("cannot write " + file.displayName() + ": " + reason);
    }
}

} // namespace snaresim::render::plot
