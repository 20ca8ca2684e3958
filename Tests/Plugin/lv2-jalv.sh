#!/usr/bin/env bash
# Plays the built LV2 in a real LV2 host: Debian's jalv on a JACK server with the dummy driver
# (no sound card), MIDI notes in from jack_midiseq, the audio out recorded by jack_rec, then
# checked: the strikes are heard (4 to 8 onsets in 3 s of notes every 0.5 s: the recording's
# start is not aligned with the sequence), both channels alike, under a thousandth of the
# samples at full scale.
#   lv2-jalv.sh BUNDLE_PARENT_DIR PLUGIN_URI WORK_DIR
# Exits 77 (ctest: skipped) when jalv, jackd or python3 is not installed.
set -uo pipefail

lv2_dir=$1 uri=$2 work=$3
lv2_dir=$(cd "$lv2_dir" && pwd -P) || exit 1   # LV2_PATH must be absolute
for tool in jackd jalv jack_midiseq jack_rec jack_connect jack_lsp jack_wait python3; do
    command -v "$tool" >/dev/null || { echo "skipped: $tool is not installed (Debian: jalv, jackd2, python3)"; exit 77; }
done

mkdir -p "$work"
rm -f "$work/jalv.wav"
export JACK_DEFAULT_SERVER="snaresim-test-$$"
export JACK_NO_AUDIO_RESERVATION=1
pids=()
# Stops the clients before their server (a client whose server is gone can wait on it for
# long), each given 5 s to end before it is killed.
stop() {
    kill "$1" 2>/dev/null || return 0
    for _ in $(seq 50); do kill -0 "$1" 2>/dev/null || return 0; sleep 0.1; done
    kill -KILL "$1" 2>/dev/null
}
cleanup() {
    exec 3>&-
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do stop "${pids[i]}"; done
    wait 2>/dev/null
}
trap cleanup EXIT

# A JACK server that was killed leaves its shared memory behind, and after a few of them jackd
# refuses to start ("Too many servers already active"). With no JACK server running, clear it.
if ! pgrep -x jackd >/dev/null && ! pgrep -x jackdbus >/dev/null; then
    rm -f /dev/shm/jack-shm-registry /dev/shm/jack_sem.* /dev/shm/jack_db-* /dev/shm/jack-[0-9]* 2>/dev/null || true
fi

jackd --no-realtime -d dummy -r 48000 -p 256 >"$work/jackd.log" 2>&1 &
pids+=($!)
jack_wait -w -t 10 >/dev/null 2>&1 || { echo "error: the JACK server did not start"; cat "$work/jackd.log"; exit 1; }

# jalv runs until its standard input closes: a FIFO this script holds open.
rm -f "$work/jalv.in"
mkfifo "$work/jalv.in"
LV2_PATH="$lv2_dir" jalv -n snaresim "$uri" <"$work/jalv.in" >"$work/jalv.log" 2>&1 &
pids+=($!)
exec 3>"$work/jalv.in"

wait_for_port() {
    for _ in $(seq 100); do
        jack_lsp 2>/dev/null | grep -qx "$1" && return 0
        sleep 0.1
    done
    echo "error: no JACK port $1"; cat "$work/jalv.log"; exit 1
}
wait_for_port snaresim:in
wait_for_port snaresim:audio_out_1

# Note 38 (centre strike, velocity 64) every half second.
jack_midiseq seq 24000 0 38 2000 >"$work/midiseq.log" 2>&1 &
pids+=($!)
wait_for_port seq:out
jack_connect seq:out snaresim:in || exit 1

# A ring buffer that holds the whole recording: a full one drops part of a frame and shifts one
# channel against the other, which the check below would take for the plug-in's fault.
jack_rec -f "$work/jalv.wav" -d 3 -b 16 -B 262144 snaresim:audio_out_1 snaresim:audio_out_2 >"$work/rec.log" 2>&1 || {
    echo "error: jack_rec failed"; cat "$work/rec.log"; exit 1; }

python3 - "$work/jalv.wav" <<'PY'
import array, sys, wave
with wave.open(sys.argv[1]) as w:
    rate, channels, width, frames = w.getframerate(), w.getnchannels(), w.getsampwidth(), w.getnframes()
    data = array.array('h', w.readframes(frames))
assert width == 2 and channels == 2, (width, channels)
left, right = data[0::2], data[1::2]
peak = max(abs(s) for s in left) / 32768.0
window = rate // 50                       # 20 ms
levels = [max(abs(s) for s in left[i:i + window]) / 32768.0 for i in range(0, len(left) - window, window)]
onsets = sum(1 for a, b in zip(levels, levels[1:]) if b > 4 * a and b > 0.02 * peak and b > 1e-3)
clipped = sum(1 for s in left if abs(s) >= 32767) / len(left)
print(f"jalv: {frames} frames at {rate} Hz recorded, peak {peak:.3f} of full scale, "
      f"{onsets} strikes found (notes every 0.5 s), channels identical: {left == right}, clipped share {clipped:.4f}")
ok = frames >= 2 * rate and peak > 1e-3 and 4 <= onsets <= 8 and left == right and clipped < 0.001
sys.exit(0 if ok else 1)
PY
status=$?
[ "$status" -eq 0 ] || cat "$work/rec.log"
exit "$status"
