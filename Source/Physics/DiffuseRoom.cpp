#include "DiffuseRoom.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace snaresim
{
namespace
{
// The lines' lengths at 48 kHz (samples, primes: no common period), scaled to the rate.
constexpr std::array<int, DiffuseRoom::kLines> kLengthsAt48k { 887, 1049, 1223, 1367, 1543, 1709, 1871, 2029 };
// Row i of the 8 x 8 Hadamard matrix (Sylvester) at column j: -1 where i & j has odd parity.
constexpr double hadamard(int i, int j) { return (std::popcount((unsigned) (i & j)) & 1) != 0 ? -1.0 : 1.0; }
constexpr int kInputRow = 4;                                             // the source in
constexpr std::array<int, DiffuseRoom::kOutputs> kOutputRow { 1, 2, 3 }; // the microphones out
constexpr double kLowT60 = 1.3, kHighT60 = 0.8;                          // of T60: the decay at low and at the highest frequencies
constexpr int kFirstPasses = 4;                                          // run through the network's longest line, for the field's energy
} // namespace

void DiffuseRoom::Network::clear() noexcept
{
    for (auto& l : line)
        std::fill(l.begin(), l.end(), 0.0);
    pos.fill(0);
    loss.fill(0.0);
}

DiffuseRoom::DiffuseRoom(const RoomSpec& spec, double sampleRate_Hz) : rate(sampleRate_Hz)
{
    for (int i = 0; i < kLines; ++i)
    {
        length[(size_t) i] = std::max(1, (int) std::lround(kLengthsAt48k[(size_t) i] * rate / 48000.0));
        live.line[(size_t) i].assign((size_t) length[(size_t) i], 0.0);
    }
    trial = live;
    setSpec(spec);
}

std::array<double, DiffuseRoom::kOutputs> DiffuseRoom::pass(Network& n, double in) const noexcept
{
    std::array<double, kLines> z {};
    double sum = 0.0;
    for (int i = 0; i < kLines; ++i)
    {
        const double y = n.line[(size_t) i][(size_t) n.pos[(size_t) i]];
        double& s = n.loss[(size_t) i];
        s = lossGain[(size_t) i] * (1.0 - lossPole[(size_t) i]) * y + lossPole[(size_t) i] * s;
        z[(size_t) i] = s;
        sum += s;
    }
    const double back = 2.0 / kLines * sum; // Householder: z - (2 / N) (1^T z) 1
    const double fed = in / std::sqrt((double) kLines);
    std::array<double, kOutputs> out {};
    for (int i = 0; i < kLines; ++i)
    {
        n.line[(size_t) i][(size_t) n.pos[(size_t) i]] = z[(size_t) i] - back + hadamard(kInputRow, i) * fed;
        n.pos[(size_t) i] = n.pos[(size_t) i] + 1 == length[(size_t) i] ? 0 : n.pos[(size_t) i] + 1;
        for (int m = 0; m < kOutputs; ++m)
            out[(size_t) m] += hadamard(kOutputRow[(size_t) m], i) * z[(size_t) i];
    }
    for (double& o : out)
        o /= std::sqrt((double) kLines);
    return out;
}

void DiffuseRoom::setSpec(const RoomSpec& spec) noexcept
{
    const double t60 = spec.reverberationTime_s;
    on = t60 > 0.0 && spec.volume_m3 > 0.0;
    if (! on)
    {
        criticalDistance_m = inputGain = 0.0;
        return;
    }
    criticalDistance_m = 0.057 * std::sqrt(spec.volume_m3 / t60);
    int total = 0;
    for (int i = 0; i < kLines; ++i)
    {
        // a pass through line i: 60 dB in kLowT60 T60 at 0 Hz, in kHighT60 T60 at Nyquist
        const double d = length[(size_t) i] / rate;
        const double low = std::pow(10.0, -3.0 * d / (kLowT60 * t60)), high = std::pow(10.0, -3.0 * d / (kHighT60 * t60));
        lossGain[(size_t) i] = low;                         // H(z) = g (1 - b) / (1 - b z^-1): g at 0 Hz,
        lossPole[(size_t) i] = (low - high) / (low + high); // g (1 - b) / (1 + b) = high at Nyquist
        total += length[(size_t) i];
    }
    // The energy a unit impulse leaves at the microphones (their mean): the first passes run,
    // then what the lines hold, spread over their length, decaying 60 dB per T60.
    trial.clear();
    double heard = 0.0;
    const int first = kFirstPasses * *std::max_element(length.begin(), length.end());
    for (int t = 0; t < first; ++t)
        for (double o : pass(trial, t == 0 ? 1.0 : 0.0))
            heard += o * o / kOutputs;
    double held = 0.0;
    for (const auto& l : trial.line)
        for (double v : l)
            held += v * v;
    heard += held * t60 * rate / (6.0 * std::log(10.0) * total);
    inputGain = 1.0 / (criticalDistance_m * std::sqrt(heard));
}

std::array<double, DiffuseRoom::kOutputs> DiffuseRoom::listen(double source) noexcept
{
    if (! on)
        return {};
    return pass(live, inputGain * source);
}

void DiffuseRoom::clear() noexcept { live.clear(); }

} // namespace snaresim
