// Compute time of the whole drum inside the air box (AirModel::airbox) at 44.1 kHz: seconds of
// compute per second of audio, beside the same drum with the cavity, on one thread and on every
// core, and the air's own update against a bare 7-point stencil on the drum's grid, measured in
// the same run (AirSpeed.h). Prints figures; nothing about time can fail.
//   cmake --build build --target drumair_bench && ./build/Tests/Engine/drumair_bench

#include "AirSpeed.h"
#include "CavityModes.h"
#include "Drum.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

using namespace snaresim;

namespace
{
struct Run
{
    double perAudioSecond = 0.0; // compute seconds per audio second
    int maxTrials = 0;           // most contact trials per head and step
    double meanTrials = 0.0;     // contact trials per head and step
};

// `seconds` of audio after a fortissimo strike (the mallet, then the snares chattering), or of
// the drum at rest (the air, both heads and both embeddings; one contact trial per head and step).
Run timeDrum(const DrumConfig& cfg, double seconds, bool struck)
{
    Drum drum(cfg);
    if (struck)
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
} // namespace

int cavityModes()
{
    std::printf("the default drum with the outside air, 48 kHz, 2 s after a fortissimo strike; seconds of compute per second of audio:\n");
    for (int round = 0; round < 2; ++round)
        for (const double upTo : { 0.0, 1000.0, 2000.0, 4000.0 })
        {
            DrumConfig cfg;
            cfg.sampleRate_Hz = 48000.0;
            cfg.outside.enabled = cfg.outside.nearField = true;
            cfg.cavity.modesUpTo_Hz = upTo;
            const double s = timeDrum(cfg, 2.0, true).perAudioSecond;
            std::printf("  cavity modes to %4.0f Hz (%3d modes): %.3f (%.2fx real time)\n", upTo,
                        (int) CavityModes::below(cfg.cavity, upTo, cfg.batter.radius_m).size(), s, 1.0 / s);
        }
    return 0;
}

int main(int argc, char** argv)
{
    if (argc > 1 && std::string(argv[1]) == "cavity-modes")
        return cavityModes();
    if (argc > 1)
    {
        std::fprintf(stderr, "usage: drumair_bench [cavity-modes]\n");
        return 2;
    }
    DrumConfig cfg; // the schema's default drum (20 wires, quadratised solve, Quality 2)
    cfg.sampleRate_Hz = 44100.0;
    const double seconds = 1.0;
    const int cores = (int) std::max(2u, std::thread::hardware_concurrency());

    DrumConfig cavity = cfg;
    cavity.cavity.model = AirModel::cavity;
    std::printf("whole default drum, 44.1 kHz, %.1f s after a fortissimo strike; seconds of compute per second of audio:\n", seconds);
    std::printf("  cavity model:                 %.3f\n", timeDrum(cavity, seconds, true).perAudioSecond);

    DrumConfig box = cfg;
    box.cavity.model = AirModel::airbox;
    {
        AirBox air(box.airBoxSpec(), 1.0 / cfg.sampleRate_Hz);
        const AirSpeed a = measureAirSpeed(air, cores);
        std::printf("  the drum's air box %.2f m, h_a %.2f mm, %ld points: bare 7-point stencil %.3g updates/s (double; float %.3g); "
                    "air update %.3g updates/s on 1 thread (%.3f of the bare), %.3g on %d threads (%.3f)\n",
                    cfg.airBox.size_m[0], 1e3 * a.spacing_m, a.points, a.bareRate(), a.bareFloatRate(), a.airRate(),
                    a.airRate() / a.bareRate(), a.airThreadsRate(), a.threads, a.airThreadsRate() / a.bareRate());
    }
    for (int threads : { 1, cores })
    {
        box.airBox.threads = threads;
        const Run struck = timeDrum(box, seconds, true);
        const double quiet = timeDrum(box, seconds, false).perAudioSecond;
        std::printf("  air box, %d thread%s: %.3f struck (contact trials per head and step: mean %.3f, most %d); %.3f unstruck (air, "
                    "heads, embeddings)\n",
                    threads, threads > 1 ? "s" : "", struck.perAudioSecond, struck.meanTrials, struck.maxTrials, quiet);
        DrumConfig newton = box;
        newton.snares.scheme = CollisionScheme::newton;
        const Run n = timeDrum(newton, seconds, true);
        std::printf("      the same with the Newton snare solve: %.3f struck (trials mean %.3f, most %d)\n", n.perAudioSecond, n.meanTrials,
                    n.maxTrials);
    }
    return 0;
}
