#include "StrikeFeatures.h"

#include "Formatted.h"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <numeric>
#include <vector>

namespace snaresim::render
{
namespace
{

// numpy's round (half to even), as the script rounds sample counts.
long roundEven(double x) { return (long) std::nearbyint(x); }

// numpy.hanning: the symmetric Hann window.
std::vector<double> hanning(std::size_t n)
{
    std::vector<double> w(n, 1.0);
    if (n > 1)
        for (std::size_t i = 0; i < n; ++i)
            w[i] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * (double) i / (double) (n - 1));
    return w;
}

// |rfft(x, n)|^2 (x zero-padded to n).
std::vector<double> powerSpectrum(std::vector<double> x, std::size_t n)
{
    x.resize(n, 0.0);
    Eigen::FFT<double> fft;
    fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
    std::vector<std::complex<double>> spectrum;
    fft.fwd(spectrum, x);
    std::vector<double> power(n / 2 + 1);
    for (std::size_t k = 0; k < power.size(); ++k)
        power[k] = std::norm(spectrum[k]);
    return power;
}

} // namespace

StrikeFeatures measureStrike(std::span<const double> samples, double rate, StrikeRules rules)
{
    const std::size_t n = samples.size();
    if (n == 0)
        throw NotAStrike("no samples");
    for (const double v : samples)
        if (! std::isfinite(v))
            throw NotAStrike("non-finite samples");
    if (rules == StrikeRules::recording && (double) n < 0.100 * rate)
        throw NotAStrike(formatted("shorter than 100 ms (%.1f ms)", 1e3 * (double) n / rate));

    const double mean = std::accumulate(samples.begin(), samples.end(), 0.0) / (double) n;
    std::vector<double> x(samples.begin(), samples.end());
    double top = 0.0;
    for (auto& v : x)
    {
        v -= mean;
        top = std::max(top, std::abs(v));
    }
    if (top < 1e-7) // below -140 dB of full scale
        throw NotAStrike("silent");
    std::size_t firstLoud = 0;
    while (std::abs(x[firstLoud]) < 0.1 * top)
        ++firstLoud;
    const std::size_t onset = (std::size_t) std::max(0L, (long) firstLoud - roundEven(0.001 * rate));

    // Envelope: the mean power over a centred 10 ms window (numpy.convolve 'same'), in dB of
    // its largest value; only its peak and the falls are needed, so it stays in power.
    const long window = std::max(1L, roundEven(0.010 * rate));
    std::vector<double> prefix(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        prefix[i + 1] = prefix[i] + x[i] * x[i];
    const long shift = (window - 1) / 2;
    std::vector<double> power(n);
    for (long i = 0; i < (long) n; ++i)
    {
        const long hi = std::min((long) n - 1, i + shift), lo = std::max(0L, i + shift - window + 1);
        power[(std::size_t) i] = hi >= lo ? (prefix[(std::size_t) hi + 1] - prefix[(std::size_t) lo]) / (double) window : 0.0;
    }
    const auto peakAt = (std::size_t)(std::max_element(power.begin(), power.end()) - power.begin());
    const double peakPower = power[peakAt];
    if (rules == StrikeRules::recording && (double) peakAt - (double) onset > 0.100 * rate)
        throw NotAStrike(formatted("no strike (the level peaks %.0f ms after the onset)", 1e3 * ((double) peakAt - (double) onset) / rate));

    auto fall = [&](double db) -> std::optional<double> {
        const double threshold = peakPower * std::pow(10.0, -db / 10.0);
        std::size_t last = peakAt; // the last sample above the threshold
        for (std::size_t i = n; i-- > peakAt;)
            if (power[i] > threshold)
            {
                last = i;
                break;
            }
        if (last + 1 >= n)
            return std::nullopt;
        return 1e3 * (double) (last + 1 - onset) / rate;
    };

    StrikeFeatures f;
    f.sampleRate_Hz = rate;
    f.onset = onset;
    f.length_ms = 1e3 * (double) (n - onset) / rate;
    f.fall20_ms = fall(20.0);
    f.fall40_ms = fall(40.0);
    if (rules == StrikeRules::recording && ! f.fall20_ms)
        throw NotAStrike("no strike (the level never falls 20 dB)");

    auto segment = [&](double t0, double t1) {
        const auto from = std::min(n, onset + (std::size_t) roundEven(t0 * rate));
        const auto to = std::min(n, onset + (std::size_t) roundEven(t1 * rate));
        return std::vector<double>(x.begin() + (std::ptrdiff_t) from, x.begin() + (std::ptrdiff_t) std::max(from, to));
    };

    // The tail's centroid, 50-300 ms (Hann).
    if (auto tail = segment(0.050, 0.300); tail.size() >= 2 && (double) tail.size() >= 0.010 * rate)
    {
        const auto w = hanning(tail.size());
        for (std::size_t i = 0; i < tail.size(); ++i)
            tail[i] *= w[i];
        const auto spectrum = powerSpectrum(tail, tail.size());
        double sum = 0.0, moment = 0.0;
        for (std::size_t k = 0; k < spectrum.size(); ++k)
        {
            sum += spectrum[k];
            moment += (double) k * rate / (double) tail.size() * spectrum[k];
        }
        if (sum > 0.0)
            f.tailCentroid_Hz = moment / sum;
    }

    // The band shares of the first 300 ms (a 5 ms half-Hann taper at its end).
    {
        auto head = segment(0.0, 0.300);
        const std::size_t taper = std::min(head.size(), (std::size_t) roundEven(0.005 * rate));
        if (taper > 1)
            for (std::size_t j = 1; j <= taper; ++j)
                head[head.size() - taper + j - 1] *= 0.5 * (1.0 + std::cos(std::numbers::pi * (double) j / (double) taper));
        const std::size_t length = head.size();
        const auto spectrum = powerSpectrum(std::move(head), length);
        double total = 0.0;
        std::array<double, 5> sums {};
        for (std::size_t k = 0; k < spectrum.size(); ++k)
        {
            const double hz = (double) k * rate / (double) length;
            total += spectrum[k];
            for (std::size_t b = 0; b < sums.size(); ++b)
                if (hz >= kShareBandEdges_Hz[b] && hz < kShareBandEdges_Hz[b + 1])
                    sums[b] += spectrum[k];
        }
        for (std::size_t b = 0; b < sums.size(); ++b)
            f.bandShares[b] = total > 0.0 ? sums[b] / total : 0.0;
    }

    // The lowest strong peak of the first 500 ms (Hann, zero-padded to 4x or more), and the
    // other peaks down to 24 dB.
    if (auto part = segment(0.0, 0.500); part.size() >= 2)
    {
        const auto w = hanning(part.size());
        for (std::size_t i = 0; i < part.size(); ++i)
            part[i] *= w[i];
        const std::size_t nfft = std::size_t(1) << (int) std::ceil(std::log2(4.0 * (double) part.size()));
        const auto spectrum = powerSpectrum(std::move(part), nfft);
        const double largest = *std::max_element(spectrum.begin(), spectrum.end());
        std::vector<double> db(spectrum.size());
        for (std::size_t k = 0; k < db.size(); ++k)
            db[k] = 10.0 * std::log10(std::max(spectrum[k], largest * 1e-30)); // 20 log10 |X|
        const double binWidth = rate / (double) nfft;
        double strongest = -1e300;
        for (std::size_t k = 0; k < db.size(); ++k)
            if ((double) k * binWidth >= 40.0)
                strongest = std::max(strongest, db[k]);
        const long reach = std::max(1L, roundEven(20.0 / binWidth));
        for (std::size_t k = 1; k + 1 < db.size(); ++k)
        {
            if ((double) k * binWidth < 40.0 || db[k] < strongest - 24.0)
                continue;
            // The largest within +-reach bins (the edges extended, as scipy's 'nearest').
            bool local = true;
            for (long j = (long) k - reach; j <= (long) k + reach && local; ++j)
                local = db[(std::size_t) std::clamp(j, 0L, (long) db.size() - 1)] <= db[k];
            if (! local)
                continue;
            const double a = db[k - 1], b = db[k], c = db[k + 1];
            const double den = a - 2.0 * b + c;
            const double hz = ((double) k + (den != 0.0 ? 0.5 * (a - c) / den : 0.0)) * binWidth;
            f.peaks.emplace_back(hz, db[k] - strongest);
            if (! f.lowestPeak_Hz && db[k] >= strongest - 12.0)
                f.lowestPeak_Hz = hz;
        }
    }
    return f;
}

} // namespace snaresim::render
