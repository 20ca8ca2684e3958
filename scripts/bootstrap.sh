#!/usr/bin/env bash
# Sets up a Debian 12 machine, builds SnareSim and either renders a demo strike or runs the tests.
#
#   bash scripts/bootstrap.sh demo      # build, then render out/demo.wav (prints its absolute path)
#   bash scripts/bootstrap.sh test      # build everything, run the short benchmark (prints its JSON
#                                       # line; never fails on time), then the whole test suite (ctest,
#                                       # a test per core at a time)
#   bash scripts/bootstrap.sh sanitize  # a second build of the tests with clang, AddressSanitizer
#                                       # and UBSan in build-asan/, then the suite there but the
#                                       # tests labelled slow (the corner test does run)
#   bash scripts/bootstrap.sh fuzz      # the libFuzzer targets of that build, FUZZ_SECONDS (30) each
#
# Safe to rerun: packages are installed only when missing, and the build in build/ only redoes
# what changed.
set -euo pipefail

usage() {
    echo "usage: bash scripts/bootstrap.sh demo|test|sanitize|fuzz" >&2
    exit 2
}

[ $# -eq 1 ] || usage
mode=$1
case "$mode" in
    demo|test|sanitize|fuzz) ;;
    *) usage ;;
esac

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$repo"
build_dir="$repo/build"
jobs=$(nproc 2>/dev/null || echo 2)

log() { printf '==> %s\n' "$*" >&2; }

# --- 1. Debian packages ---------------------------------------------------------------------------
packages=(
    build-essential         # C/C++ compiler, make
    cmake
    pkg-config              # JUCE finds ALSA, freetype, libpng, libjpeg with it
    juce-modules-source     # JUCE 7 modules + CMake support (pulls in the X11/ALSA/freetype -dev packages)
    libeigen3-dev
    libcli11-dev            # the renderer's command line (header-only)
    libflac-dev             # the renderer reads FLAC recordings (--match)
    catch2
    lv2-dev
    libjack-jackd2-dev      # JACK support in the standalone application
    xvfb xauth              # a virtual display for the editor tests (xvfb-run)
    jalv jackd2             # a real LV2 host on a dummy JACK server, for the LV2 test
    python3                 # the LV2 test's recording check, scripts/band_share.py
)
case "$mode" in
    sanitize|fuzz) packages+=(clang libclang-rt-14-dev) ;;  # the sanitizers' and libFuzzer's runtimes
esac
case "$mode" in
    # the suite's test of scripts/snare_features.py (numpy, scipy; soundfile reads FLAC)
    test|sanitize) packages+=(python3-numpy python3-scipy python3-soundfile) ;;
esac
case "$mode" in
    # recorded snare drums: the suite holds the factory presets against them; the engine built
    # for arm64 (a cross compiler) and a strike played there (qemu-user)
    test) packages+=(hydrogen-drumkits g++-aarch64-linux-gnu qemu-user file) ;;
esac

missing=()
for pkg in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}\n' "$pkg" 2>/dev/null | grep -q '^install ok installed$'; then
        missing+=("$pkg")
    fi
done

if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -eq 0 ]; then
        as_root=()
    elif command -v sudo >/dev/null 2>&1; then
        as_root=(sudo)
    else
        echo "error: missing packages (${missing[*]}) and not root, and sudo is not available." >&2
        echo "       Install them as root:  apt-get install ${missing[*]}" >&2
        exit 1
    fi
    log "installing: ${missing[*]}"
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
    "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y --no-install-recommends "${missing[@]}"
fi

# --- 2. Configure ---------------------------------------------------------------------------------
if [ "$mode" = sanitize ] || [ "$mode" = fuzz ]; then
    # Everything again with clang, the sanitizers and libFuzzer's coverage (JUCE compiled once
    # more, for this build).
    build_dir="$repo/build-asan"
    log "configuring $build_dir (clang, AddressSanitizer, UndefinedBehaviorSanitizer, libFuzzer)"
    # Line tables only: readable sanitizer reports at half the compile time of -g.
    CC=clang CXX=clang++ cmake -S "$repo" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
        -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
        -DSNARESIM_FUZZ=ON >/dev/null
else
    log "configuring $build_dir"
    cmake -S "$repo" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON >/dev/null
fi

# A sanitizer error fails the test that hit it. Leaks are reported at exit.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$repo/Tests/Fuzz/lsan.supp}"

# --- 3. Build and run -----------------------------------------------------------------------------
case "$mode" in
    demo)
        log "building snaresim-render"
        cmake --build "$build_dir" --target snaresim-render -j "$jobs"

        renderer="$build_dir/Source/Renderer/snaresim-render"
        if [ ! -x "$renderer" ]; then
            renderer=$(find "$build_dir" -type f -name snaresim-render -perm -u+x -print -quit)
        fi
        [ -n "$renderer" ] && [ -x "$renderer" ] || { echo "error: snaresim-render was not built" >&2; exit 1; }

        mkdir -p "$repo/out"
        log "rendering a demo strike"
        "$renderer" -o "$repo/out/demo.wav" --hit 0:100 --seconds 2
        echo "$repo/out/demo.wav"
        ;;
    test)
        log "building everything"
        cmake --build "$build_dir" -j "$jobs"
        # The short benchmark, so that it cannot rot: 0.25 s of audio, its JSON line on stdout.
        # It fails only on a crash or non-finite output, never on a time (see BENCHMARKS.md).
        log "running the short benchmark (timings are informative only)"
        renderer="$build_dir/Source/Renderer/snaresim-render"
        if [ ! -x "$renderer" ]; then
            renderer=$(find "$build_dir" -type f -name snaresim-render -perm -u+x -print -quit)
        fi
        "$renderer" --bench --bench-short --json

        log "running the tests"
        # As many at a time as there are cores: every test works in its own folder; the hosts,
        # the validators and jalv's JACK server run alone (RUN_SERIAL).
        ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
        ;;
    sanitize)
        # What the tests below run: the test programs, the renderer they call and the fuzzers
        # (their seed corpora are tests). Not the plug-in's formats, the programs that host them,
        # the golden tests or the lab: those run in the release suite only.
        targets=(engine_tests renderer_tests command_line_tests match_tests host_rate_tests
                 strike_distance_tests snaresim_plugin_tests
                 snaresim_editor_screenshot snaresim-render
                 fuzz_state fuzz_midi_input fuzz_command_line fuzz_midi_file)
        log "building the tests with the sanitizers"
        cmake --build "$build_dir" --target "${targets[@]}" -j "$jobs"
        log "running the tests under AddressSanitizer and UndefinedBehaviorSanitizer"
        # Two at a time: the instrumented physics is slow, and every test works in its own folder.
        # The tests labelled slow (long renders and mode fits that repeat the code paths of
        # shorter tests) run in the release suite only; the corner test does run here, on every
        # core, with rolls of 0.13 s, three strikes, and 50 random combinations (0.5 s and 120 in
        # the release suite; it prints what it used).
        ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" -LE slow
        SNARESIM_CORNER_SECONDS="${SNARESIM_CORNER_SECONDS:-0.13}" \
            SNARESIM_CORNER_COMBINATIONS="${SNARESIM_CORNER_COMBINATIONS:-50}" \
            ctest --test-dir "$build_dir" --output-on-failure -R "parameter at its limits"
        ;;
    fuzz)
        log "building the fuzzers"
        targets=(fuzz_state fuzz_midi_input fuzz_command_line fuzz_midi_file)
        cmake --build "$build_dir" --target "${targets[@]}" -j "$jobs"
        seconds=${FUZZ_SECONDS:-30}
        status=0
        for target in "${targets[@]}"; do
            name=${target#fuzz_}
            work="$build_dir/fuzz-runs/$name"
            rm -rf "$work"
            mkdir -p "$work/corpus"
            cp "$repo/Tests/Fuzz/corpus/$name/." "$work/corpus/" -r
            log "fuzzing $name for $seconds s (corpus copy and findings in $work)"
            if ! (cd "$work" && "$build_dir/Tests/Fuzz/$target" -max_total_time="$seconds" -timeout=20 \
                    -rss_limit_mb=4096 -print_final_stats=1 corpus >"$work/log.txt" 2>&1); then
                echo "FUZZER FOUND A CRASH in $name: reproducer(s) in $work (crash-*, timeout-*, oom-*)" >&2
                tail -n 60 "$work/log.txt" >&2
                status=1
            fi
            grep -E "^(stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb)|cov: " "$work/log.txt" \
                | tail -n 4
        done
        exit "$status"
        ;;
esac
