#pragma once
// Spectral peak picking shared by the engine tests (Hann window, zero padding, parabolic
// interpolation on the log magnitude), and a mode's decay rate.

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace snaresim::test
{

inline std::vector<std::complex<double>> hannSpectrum(const std::vector<double>& x, size_t pad = 4)
{
    std::vector<double> windowed(pad * x.size(), 0.0);
    for (size_t i = 0; i < x.size(); ++i)
        windowed[i] = x[i] * 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * (double) i / (double) (x.size() - 1)));
    Eigen::FFT<double> fft;
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, windowed);
    spectrum.resize(windowed.size() / 2);
    return spectrum;
}

struct Peak
{
    double frequency;
    double logMagnitude;
    size_t bin;
};

// Local maxima of |X| within [fLo, fHi], strongest first.
inline std::vector<Peak> peaks(const std::vector<std::complex<double>>& X, double binHz, double fLo, double fHi)
{
    std::vector<double> mag(X.size());
    for (size_t i = 0; i < X.size(); ++i)
        mag[i] = std::log(std::abs(X[i]) + 1e-300);
    std::vector<Peak> found;
    for (size_t i = std::max<size_t>(1, (size_t) (fLo / binHz)); i < std::min(mag.size() - 1, (size_t) (fHi / binHz)); ++i)
        if (mag[i] > mag[i - 1] && mag[i] >= mag[i + 1])
        {
            const double a = mag[i - 1], b = mag[i], c = mag[i + 1];
            const double offset = 0.5 * (a - c) / (a - 2.0 * b + c);
            found.push_back({ ((double) i + offset) * binHz, b, i });
        }
    std::sort(found.begin(), found.end(), [](const Peak& p, const Peak& q) { return p.logMagnitude > q.logMagnitude; });
    return found;
}

// How fast the part of x near f fades (dB/s; a mode's decay rate). The band is a Gaussian
// of standard deviation 5 % of f on the FFT's positive bins (the rest zeroed), so the analytic
// signal z it gives is x smoothed over a Gaussian of sd s_t = 1 / (2 pi 0.05 f) in time, which
// keeps an exponential's slope exactly and has no long tails. Its magnitude in dB is fitted
// by a line from 3 s_t after its largest value to where it has fallen 30 dB below that start
// (a mode's first 30 dB, as T30; a weaker, slower mode behind it does not count), or to the
// last 10 % of the record when it never falls so far (then a lossless mode's beating with a
// neighbour shows as wiggles about the line, not as a slope).
inline double bandDecay_dB_per_s(const std::vector<double>& x, double sampleRate_Hz, double f_Hz)
{
    const size_t n = x.size();
    std::vector<std::complex<double>> in(x.begin(), x.end()), X, z;
    Eigen::FFT<double> fft;
    fft.fwd(X, in);
    const double binHz = sampleRate_Hz / (double) n, sd = 0.05 * f_Hz;
    for (size_t b = 0; b < n; ++b)
    {
        const double u = ((double) b * binHz - f_Hz) / sd;
        X[b] *= b > n / 2 ? 0.0 : std::exp(-0.5 * u * u);
    }
    fft.inv(z, X);
    std::vector<double> y(n);
    for (size_t i = 0; i < n; ++i)
        y[i] = 20.0 * std::log10(std::abs(z[i]) + 1e-300);
    const size_t last = n - n / 10;
    const size_t peak = (size_t) (std::max_element(y.begin(), y.begin() + (std::ptrdiff_t) last) - y.begin());
    const size_t first = std::min(last - 1, peak + (size_t) (3.0 * sampleRate_Hz / (2.0 * std::numbers::pi * sd)));
    double st = 0, sy = 0, stt = 0, sty = 0, m = 0;
    for (size_t i = first; i < last && y[i] > y[first] - 30.0; ++i)
    {
        const double t = (double) i / sampleRate_Hz;
        st += t;
        sy += y[i];
        stt += t * t;
        sty += t * y[i];
        m += 1.0;
    }
    return -(m * sty - st * sy) / (m * stt - st * st);
}

} // namespace snaresim::test
