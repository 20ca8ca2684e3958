// Compute time of the whole drum inside the air box (AirModel::airbox) at 44.1 kHz: seconds of
// compute per second of audio, beside the same drum with the cavity, split into the air's own
// update, the rest of the unstruck drum (heads, embeddings) and what a strike adds (the
// contacts solved jointly with each head's air). Prints figures; nothing about time can fail.
//   cmake --build build --target drumair_bench && ./build/Tests/Engine/drumair_bench

#include "AirBox.h"
#include "Drum.h"
#include "HeadEmbedding.h"
#include "Membrane.h"

#include <chrono>
#include <cstdio>

using namespace snaresim;

namespace
{
struct Run
{
    double perAudioSecond = 0.0; // compute seconds per audio second
    int maxTrials = 0;           // most contact trials per head and step
    double meanTrials = 0.0;     // contact trials per head and step
};

// One second of audio after a fortissimo strike (the mallet, then the snares chattering).
Run timeDrum(const DrumConfig& cfg, double seconds)
{
    Drum drum(cfg);
    drum.playNote(38, 127);
    const int steps = (int) (seconds * cfg.sampleRate_Hz);
    double sink = 0.0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
        sink += drum.step();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (sink == 12345.0)
        std::printf(" ");
    const auto& st = drum.solverStats();
    return { s / seconds, st.maxAirTrials, (double) st.airTrials / (2.0 * steps) };
}

// The drum in its box, unstruck (the air, the heads, the embeddings: one trial per head, no force).
double timeQuiet(const DrumConfig& cfg, double seconds)
{
    Drum drum(cfg);
    const int steps = (int) (seconds * cfg.sampleRate_Hz);
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
        drum.step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / seconds;
}

// The air's own update alone (eq. 25), on the same grid with the same links cut (shell and heads).
double timeAir(const DrumConfig& cfg, double seconds)
{
    const double k = 1.0 / cfg.sampleRate_Hz, H = cfg.cavity.shellDepth_m;
    AirBox air(cfg.airBoxSpec(), k);
    air.setThreads(cfg.air.threads);
    Membrane batter(cfg.batter, k), carry(cfg.carry, k);
    const HeadEmbedding top(air, batter, 0.5 * H), bottom(air, carry, -0.5 * H); // cut the heads' links
    air.setPotential([](double x, double y, double z) { return 1e-3 * (x + 0.5 * y - z); });
    const int steps = (int) (seconds * cfg.sampleRate_Hz);
    const auto t0 = std::chrono::steady_clock::now();
    for (int n = 0; n < steps; ++n)
    {
        air.computeNext();
        air.advance();
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / seconds;
}
} // namespace

int main()
{
    DrumConfig cfg; // the schema's default drum (20 wires, quadratised solve, Quality 2)
    cfg.sampleRate_Hz = 44100.0;
    const double seconds = 1.0;

    DrumConfig cavity = cfg;
    cavity.cavity.model = AirModel::cavity;
    std::printf("whole default drum, 44.1 kHz, %.1f s after a fortissimo strike; seconds of compute per second of audio:\n",
                seconds);
    std::printf("  cavity model:                 %.3f\n", timeDrum(cavity, seconds).perAudioSecond);

    for (int threads : { 1, 2 })
    {
        DrumConfig box = cfg;
        box.cavity.model = AirModel::airbox;
        box.air.threads = threads;
        Drum probe(box);
        const auto& air = probe.airBox().air();
        const Run struck = timeDrum(box, seconds);
        const double quiet = timeQuiet(box, seconds), alone = timeAir(box, seconds);
        std::printf("  air box %.2f m, h_a %.2f mm, %ld points, %d thread%s: %.3f struck (contact trials per head and step: "
                    "mean %.3f, most %d); %.3f unstruck (air, heads, embeddings); %.3f the air's own update alone\n",
                    cfg.air.size_m[0], 1e3 * air.spacing(), air.numPoints(), threads, threads > 1 ? "s" : "", struck.perAudioSecond,
                    struck.meanTrials, struck.maxTrials, quiet, alone);
        DrumConfig newton = box;
        newton.snares.scheme = CollisionScheme::newton;
        const Run n = timeDrum(newton, seconds);
        std::printf("      the same with the Newton snare solve: %.3f struck (trials mean %.3f, most %d)\n", n.perAudioSecond, n.meanTrials,
                    n.maxTrials);
    }
    return 0;
}
