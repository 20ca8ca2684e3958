#!/usr/bin/env bash
# Builds the engine (Source/Physics, Model and Player: Eigen and the standard library, no JUCE) with a
# cross compiler, links PlayStrike.cpp against it, and runs that under EMULATOR when one is
# given (qemu-user): the engine builds and plays on another architecture.
#
#   build_engine.sh CXX SOURCE_DIR PRESET_DATA_DIR [EMULATOR]
#
# PRESET_DATA_DIR: the factory presets as generated C++ (the native build's
# juce_binarydata_snaresim_preset_files/JuceLibraryCode: plain data, no JUCE).
set -euo pipefail
[ $# -ge 3 ] || { echo "usage: build_engine.sh CXX SOURCE_DIR PRESET_DATA_DIR [EMULATOR]" >&2; exit 2; }
cxx=$1 src=$2 presets=$3 emulator=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

flags=(-std=c++20 -O2 -DNDEBUG -Wall -Wextra -fno-math-errno -fno-trapping-math -fopenmp-simd
       -I"$src/Source/Physics" -I"$src/Source/Model" -I"$src/Source/Player" -I"$presets" -I/usr/include/eigen3)
count=0
for f in "$src"/Source/{Physics,Model,Player}/*.cpp "$presets"/BinaryData*.cpp; do
    "$cxx" "${flags[@]}" -c "$f" -o "$work/$(basename "$f" .cpp).o"
    count=$((count + 1))
done
"$cxx" "${flags[@]}" -static "$src/Tests/Cross/PlayStrike.cpp" "$work"/*.o -o "$work/play_strike" -lpthread
echo "$count sources compiled and linked with $cxx"
file_type=$(file -b "$work/play_strike" 2>/dev/null || true)
[ -n "$file_type" ] && echo "play_strike: $file_type"
if [ -n "$emulator" ]; then
    "$emulator" "$work/play_strike"
fi
