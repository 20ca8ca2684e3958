// snaresim-render --set-at: a parameter changed during the render as a host's automation changes
// it, through the same session as the plug-in (smoothed, or a new drum crossfaded in), and the
// bad input it gets.

#include "RendererTestSupport.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

using namespace rendertest;

namespace
{

constexpr int kRate = 48000;
// The changes below come at 0.1 s; the interpolation to 48 kHz reaches 2 ms (96 samples) each
// side of a simulated sample (HostRateInterpolator.h), and the renderer takes its lag off.
constexpr double kBeforeChange_s = 0.1 - 0.002;

std::vector<float> render(const TempDir& dir, const std::string& name, const std::vector<std::string>& more)
{
    const auto wav = dir.out() / name;
    std::vector<std::string> args { "-o", wav.string(), "--seconds", "0.3", "--set", "bandwidth=7839.5127" };
    args.insert(args.end(), more.begin(), more.end());
    const auto run = runRenderer(args, dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto data = readWav(wav);
    REQUIRE(data.opened);
    REQUIRE(data.length == (long long) (0.3 * kRate));
    for (const float x : data.samples)
        REQUIRE(std::isfinite(x));
    return data.samples;
}

std::vector<float> slice(const std::vector<float>& x, double from_s, double to_s)
{
    return { x.begin() + (long) std::lround(from_s * kRate), x.begin() + (long) std::lround(to_s * kRate) };
}

double rms(const std::vector<float>& x)
{
    double sum = 0.0;
    for (const float v : x)
        sum += (double) v * v;
    return x.empty() ? 0.0 : std::sqrt(sum / (double) x.size());
}

} // namespace

TEST_CASE("set-at: a parameter changes from its sample on, smoothed as the plug-in smooths it", "[renderer][automation]")
{
    TempDir dir;
    const auto plain = render(dir, "plain.wav", { "--hit", "0:100" });
    const auto changed = render(dir, "changed.wav", { "--hit", "0:100", "--set-at", "0.1:batter_tension=5500" });

    // Before the change the two renders are the same to the bit (but for the 2 ms before it: the
    // drum's lag is taken off, and the interpolation reaches that far on either side of a
    // simulated sample); after it they part.
    CHECK(slice(plain, 0.0, kBeforeChange_s) == slice(changed, 0.0, kBeforeChange_s));
    const auto after = slice(plain, 0.15, 0.3), afterChanged = slice(changed, 0.15, 0.3);
    CHECK(rmsDifference(after, afterChanged) > 0.1 * rms(after));

    // Smoothed over 30 ms: in the first millisecond the tension has moved by a thirtieth of the way, so the
    // renders still differ far less than they do once it has arrived.
    const double early = rmsDifference(slice(plain, 0.1, 0.101), slice(changed, 0.1, 0.101));
    const double late = rmsDifference(slice(plain, 0.2, 0.201), slice(changed, 0.2, 0.201));
    CHECK(early < 0.1 * late);

    // Two changes in command-line order: the later one at the same time wins.
    const auto twice =
        render(dir, "twice.wav", { "--hit", "0:100", "--set-at", "0.1:batter_tension=1500", "--set-at", "0.1:batter_tension=5500" });
    CHECK(twice == changed);
}

TEST_CASE("set-at: a parameter that needs a new drum builds it at its sample and crossfades it in", "[renderer][automation]")
{
    TempDir dir;
    const auto plain = render(dir, "plain.wav", { "--hit", "0:100", "--hit", "0.2:100" });
    const auto rebuilt = render(dir, "rebuilt.wav", { "--hit", "0:100", "--hit", "0.2:100", "--set-at", "0.1:snare_count=8" });

    CHECK(slice(plain, 0.0, kBeforeChange_s) == slice(rebuilt, 0.0, kBeforeChange_s));
    // The ringing drum fades out over 20 ms and the new one starts at rest, as in the plug-in:
    // quiet from then until the next strike (and the interpolation's 2 ms before it).
    CHECK(rms(slice(rebuilt, 0.13, 0.198)) < 1e-3 * rms(slice(plain, 0.13, 0.198)));
    // The new drum, with its 8 wires, plays the next strike.
    const auto second = slice(rebuilt, 0.2, 0.3);
    CHECK(rms(second) > 0.1 * rms(slice(plain, 0.2, 0.3)));
    CHECK(rmsDifference(second, slice(plain, 0.2, 0.3)) > 0.05 * rms(second));
}

TEST_CASE("set-at: --bench plays the changes as the plug-in would", "[renderer][automation][bench]")
{
    TempDir dir;
    const auto run = runRenderer({ "--bench", "--bench-short", "--json", "--set", "bandwidth=5000", "--set-at", "0.1:snares_engaged=off",
                                   "--set-at", "0.15:snare_count=6" },
                                 dir.root() / "capture");
    INFO("stderr: " << run.err);
    REQUIRE(run.exitCode == 0);
    const auto report = parseJson(run.out);
    CHECK((double) report["nonfinite_samples"] == 0.0);
}

TEST_CASE("bad input: --set-at", "[renderer][errors][automation]")
{
    TempDir dir;
    const auto out = (dir.out() / "out.wav").string();
    // Each value of --set-at, and what the one-line error must name. Out of range and
    // unbuildable values are refused before anything is written.
    const std::pair<const char*, const char*> cases[] = {
        { "0.1", "--set-at" },
        { "x:snare_count=3", "--set-at time" },
        { "-1:snare_count=3", "--set-at" },
        { "0.1:nope=3", "nope" },
        { "0.1:snare_count=2.5", "snare_count" },
        { "0.1:snare_count=1000", "--set-at 0.1:snare_count=1000" },
        { "0.1:snares_engaged=maybe", "maybe" },
        { "0.1:shell_depth=1 mm", "--set-at 0.1:shell_depth=1 mm" },
    };
    for (const auto& [value, mentions] : cases)
        requireRejected(dir, { "-o", out, "--hit", "0:100", "--seconds", "0.2", "--set-at", value }, mentions);
}
