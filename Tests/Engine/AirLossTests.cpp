// The paper's section 5.3: the struck batter alone in the air box rings on in a band near
// 0.196 Fs, where the 7-point scheme's axial waves stop travelling, and sigma_a damps that band
// by the rate eq. 25 gives every air mode of its frequency (AirBandRun.h).

#include "AirBandRun.h"
#include "Report.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace snaresim;

TEST_CASE("section 5.3: the air grid's band near 0.196 Fs rings on, and sigma_a damps it by the rate of eq. 25", "[airbox][loss]")
{
    // A box just larger than the head (0.42 m across, 0.5 m high) and 0.2 s: the band stands
    // out from 40 ms on, and the two runs share the grid of sigma_a = 2e-6 m (eq. 41).
    test::AirBandSetup setup;
    setup.box_m = { 0.42, 0.42, 0.5 };
    setup.mic_m = { 0.07, 0.07, 0.07 };
    setup.seconds = 0.2;
    const double fs = setup.sampleRate_Hz, t0 = 0.04, t1 = setup.seconds - 0.01;

    setup.sigma_m = 0.0;
    const test::Frames lossless = test::stft(test::runAirBand(setup), fs);
    const test::BandDecay band0 = test::bandDecay(lossless, t0, t1, 0.17 * fs, 0.22 * fs);
    const test::BandDecay below = test::bandDecay(lossless, t0, t1, 0.0, 0.0, 0.17 * fs);
    setup.sigma_m = 2e-6;
    const test::BandDecay band1 = test::bandDecay(test::stft(test::runAirBand(setup), fs), t0, t1, 0.0, 0.0, band0.peak_Hz);

    // Where the axial waves stop: sin(pi f / fs) = c k / h = 1/sqrt(3) on the grid of eq. 41
    // (h slightly above sqrt(3) c k for sigma_a = 2e-6 m).
    AirBoxSpec spec;
    spec.sigma_m = 2e-6;
    const double lambda = spec.soundSpeed_m_per_s / (fs * AirBox::gridSpacing(spec, 1.0 / fs));
    const double cutoff = fs * std::asin(lambda) / std::numbers::pi;
    const double predicted = test::sigmaDecay_dB_per_s(band0.peak_Hz, 2e-6, fs);
    // The head's own modes there fade at sigma0 + sigma1 kappa^2 (kappa = 2 pi f / c_m).
    const MembraneSpec head = test::bandBatter(fs);
    const double kappa = 2.0 * std::numbers::pi * band0.peak_Hz / std::sqrt(head.tension_N_per_m / head.density_kg_per_m2);
    const double headRate = 20.0 * std::log10(std::exp(1.0)) * (head.sigma0_per_s + head.sigma1_m2_per_s * kappa * kappa);
    snaresim::test::reportf(
        "section 5.3 (box %.2f x %.2f x %.2f m, %.2f s): band at %.0f Hz = %.4f Fs (axial cutoff %.0f Hz), %.1f dB above 0.17 Fs; "
        "decay %.1f dB/s with sigma_a = 0, %.1f dB/s with 2e-6 m: sigma_a adds %.1f dB/s (eq. 25: %.1f); the head alone "
        "would fade at %.0f dB/s there\n",
        setup.box_m[0], setup.box_m[1], setup.box_m[2], setup.seconds, band0.peak_Hz, band0.peak_Hz / fs, cutoff,
        band0.level_dB - below.level_dB, band0.rate_dB_per_s, band1.rate_dB_per_s, band1.rate_dB_per_s - band0.rate_dB_per_s, predicted,
        headRate);

    // The band lies at the axial cutoff (to a bin of the 512-point frames, 86 Hz) and stands
    // out: many of the grid's modes crowd there, and the spectrum just below is far weaker.
    CHECK(std::abs(band0.peak_Hz - cutoff) < 1.5 * lossless.binHz);
    CHECK(band0.level_dB > below.level_dB + 20.0);
    // Without sigma_a it is slow: it outlasts the head's own ringing at that frequency by far,
    // so what rings there is the air's.
    CHECK(band0.rate_dB_per_s < 0.25 * headRate);
    // sigma_a damps every air mode of that frequency by the same rate (AirBandRun.h), so the
    // band's decay grows by that rate; the walls and the head, which do not share the air's
    // modes, leave a margin.
    CHECK(band1.rate_dB_per_s - band0.rate_dB_per_s == Approx(predicted).epsilon(0.2));
}
