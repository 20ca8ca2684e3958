#!/usr/bin/env bash
# Runs a third-party plug-in validator on the built VST3, for ctest:
#   validate.sh pluginval      TOOLS_DIR BUNDLE   # pluginval, strictness 10, editor tests on a virtual display
#   validate.sh vst3-validator TOOLS_DIR BUNDLE   # Steinberg's validator, extensive mode (-e)
# The validators are not Debian packages: when TOOLS_DIR has no such tool the test says so in
# one line and exits 77, which ctest reports as skipped (SKIP_RETURN_CODE).
set -uo pipefail

tool=$1 tools_dir=$2 bundle=$3
exe="$tools_dir/$tool"

if [ ! -x "$exe" ]; then
    echo "skipped: $tool not found at $exe (see docs/TESTING.md, The plug-in)"
    exit 77
fi
[ -d "$bundle" ] || { echo "error: no plug-in bundle at $bundle" >&2; exit 1; }
# The VST3 validator finds the binary from the bundle's own name: no trailing "/..".
bundle=$(cd "$bundle" && pwd -P)

case "$tool" in
    pluginval)
        command -v xvfb-run >/dev/null || { echo "error: xvfb-run is needed for the editor tests (Debian: xvfb)" >&2; exit 1; }
        # pluginval keeps settings and logs under HOME: a private one per run.
        export HOME
        HOME=$(mktemp -d)
        trap 'rm -rf "$HOME"' EXIT
        xvfb-run -a "$exe" --strictness-level 10 --timeout-ms 300000 --validate "$bundle"
        ;;
    vst3-validator)
        "$exe" -e "$bundle"
        ;;
    *)
        echo "error: unknown validator $tool" >&2
        exit 2
        ;;
esac
