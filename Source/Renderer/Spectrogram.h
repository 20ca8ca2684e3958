#pragma once
// --spectrogram: a log-frequency spectrogram of one rendered signal as a picture.
// Short-time Fourier transform (Eigen's FFT): Hann window of 2048 samples at 48 kHz, the
// same duration at other rates (round(2048 fs / 48000) samples, zero-padded to the next
// power of two for the FFT), hop a quarter of the window (75 % overlap); frames start at
// sample 0 and lie inside the render (one zero-padded frame when it is shorter than a
// window); each pixel column shows the frames centred in it, or the nearest. Magnitude in dB relative to a
// full-scale sine, 90 dB shown; frequency logarithmic from 40 Hz to Nyquist; time in s.
// Fed block by block while rendering; keeps a bounded number of frames (consecutive
// frames are averaged in power beyond that), so any render length fits.

#include <juce_graphics/juce_graphics.h>

#include <Eigen/Core>
#include <unsupported/Eigen/FFT>

#include <cmath>
#include <complex>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace snaresim::render
{

class Spectrogram
{
public:
    static constexpr int width = 1200;
    static constexpr int height = 700;
    static constexpr double rangeDb = 90.0;
    static constexpr double lowestFrequency_Hz = 40.0;

    // signalName: what the samples are ("mix", "top", ...), for the title.
    Spectrogram(std::int64_t numSamples, double sampleRate_Hz, std::string signalName);

    void add(std::span<const float> samples);

    // Completes the last frames (zero padding) and draws.
    juce::Image draw();

    // Layout: the spectrogram's pixels. Pixel column x of the area shows the frames centred in
    // samples [x N / width, (x + 1) N / width) of an N-sample render (or the nearest frame);
    // pixel row y shows frequency row getBottom() - 1 - y.
    static juce::Rectangle<int> plotArea() { return { 100, 50, 955, 580 }; }

    // The frequency axis: row r (0 at the bottom, plotArea().getHeight() rows) covers
    // [rowEdge_Hz(r), rowEdge_Hz(r + 1)), equal steps of log frequency from 40 Hz to Nyquist.
    static double rowEdge_Hz(int row, double sampleRate_Hz)
    {
        const double nyquist = sampleRate_Hz / 2.0;
        return lowestFrequency_Hz * std::pow(nyquist / lowestFrequency_Hz, (double) row / plotArea().getHeight());
    }

    int windowLength() const { return windowSize; }
    int hopSize() const { return hop; }
    int fftLength() const { return fftSize; }
    std::int64_t numFrames() const { return frames; }

private:
    struct RowBins
    {
        int first = 0, last = -1; // bins whose centre lies in the row: the maximum of them
        int below = 0;            // otherwise: interpolated between bins below and below + 1
        double fraction = 0.0;
    };

    void analyseFrame();
    juce::Colour colourAt(double dB, double top) const;

    std::int64_t samples;
    double sampleRate;
    std::string name;
    int windowSize, hop, fftSize, rows;
    std::int64_t frames; // frames the whole render gives
    std::int64_t framesDone = 0;
    std::int64_t slots; // stored columns: consecutive frames share one beyond kMaxSlots

    std::vector<double> window;
    double windowSum = 0.0;
    std::vector<RowBins> rowBins;
    std::vector<float> pending; // samples from the next frame's start on
    std::vector<double> frameIn;
    std::vector<std::complex<double>> frameOut;
    std::vector<float> power; // slots x rows, summed power
    std::vector<int> counts;  // frames per slot
    Eigen::FFT<double> fft;
};

} // namespace snaresim::render
