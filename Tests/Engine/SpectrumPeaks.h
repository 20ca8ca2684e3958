#pragma once
// Spectral peak picking shared by the engine tests (Hann window, zero padding, parabolic
// interpolation on the log magnitude).

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

} // namespace snaresim::test
