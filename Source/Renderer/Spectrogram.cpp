#include "Spectrogram.h"

#include "Formatted.h"
#include "Plotting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace snaresim::render
{
namespace
{

constexpr std::int64_t kMaxSlots = 4096;
constexpr float kFloorPower = 1.0e-30f;

const juce::Rectangle<int> kArea = Spectrogram::plotArea(); // the spectrogram itself
const juce::Rectangle<int> kColourBar { 1085, 50, 24, 580 };

// An approximation of matplotlib's "inferno" colour map (dark: quiet, light: loud).
const juce::uint32 kColourMap[] = { 0xff000004, 0xff1f0c48, 0xff550f6d, 0xff88226a, 0xffba3655,
                                    0xffe35933, 0xfff98c0a, 0xfff9c932, 0xfffcffa4 };

juce::Colour mapColour(double t)
{
    constexpr int n = (int) std::size(kColourMap);
    t = std::clamp(t, 0.0, 1.0) * (n - 1);
    const int i = std::min((int) t, n - 2);
    return juce::Colour(kColourMap[i]).interpolatedWith(juce::Colour(kColourMap[i + 1]), (float) (t - i));
}

int nextPowerOfTwo(int n)
{
    int p = 1;
    while (p < n)
        p *= 2;
    return p;
}

} // namespace

Spectrogram::Spectrogram(std::int64_t numSamples, double sampleRate_Hz, std::string signalName)
    : samples(std::max<std::int64_t>(numSamples, 1)), sampleRate(sampleRate_Hz), name(std::move(signalName))
{
    windowSize = std::max(16, (int) std::lround(2048.0 * sampleRate / 48000.0));
    hop = std::max(1, (int) std::lround(windowSize / 4.0));
    fftSize = nextPowerOfTwo(windowSize);
    rows = kArea.getHeight();

    // Whole frames only (zero padding after a still-ringing end would smear the last
    // frame); a render shorter than one window gives one zero-padded frame.
    frames = samples <= windowSize ? 1 : 1 + (samples - windowSize) / hop;
    slots = std::min(frames, kMaxSlots);

    // Periodic Hann window.
    window.resize((std::size_t) windowSize);
    for (int i = 0; i < windowSize; ++i)
    {
        window[(std::size_t) i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * i / windowSize);
        windowSum += window[(std::size_t) i];
    }

    // Rows: equal steps of log frequency from 40 Hz to Nyquist (row 0 at the bottom).
    const double binWidth = sampleRate / fftSize;
    const int lastBin = fftSize / 2;
    rowBins.resize((std::size_t) rows);
    for (int r = 0; r < rows; ++r)
    {
        const double lo = rowEdge_Hz(r, sampleRate);
        const double hi = rowEdge_Hz(r + 1, sampleRate);
        auto& row = rowBins[(std::size_t) r];
        row.first = (int) std::ceil(lo / binWidth);
        row.last = std::min(lastBin, (int) std::ceil(hi / binWidth) - 1);
        const double position = std::min(std::sqrt(lo * hi) / binWidth, (double) lastBin);
        row.below = std::min((int) position, lastBin - 1);
        row.fraction = position - row.below;
    }

    frameIn.assign((std::size_t) fftSize, 0.0);
    power.assign((std::size_t)(slots * rows), 0.0f);
    counts.assign((std::size_t) slots, 0);
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    pending.reserve((std::size_t)(windowSize + 4096));
}

void Spectrogram::add(std::span<const float> block)
{
    if (framesDone >= frames)
        return;
    for (const float x : block)
        pending.push_back(std::isfinite(x) ? x : 0.0f);
    while (framesDone < frames && (int) pending.size() >= windowSize)
        analyseFrame();
}

void Spectrogram::analyseFrame()
{
    for (int i = 0; i < windowSize; ++i)
        frameIn[(std::size_t) i] = window[(std::size_t) i] * (double) pending[(std::size_t) i];
    fft.fwd(frameOut, frameIn);

    // Power relative to a full-scale sine: amplitude 2 |X| / sum(w).
    const double scale = 2.0 / windowSum;
    auto binPower = [&](int k) { return std::norm(frameOut[(std::size_t) k] * scale); };

    const auto slot = framesDone * slots / frames;
    float* out = power.data() + slot * rows;
    for (int r = 0; r < rows; ++r)
    {
        const auto& row = rowBins[(std::size_t) r];
        double p = 0.0;
        if (row.last >= row.first)
            for (int k = row.first; k <= row.last; ++k)
                p = std::max(p, binPower(k));
        else
            p = (1.0 - row.fraction) * binPower(row.below) + row.fraction * binPower(row.below + 1);
        out[r] += (float) p;
    }
    ++counts[(std::size_t) slot];
    ++framesDone;

    pending.erase(pending.begin(), pending.begin() + std::min<std::ptrdiff_t>(hop, (std::ptrdiff_t) pending.size()));
}

juce::Colour Spectrogram::colourAt(double dB, double top) const { return mapColour((dB - (top - rangeDb)) / rangeDb); }

juce::Image Spectrogram::draw()
{
    while (framesDone < frames)
    {
        pending.resize(std::max<std::size_t>(pending.size(), (std::size_t) windowSize), 0.0f);
        analyseFrame();
    }

    // Per pixel column, the mean power of the frames centred inside it (or the nearest frame).
    const int columns = kArea.getWidth();
    std::vector<float> dB((std::size_t) columns * (std::size_t) rows);
    double loudest = -1.0e300;
    for (int x = 0; x < columns; ++x)
    {
        const double from = (double) x / columns * (double) samples, to = (double) (x + 1) / columns * (double) samples;
        const double centre = windowSize / 2.0;
        auto firstFrame = (std::int64_t) std::ceil((from - centre) / hop);
        auto lastFrame = (std::int64_t) std::ceil((to - centre) / hop) - 1;
        firstFrame = std::clamp<std::int64_t>(firstFrame, 0, frames - 1);
        lastFrame = std::clamp<std::int64_t>(lastFrame, 0, frames - 1);
        if (lastFrame < firstFrame)
            firstFrame = lastFrame = std::clamp<std::int64_t>(std::llround(((from + to) / 2.0 - centre) / hop), 0, frames - 1);
        const auto firstSlot = firstFrame * slots / frames, lastSlot = lastFrame * slots / frames;

        for (int r = 0; r < rows; ++r)
        {
            double sum = 0.0;
            int count = 0;
            for (auto s = firstSlot; s <= lastSlot; ++s)
            {
                sum += power[(std::size_t)(s * rows + r)];
                count += counts[(std::size_t) s];
            }
            const double value = 10.0 * std::log10(std::max(sum / std::max(count, 1), (double) kFloorPower));
            dB[(std::size_t)(x * rows + r)] = (float) value;
            loudest = std::max(loudest, value);
        }
    }

    // The colour scale: 90 dB below the loudest value rounded up to 10 dB (silence: 0 dB, so
    // that it shows dark).
    const bool silent = loudest <= 10.0 * std::log10((double) kFloorPower) + 1.0;
    const double top = silent ? 0.0 : std::ceil(loudest / 10.0 - 1e-9) * 10.0;

    auto image = plot::whiteImage(width, height);
    {
        juce::Image::BitmapData pixels(image, juce::Image::BitmapData::writeOnly);
        for (int x = 0; x < columns; ++x)
            for (int r = 0; r < rows; ++r)
                pixels.setPixelColour(kArea.getX() + x, kArea.getBottom() - 1 - r, colourAt(dB[(std::size_t)(x * rows + r)], top));
        for (int y = 0; y < kColourBar.getHeight(); ++y)
        {
            const auto colour = mapColour(1.0 - (y + 0.5) / kColourBar.getHeight());
            for (int x = 0; x < kColourBar.getWidth(); ++x)
                pixels.setPixelColour(kColourBar.getX() + x, kColourBar.getY() + y, colour);
        }
    }

    juce::Graphics g(image);
    const double seconds = (double) samples / sampleRate;
    const double nyquist = sampleRate / 2.0;

    // Frequency ticks: labelled 100 Hz, 1 kHz, 10 kHz (those inside), unlabelled 2..9 x 10^k.
    std::vector<plot::Tick> yTicks;
    for (double decade = 10.0; decade < nyquist; decade *= 10.0)
        for (int m = 1; m <= 9; ++m)
        {
            const double f = m * decade;
            if (f < lowestFrequency_Hz || f > nyquist)
                continue;
            std::string label;
            if (m == 1)
                label = f >= 1000.0 ? formatted("%.0f kHz", f / 1000.0) : formatted("%.0f Hz", f);
            yTicks.push_back({ f, label, m == 1 });
        }

    const auto timeTicks = plot::niceTicks(0.0, seconds, 10);
    const double timeStep = plot::tickStep(timeTicks);
    plot::Axes axes { kArea.toFloat(), 0.0, seconds, lowestFrequency_Hz, nyquist, false, true };
    const auto title = "Spectrogram (" + name + "): Hann " + std::to_string(windowSize) + " samples (" +
                       formatted("%.1f", 1000.0 * windowSize / sampleRate) + " ms), 75 % overlap, " + formatted("%.0f", sampleRate) + " Hz";
    plot::drawAxes(g, axes, plot::labelled(timeTicks, [&](double v) { return plot::decimalLabel(v, timeStep); }), yTicks,
                   { title, "time (s)", "frequency (Hz)" }, false);

    // The colour bar: 10 dB ticks.
    const plot::Axes bar { kColourBar.toFloat(), 0.0, 1.0, top - rangeDb, top };
    g.setColour(juce::Colour(0xff303030));
    g.drawRect(kColourBar.toFloat().expanded(0.5f), 1.0f);
    g.setFont(plot::font(15.0f));
    for (double level = top - rangeDb; level <= top + 1e-9; level += 10.0)
    {
        const float y = bar.yToPixel(level);
        g.drawLine((float) kColourBar.getRight(), y, (float) kColourBar.getRight() + 5.0f, y, 1.0f);
        g.drawText(formatted("%.0f", level), juce::Rectangle<float>((float) kColourBar.getRight() + 8.0f, y - 9.0f, 50.0f, 18.0f),
                   juce::Justification::centredLeft, false);
    }
    plot::drawVerticalText(g, "magnitude (dB re full-scale sine)", (float) kColourBar.getRight() + 70.0f, (float) kColourBar.getCentreY(),
                           plot::font(17.0f));
    return image;
}

} // namespace snaresim::render
